#pragma once
/// \file branch_start.hpp
/// \brief Branch switching's shared steps (PeriodDoubling's period-2T branch, SymmetricBranches'
/// asymmetric branch): a bifurcation located by a secant in p on a function of the orbit's
/// multipliers, the branch's secant tangent, the first orbit of the new branch by Newton with
/// (x_P, p) at a given arclength from the bifurcation, and the new branch continued from it.

#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/period_run.hpp>
#include <stickslip/steady_state/shooting.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>

namespace stickslip::detail {

/// Newton on (x_P(t0 + k T(p)) - x_P, dir^T (y - y_b) - offset) = 0, y = (x_P, p), from
/// y_b + offset dir, where y_b = (base.x0_P, p_b) is the orbit at the bifurcation and `dir` a unit
/// vector in (x_P, p). Returns the converged orbit (period k T(p)) and its p; a not-ok orbit
/// with `why` otherwise.
template <class System>
PeriodicOrbit<System> start_on_branch(
    System& sys, const std::function<void(System&, typename System::Scalar)>& set_parameter,
    const std::function<typename System::Scalar(typename System::Scalar)>& period_of, int k,
    const ShootingOptions<typename System::Scalar>& options, const PeriodicOrbit<System>& base,
    typename System::Scalar p_b, const Eigen::Matrix<typename System::Scalar, Eigen::Dynamic, 1>& dir,
    typename System::Scalar offset, typename System::Scalar& p, std::string& why) {
  using Scalar = typename System::Scalar;
  using State = typename System::State;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  Shooting<System> shooting(sys, options);
  const auto P = options.periodic_indices(base.x0.size());
  const auto np = static_cast<Eigen::Index>(P.size());
  auto pack = [&](const State& s, Scalar q) {
    Vector y(np + 1);
    for (Eigen::Index i = 0; i < np; ++i) y[i] = s[P[static_cast<std::size_t>(i)]];
    y[np] = q;
    return y;
  };
  const Vector y_b = pack(base.x0, p_b);
  State x = base.x0;
  p = p_b + offset * dir[np];
  for (Eigen::Index i = 0; i < np; ++i) x[P[static_cast<std::size_t>(i)]] += offset * dir[i];
  Vector r, rp, rm, rhs(np + 1), dy(np + 1);
  Matrix J(np + 1, np + 1);
  PeriodicOrbit<System> failed;
  for (int it = 0; it <= options.max_iterations; ++it) {
    set_parameter(sys, p);
    const PeriodRun<System> run = run_period(sys, base.mode, base.t0, x, k * period_of(p), options, true);
    if (!run.ok()) {
      why = "the orbit run failed at p = " + format_value(p) + ": " + run.message;
      return failed;
    }
    const Scalar res = shooting.residual(run.x_end, x, r);
    if (res <= shooting.tolerance_at(x)) {
      PeriodicOrbit<System> orbit =
          shooting.make_orbit(run, base.mode, base.t0, x, k * period_of(p), false, res, it + 1);
      if (!orbit.ok()) why = orbit.message;
      return orbit;
    }
    if (it == options.max_iterations) {
      why = "Newton on the first orbit did not converge (residual " + format_value(res) + ")";
      return failed;
    }
    const Scalar h = options.fd_step * std::max(Scalar(1), std::abs(p));
    set_parameter(sys, p + h);
    const PeriodRun<System> up = run_period(sys, base.mode, base.t0, x, k * period_of(p + h), options, false);
    set_parameter(sys, p - h);
    const PeriodRun<System> down = run_period(sys, base.mode, base.t0, x, k * period_of(p - h), options, false);
    if (!up.ok() || !down.ok()) {
      why = "the runs at p +- h failed near p = " + format_value(p);
      return failed;
    }
    shooting.residual(up.x_end, x, rp);
    shooting.residual(down.x_end, x, rm);
    J.topLeftCorner(np, np) = shooting.periodic_block(run.monodromy) - Matrix::Identity(np, np);
    J.topRightCorner(np, 1) = (rp - rm) / (2 * h);
    J.bottomRows(1) = dir.transpose();
    rhs.head(np) = -r;
    rhs[np] = offset - dir.dot(pack(x, p) - y_b);
    if (!shooting.newton_step(J, rhs, dy)) {
      why = "singular Newton matrix on the first orbit at p = " + format_value(p);
      return failed;
    }
    for (Eigen::Index i = 0; i < np; ++i) x[P[static_cast<std::size_t>(i)]] += dy[i];
    p += dy[np];
  }
  why = "Newton on the first orbit did not converge";
  return failed;
}

/// One end of a secant bracket: parameter, the function's value there and the orbit.
template <class System>
struct SecantEnd {
  typename System::Scalar p = 0, g = 0;
  PeriodicOrbit<System> orbit;
};

/// Illinois secant on g(p) over the bracket [lo, hi] (g of opposite signs; the value of an end
/// kept twice halved): `shoot(p, from, end, why)` computes the orbit and g at p from the
/// nearer end's orbit (false: failed, why set); `done(end)` says when the nearer end is close
/// enough. True with `found` the end that was; false with why after a failure or 40 orbits.
template <class System, class Shoot, class Done>
bool illinois_secant(SecantEnd<System> lo, SecantEnd<System> hi, Shoot&& shoot, Done&& done,
                     SecantEnd<System>& found, std::string& why) {
  using Scalar = typename System::Scalar;
  int side = 0;
  for (int it = 0; it < 40; ++it) {
    const SecantEnd<System>& best = std::abs(lo.g) <= std::abs(hi.g) ? lo : hi;
    if (done(best)) {
      found = best;
      return true;
    }
    const Scalar p = (lo.p * hi.g - hi.p * lo.g) / (hi.g - lo.g);
    SecantEnd<System> e;
    if (!shoot(p, best, e, why)) return false;
    if ((e.g <= 0) == (lo.g <= 0)) {
      lo = std::move(e);
      if (side == -1) hi.g /= 2;
      side = -1;
    } else {
      hi = std::move(e);
      if (side == 1) lo.g /= 2;
      side = 1;
    }
  }
  why = "the secant did not reach the tolerance in 40 orbits";
  return false;
}

/// The unit secant from point a to point b of a branch in (x_P, p).
template <class Point, class Options>
Eigen::Matrix<typename Point::Scalar, Eigen::Dynamic, 1> branch_secant(const Point& a, const Point& b,
                                                                      const Options& options) {
  const auto P = options.periodic_indices(a.orbit.x0.size());
  Eigen::Matrix<typename Point::Scalar, Eigen::Dynamic, 1> t(static_cast<Eigen::Index>(P.size()) + 1);
  for (std::size_t k = 0; k < P.size(); ++k) t[static_cast<Eigen::Index>(k)] = b.orbit.x0[P[k]] - a.orbit.x0[P[k]];
  t[t.size() - 1] = b.parameter - a.parameter;
  t.normalize();
  return t;
}

/// Continuation of the new branch from its first orbit (at p) away from the bifurcation at
/// p_b; StartFailed with a message (naming `what`) when p is outside the range.
template <class System>
ContinuationResult<System> continue_new_branch(
    System& sys, const typename Continuation<System>::SetParameter& set_parameter,
    const typename Continuation<System>::PeriodOf& period, const ShootingOptions<typename System::Scalar>& shooting,
    ContinuationOptions<typename System::Scalar> options, const typename Continuation<System>::StartMode& start_mode,
    const PeriodicOrbit<System>& orbit, typename System::Scalar p, typename System::Scalar p_b, const std::string& what) {
  options.direction = p >= p_b ? 1 : -1;
  if (!(p >= options.parameter_min && p <= options.parameter_max)) {
    ContinuationResult<System> result;
    result.status = ContinuationStatus::StartFailed;
    result.message = "the first " + what + "'s p = " + format_value(p) + " is outside the range";
    return result;
  }
  Continuation<System> cont(sys, set_parameter, period, shooting, options);
  if (start_mode) cont.start_mode(start_mode);
  return cont.run(orbit.mode, orbit.t0, orbit.x0, p);
}

}  // namespace stickslip::detail
