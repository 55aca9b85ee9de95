#pragma once
/// \file period_doubling.hpp
/// \brief Branch switching at a period doubling (flip) of a branch of forced periodic orbits:
/// the flip located by a secant on the multiplier through -1, and the branch of period-2T
/// orbits born there, started along the multiplier's eigenvector and continued.

#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/bifurcation.hpp>
#include <stickslip/steady_state/continuation.hpp>
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
  struct End {
    Scalar p, g;  // g = mu + 1
    PeriodicOrbit<System> orbit;
  };
  End lo{a.parameter, flip_multiplier(a.orbit.monodromy, nullptr) + 1, a.orbit};
  End hi{b.parameter, flip_multiplier(b.orbit.monodromy, nullptr) + 1, b.orbit};
  if (!(lo.g * hi.g <= 0)) {
    f.message = "no multiplier crosses -1 between the points (mu + 1 = " + detail::format_value(lo.g) + ", " +
                detail::format_value(hi.g) + ")";
    return f;
  }
  int side = 0;  // Illinois: halve the value of the end kept twice
  for (int it = 0; it < 40; ++it) {
    End* best = std::abs(lo.g) <= std::abs(hi.g) ? &lo : &hi;
    if (std::abs(best->g) <= tolerance) {
      f.ok = true;
      f.parameter = best->p;
      f.orbit = best->orbit;
      f.multiplier = flip_multiplier(best->orbit.monodromy, &f.eigenvector);
      const auto P = shooting_.periodic_indices(a.orbit.x0.size());
      f.tangent.resize(static_cast<Eigen::Index>(P.size()) + 1);
      for (std::size_t k = 0; k < P.size(); ++k)
        f.tangent[static_cast<Eigen::Index>(k)] = b.orbit.x0[P[k]] - a.orbit.x0[P[k]];
      f.tangent[f.tangent.size() - 1] = b.parameter - a.parameter;
      f.tangent.normalize();
      return f;
    }
    const Scalar p = (lo.p * hi.g - hi.p * lo.g) / (hi.g - lo.g);
    set_(sys_, p);
    const PeriodicOrbit<System> o = shooting.forced(best->orbit.mode, best->orbit.t0, best->orbit.x0, period_(p));
    if (!o.ok()) {
      f.message = "the orbit at p = " + detail::format_value(p) + " failed: " + o.message;
      return f;
    }
    const Scalar g = flip_multiplier(o.monodromy, nullptr) + 1;
    if ((g <= 0) == (lo.g <= 0)) {
      lo = End{p, g, o};
      if (side == -1) hi.g /= 2;
      side = -1;
    } else {
      hi = End{p, g, o};
      if (side == 1) lo.g /= 2;
      side = 1;
    }
  }
  f.message = "the secant on mu + 1 did not reach the tolerance in 40 orbits";
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
  State x = xf;
  Scalar p = flip.parameter;
  for (Eigen::Index k = 0; k < np; ++k) x[P[static_cast<std::size_t>(k)]] += offset * dir[k];
  p += offset * dir[np];
  auto pack = [&](const State& s, Scalar q) {
    Vector y(np + 1);
    for (Eigen::Index k = 0; k < np; ++k) y[k] = s[P[static_cast<std::size_t>(k)]];
    y[np] = q;
    return y;
  };
  const Vector y_f = pack(xf, flip.parameter);
  PeriodicOrbit<System> orbit;
  Vector r, rp, rm, rhs(np + 1), dy(np + 1);
  Matrix J(np + 1, np + 1);
  for (int it = 0; it <= shooting_.max_iterations; ++it) {
    set_(sys_, p);
    const PeriodRun<System> run = run_period(sys_, flip.orbit.mode, flip.orbit.t0, x, 2 * period_(p), shooting_, true);
    if (!run.ok()) {
      result.message = "the 2T orbit run failed at p = " + detail::format_value(p) + ": " + run.message;
      return result;
    }
    const Scalar res = shooting.residual(run.x_end, x, r);
    if (res <= shooting.tolerance_at(x)) {
      orbit = shooting.make_orbit(run, flip.orbit.mode, flip.orbit.t0, x, 2 * period_(p), false, res, it + 1);
      break;
    }
    if (it == shooting_.max_iterations) {
      result.message = "Newton on the first 2T orbit did not converge (residual " + detail::format_value(res) + ")";
      return result;
    }
    const Scalar h = shooting_.fd_step * std::max(Scalar(1), std::abs(p));
    set_(sys_, p + h);
    const PeriodRun<System> up = run_period(sys_, flip.orbit.mode, flip.orbit.t0, x, 2 * period_(p + h), shooting_, false);
    set_(sys_, p - h);
    const PeriodRun<System> down = run_period(sys_, flip.orbit.mode, flip.orbit.t0, x, 2 * period_(p - h), shooting_, false);
    if (!up.ok() || !down.ok()) {
      result.message = "the 2T run at p +- h failed near p = " + detail::format_value(p);
      return result;
    }
    shooting.residual(up.x_end, x, rp);
    shooting.residual(down.x_end, x, rm);
    J.topLeftCorner(np, np) = shooting.periodic_block(run.monodromy) - Matrix::Identity(np, np);
    J.topRightCorner(np, 1) = (rp - rm) / (2 * h);
    J.bottomRows(1) = dir.transpose();
    rhs.head(np) = -r;
    rhs[np] = offset - dir.dot(pack(x, p) - y_f);
    if (!shooting.newton_step(J, rhs, dy)) {
      result.message = "singular Newton matrix on the first 2T orbit at p = " + detail::format_value(p);
      return result;
    }
    for (Eigen::Index k = 0; k < np; ++k) x[P[static_cast<std::size_t>(k)]] += dy[k];
    p += dy[np];
  }
  if (!orbit.ok()) {
    result.message = "the first 2T orbit: " + orbit.message;
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
  ContinuationOptions<Scalar> co = opt_;
  co.direction = p >= flip.parameter ? 1 : -1;
  if (!(p >= co.parameter_min && p <= co.parameter_max)) {
    result.message = "the first 2T orbit's p = " + detail::format_value(p) + " is outside the range";
    return result;
  }
  const auto period = period_;
  Continuation<System> cont(sys_, set_, [period](Scalar q) { return 2 * period(q); }, shooting_, co);
  if (start_mode_) cont.start_mode(start_mode_);
  return cont.run(orbit.mode, orbit.t0, orbit.x0, p);
}

}  // namespace stickslip
