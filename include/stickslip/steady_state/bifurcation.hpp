#pragma once
/// \file bifurcation.hpp
/// \brief Bifurcations along a branch of forced periodic orbits: which Floquet multiplier crossed
/// the unit circle between two points (through +1: a fold, or a pitchfork where the branch does
/// not turn; through -1: a period doubling; a complex pair: Neimark-Sacker), the flip located
/// to a tolerance, and the branch of period-2T orbits born there.

#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/shooting.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace stickslip {

/// What happened between two points of a branch where the multipliers outside the unit circle
/// changed.
enum class BifurcationKind : std::uint8_t {
  /// A real multiplier through +1 where the branch turns back in the parameter (a fold: the
  /// parameter steps on either side of the crossing have opposite signs).
  Fold,
  /// A real multiplier through +1 where the branch goes on in the same parameter direction: a
  /// branch point (a symmetry-breaking pitchfork; or transcritical), where another branch of
  /// orbits of the same period crosses this one.
  Pitchfork,
  /// A real multiplier through -1 (a flip): a branch of period-2T orbits is born.
  PeriodDoubling,
  /// A complex pair through the unit circle: a torus (quasi-periodic response) is born.
  NeimarkSacker
};

/// Human-readable name of a bifurcation kind.
inline const char* to_string(BifurcationKind k) noexcept {
  switch (k) {
    case BifurcationKind::Fold: return "fold";
    case BifurcationKind::Pitchfork: return "pitchfork";
    case BifurcationKind::PeriodDoubling: return "period_doubling";
    case BifurcationKind::NeimarkSacker: return "neimark_sacker";
  }
  return "unknown";
}

/// A bifurcation between points `before` and `before + 1` of a branch.
template <class Scalar>
struct BifurcationPoint {
  BifurcationKind kind = BifurcationKind::Fold;  ///< which multiplier crossed, and how
  std::size_t before = 0;  ///< index of the point before the crossing (the next one is after it)
  /// The parameter where the crossing multiplier's modulus, interpolated linearly between the
  /// two points, is 1.
  Scalar parameter = 0;
  /// true: a multiplier left the unit circle (one more outside at the second point); false: it
  /// came back in.
  bool destabilising = true;
};

namespace detail {
// Multipliers outside the unit circle by kind: real > 0, real < 0, complex (each of a pair).
struct MultiplierCounts {
  int plus = 0, minus = 0, complex = 0;
  int total() const { return plus + minus + complex; }
};
template <class Vec, class Scalar>
MultiplierCounts count_outside(const Vec& mu, Scalar tol) {
  MultiplierCounts c;
  for (Eigen::Index i = 0; i < mu.size(); ++i) {
    using std::abs;
    if (!(abs(mu[i]) > Scalar(1) + tol)) continue;
    if (abs(mu[i].imag()) > tol * abs(mu[i]))
      ++c.complex;
    else if (mu[i].real() > 0)
      ++c.plus;
    else
      ++c.minus;
  }
  return c;
}
// |mu| of the multiplier of that kind nearest the unit circle (kind: 1 real > 0, -1 real < 0,
// 0 complex); NaN when there is none.
template <class Vec, class Scalar>
Scalar nearest_modulus(const Vec& mu, int kind, Scalar tol) {
  using std::abs;
  Scalar best = std::numeric_limits<Scalar>::quiet_NaN(), dist = std::numeric_limits<Scalar>::infinity();
  for (Eigen::Index i = 0; i < mu.size(); ++i) {
    const bool cplx = abs(mu[i].imag()) > tol * abs(mu[i]);
    const int k = cplx ? 0 : (mu[i].real() > 0 ? 1 : -1);
    if (k != kind) continue;
    const Scalar d = abs(abs(mu[i]) - Scalar(1));
    if (d < dist) {
      dist = d;
      best = abs(mu[i]);
    }
  }
  return best;
}
}  // namespace detail

/// The bifurcations along `points` (ContinuationPoint-like: .parameter, .orbit.floquet): between
/// consecutive points whose numbers of multipliers outside the unit circle (|mu| > 1 + tol)
/// differ, the kind whose count changed the way the total did. A crossing through +1 is a Fold
/// when the parameter steps around it (from the point before to the point after the two) change
/// sign, a Pitchfork when they keep one sign (at least two steps known; with one, a Fold).
/// `tol` also separates real from complex multipliers (|Im mu| > tol |mu|).
template <class Point, class Scalar = typename Point::Scalar>
std::vector<BifurcationPoint<Scalar>> locate_bifurcations(const std::vector<Point>& points,
                                                          Scalar tol = Scalar(1e-6)) {
  std::vector<BifurcationPoint<Scalar>> out;
  for (std::size_t a = 0; a + 1 < points.size(); ++a) {
    const auto& ma = points[a].orbit.floquet.multipliers;
    const auto& mb = points[a + 1].orbit.floquet.multipliers;
    if (ma.size() == 0 || ma.size() != mb.size()) continue;
    const auto ca = detail::count_outside(ma, tol), cb = detail::count_outside(mb, tol);
    const int d = cb.total() - ca.total();
    if (d == 0) continue;
    const int changes[3] = {cb.plus - ca.plus, cb.minus - ca.minus, cb.complex - ca.complex};
    const int kinds[3] = {1, -1, 0};
    for (int j = 0; j < 3; ++j) {
      if (changes[j] == 0 || (changes[j] > 0) != (d > 0)) continue;
      BifurcationPoint<Scalar> b;
      b.before = a;
      b.destabilising = d > 0;
      const Scalar pa = points[a].parameter, pb = points[a + 1].parameter;
      const Scalar ra = detail::nearest_modulus(ma, kinds[j], tol) - Scalar(1);
      const Scalar rb = detail::nearest_modulus(mb, kinds[j], tol) - Scalar(1);
      b.parameter = (detail::is_finite(ra) && detail::is_finite(rb) && ra != rb)
                        ? pa + (pb - pa) * std::clamp(ra / (ra - rb), Scalar(0), Scalar(1))
                        : (pa + pb) / 2;
      if (kinds[j] == -1) {
        b.kind = BifurcationKind::PeriodDoubling;
      } else if (kinds[j] == 0) {
        b.kind = BifurcationKind::NeimarkSacker;
      } else {
        // The parameter steps around the crossing: a - 1 -> a, a -> a + 1, a + 1 -> a + 2.
        std::vector<Scalar> steps;
        if (a >= 1) steps.push_back(pa - points[a - 1].parameter);
        steps.push_back(pb - pa);
        if (a + 2 < points.size()) steps.push_back(points[a + 2].parameter - pb);
        bool turns = steps.size() < 2;
        for (std::size_t i = 1; i < steps.size(); ++i)
          if (!(steps[i] * steps[0] > 0)) turns = true;
        b.kind = turns ? BifurcationKind::Fold : BifurcationKind::Pitchfork;
      }
      out.push_back(b);
    }
  }
  return out;
}

}  // namespace stickslip
