#pragma once
/// \file period_doubling.hpp
/// \brief Branch switching at a period doubling (flip) of a branch of forced periodic orbits:
/// the flip located by a secant on the multiplier through -1, and the branch of period-2T
/// orbits born there, started along the multiplier's eigenvector and continued.

#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/bifurcation.hpp>
#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/detail/branch_start.hpp>
#include <stickslip/steady_state/period_run.hpp>
#include <stickslip/steady_state/shooting.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace stickslip {

/// A flip of a branch located to a tolerance (locate_flip).
template <class System>
struct FlipPoint {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  bool ok = false;       ///< located; otherwise `message` says why not
  std::string message;   ///< why the location failed
  Scalar parameter = 0;  ///< p at the flip
  Scalar multiplier = 0; ///< the real multiplier nearest -1 there (-1 to the tolerance)
  PeriodicOrbit<System> orbit;  ///< the period-T orbit at the flip
  /// Real eigenvector of the multiplier in the periodic components (max norm 1): the direction
  /// in which the period-2T orbits leave the period-T orbit.
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> eigenvector;
  /// The period-T branch's unit tangent in (x_P, p) at the flip (the secant of the two points).
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> tangent;
};

/// Branch switching at period doublings of the branches that Continuation follows (same system,
/// parameter map, period and options). The system is left at the parameter of the last orbit.
template <class System>
class PeriodDoubling {
 public:
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// The continuation whose branches are switched.
  using Cont = Continuation<System>;
  /// Dynamic vector type.
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Dynamic matrix type.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// Keeps a reference to `system`. Throws std::invalid_argument for empty callbacks or invalid
  /// options.
  PeriodDoubling(System& system, typename Cont::SetParameter set_parameter, typename Cont::PeriodOf period,
                 ShootingOptions<Scalar> shooting = {}, ContinuationOptions<Scalar> options = {})
      : sys_(system), set_(std::move(set_parameter)), period_(std::move(period)), shooting_(std::move(shooting)),
        opt_(options) {
    if (!set_) throw std::invalid_argument("PeriodDoubling: set_parameter must not be empty");
    if (!period_) throw std::invalid_argument("PeriodDoubling: period must not be empty");
    opt_.validate("PeriodDoubling");
  }

  /// The start-mode rule of the continued 2T branch (Continuation::start_mode).
  void start_mode(typename Cont::StartMode rule) { start_mode_ = std::move(rule); }

  /// The flip between points `a` and `b` of a period-T branch (a PeriodDoubling bifurcation of
  /// locate_bifurcations): the real multiplier mu nearest -1 is driven to |mu + 1| <= tolerance
  /// by a secant in p (Illinois: the bracket [a, b] kept), each orbit shot at fixed p from the
  /// bracket's nearer orbit. Not ok when the points' orbits lie on different sections t0, a
  /// shooting fails or the secant does not converge in 40 orbits.
  FlipPoint<System> locate_flip(const ContinuationPoint<System>& a, const ContinuationPoint<System>& b,
                                Scalar tolerance = Scalar(1e-8));

  /// The branch of period-2T orbits born at `flip`: the first orbit by Newton on
  /// x_P(t0 + 2 T(p)) - x_P = 0 with (x_P, p) at arclength `offset` from the flip along the
  /// eigenvector made orthogonal to the period-T branch's tangent, then Continuation of the
  /// 2T orbits (period 2 T(p)) away from the flip in p. StartFailed when that first orbit
  /// does not converge or is the period-T orbit (its half-period mismatch
  /// max |x_P(t0 + T) - x_P(t0)| below 100 Newton tolerances).
  ContinuationResult<System> period_doubled_branch(const FlipPoint<System>& flip, Scalar offset);

 private:
  // The real multiplier nearest -1 of an orbit and its real eigenvector (max norm 1).
  static Scalar flip_multiplier(const Matrix& M, Vector* v) {
    const Eigen::EigenSolver<Matrix> es(M, v != nullptr);
    Eigen::Index k = 0;
    Scalar best = std::numeric_limits<Scalar>::infinity();
    for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
      const Scalar d = std::abs(es.eigenvalues()[i] + std::complex<Scalar>(1, 0));
      if (d < best) {
        best = d;
        k = i;
      }
    }
    if (v) {
      *v = es.eigenvectors().col(k).real();
      const Scalar s = v->cwiseAbs().maxCoeff();
      if (s > 0) *v /= s;
    }
    return es.eigenvalues()[k].real();
  }

  System& sys_;
  typename Cont::SetParameter set_;
  typename Cont::PeriodOf period_;
  ShootingOptions<Scalar> shooting_;
  ContinuationOptions<Scalar> opt_;
  typename Cont::StartMode start_mode_;
};

template <class System>
FlipPoint<System> PeriodDoubling<System>::locate_flip(const ContinuationPoint<System>& a,
                                                      const ContinuationPoint<System>& b, Scalar tolerance) {
  FlipPoint<System> f;
  detail::require_positive("PeriodDoubling::locate_flip", "tolerance", tolerance);
  if (!(a.orbit.t0 == b.orbit.t0)) {
    f.message = "the two points lie on different sections t0 (the continuation moved it between them)";
    return f;
  }
  Shooting<System> shooting(sys_, shooting_);
  using End = detail::SecantEnd<System>;
  const End lo{a.parameter, flip_multiplier(a.orbit.monodromy, nullptr) + 1, a.orbit};
  const End hi{b.parameter, flip_multiplier(b.orbit.monodromy, nullptr) + 1, b.orbit};
  if (!(lo.g * hi.g <= 0)) {
    f.message = "no multiplier crosses -1 between the points (mu + 1 = " + detail::format_value(lo.g) + ", " +
                detail::format_value(hi.g) + ")";
    return f;
  }
  // The secant on g = mu + 1, each orbit shot at fixed p from the bracket's nearer orbit.
  const auto shoot = [&](Scalar p, const End& from, End& e, std::string& why) {
    set_(sys_, p);
    e.p = p;
    e.orbit = shooting.forced(from.orbit.mode, from.orbit.t0, from.orbit.x0, period_(p));
    if (!e.orbit.ok()) {
      why = "the orbit at p = " + detail::format_value(p) + " failed: " + e.orbit.message;
      return false;
    }
    e.g = flip_multiplier(e.orbit.monodromy, nullptr) + 1;
    return true;
  };
  End found;
  if (!detail::illinois_secant(lo, hi, shoot, [&](const End& e) { return std::abs(e.g) <= tolerance; }, found,
                               f.message))
    return f;
  f.ok = true;
  f.parameter = found.p;
  f.orbit = found.orbit;
  f.multiplier = flip_multiplier(found.orbit.monodromy, &f.eigenvector);
  f.tangent = detail::branch_secant(a, b, shooting_);
  return f;
}

template <class System>
ContinuationResult<System> PeriodDoubling<System>::period_doubled_branch(const FlipPoint<System>& flip,
                                                                          Scalar offset) {
  static const std::string where = "PeriodDoubling::period_doubled_branch";
  if (!flip.ok) throw std::invalid_argument(where + ": flip must be located (ok)");
  detail::require_positive(where, "offset", offset);
  ContinuationResult<System> result;
  result.status = ContinuationStatus::StartFailed;
  const State& xf = flip.orbit.x0;
  const auto P = shooting_.periodic_indices(xf.size());
  const auto np = static_cast<Eigen::Index>(P.size());
  // Direction: the eigenvector without its component along the period-T branch's tangent.
  Vector dir(np + 1);
  dir.head(np) = flip.eigenvector;
  dir[np] = 0;
  dir -= dir.dot(flip.tangent) * flip.tangent;
  if (!(dir.norm() > 0)) {
    result.message = "the eigenvector is along the period-T branch";
    return result;
  }
  dir.normalize();
  // Newton on (x_P(t0 + 2T(p)) - x_P, dir^T (y - y_f) - offset) = 0, y = (x_P, p).
  Shooting<System> shooting(sys_, shooting_);
  Scalar p = flip.parameter;
  std::string why;
  const PeriodicOrbit<System> orbit =
      detail::start_on_branch<System>(sys_, set_, period_, 2, shooting_, flip.orbit, flip.parameter, dir, offset, p, why);
  if (!orbit.ok()) {
    result.message = "the first 2T orbit: " + why;
    return result;
  }
  // Not the period-T orbit: its state after one forcing period differs from its start.
  set_(sys_, p);
  const PeriodRun<System> half = run_period(sys_, orbit.mode, orbit.t0, orbit.x0, period_(p), shooting_, false);
  Vector rh;
  if (!half.ok() || shooting.residual(half.x_end, orbit.x0, rh) <= 100 * shooting.tolerance_at(orbit.x0)) {
    result.message = "the first 2T orbit at p = " + detail::format_value(p) +
                     " is the period-T orbit (raise the offset)";
    return result;
  }
  const auto period = period_;
  return detail::continue_new_branch<System>(sys_, set_, [period](Scalar q) { return 2 * period(q); }, shooting_, opt_,
                                             start_mode_, orbit, p, flip.parameter, "2T orbit");
}

}  // namespace stickslip
