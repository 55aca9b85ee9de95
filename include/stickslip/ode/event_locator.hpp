#pragma once
/// \file event_locator.hpp
/// \brief Guard arming and crossing detection, and the Illinois root finder used to place an
/// event in time on a method's dense output.
///
/// Rule (see docs/ode.md, "Event semantics"): each guard g_i has a trigger level L_i and a sign
/// s_i; it fires in a step when s_i (g_i - L_i) < 0 at the step end, having been >= 0 before.
///  - Falling (s = +1), Rising (s = -1): *armed* (L = 0) when the mode starts with g strictly on
///    the non-triggering side by more than the zero tolerance z. Otherwise it is *disarmed*: its
///    level is moved just beyond the start value into the triggering direction
///    (L = min(g0, 0) - z for Falling, max(g0, 0) + z for Rising), so it neither re-triggers on
///    round-off nor stays blind; it is armed (L = 0) once it is more than z on the non-triggering
///    side (at a step end, or at the point of a step to which the stepper cuts it back when the
///    guard fires after such an excursion inside the step). A disarmed guard that fires is an
///    *immediate* event (counted by the Zeno guard).
///  - Either: armed with s = sign(g0) when |g0| > z; otherwise it cannot fire (s = 0) until
///    |g| > z, then s = sign(g).

#include <stickslip/ode/detail/hermite_cubic.hpp>
#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

namespace stickslip {
namespace detail {

/// Trigger levels, signs and arming of the guards of the current mode.
template <class Scalar>
class GuardMonitor {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// Set up for a mode with guard values g0 and their directions; z = zero tolerance.
  /// `direction(i)` returns the CrossingDirection of guard i. The storage only grows: it
  /// allocates when a mode has more guards than any mode before, never for fewer.
  template <class DirectionFn>
  void start_mode(const Vector& g0, DirectionFn&& direction, Scalar z) {
    const Eigen::Index n = g0.size();
    if (level_.size() < n) {
      level_.resize(n);
      sign_.resize(n);
      armed_.resize(n);
      dir_.resize(n);
    }
    z_ = z;
    for (Eigen::Index i = 0; i < n; ++i) {
      const CrossingDirection d = direction(i);
      dir_[i] = static_cast<int>(d);
      const Scalar g = g0[i];
      level_[i] = Scalar(0);
      armed_[i] = 1;
      if (d == CrossingDirection::Falling) {
        sign_[i] = Scalar(1);
        if (!(g > z)) {
          armed_[i] = 0;
          level_[i] = std::min(g, Scalar(0)) - z;
        }
      } else if (d == CrossingDirection::Rising) {
        sign_[i] = Scalar(-1);
        if (!(g < -z)) {
          armed_[i] = 0;
          level_[i] = std::max(g, Scalar(0)) + z;
        }
      } else {
        if (std::abs(g) > z) {
          sign_[i] = g > 0 ? Scalar(1) : Scalar(-1);
        } else {
          sign_[i] = Scalar(0);
          armed_[i] = 0;
        }
      }
    }
  }

  /// Signed distance to the trigger: >= 0 before, < 0 once guard i has crossed.
  Scalar distance(Eigen::Index i, Scalar g) const { return sign_[i] * (g - level_[i]); }

  /// True when guard i has crossed at value g.
  bool crossed(Eigen::Index i, Scalar g) const { return distance(i, g) < Scalar(0); }

  /// True when any guard has crossed at values g.
  bool any_crossed(const Vector& g) const {
    for (Eigen::Index i = 0; i < g.size(); ++i)
      if (crossed(i, g[i])) return true;
    return false;
  }

  /// After an accepted step without event: arm the disarmed guards that left zero.
  void update_arming(const Vector& g) {
    for (Eigen::Index i = 0; i < g.size(); ++i) {
      if (armed_[i]) continue;
      const auto d = static_cast<CrossingDirection>(dir_[i]);
      if (!out_of_zero(i, g[i])) continue;
      armed_[i] = 1;
      if (d == CrossingDirection::Either)
        sign_[i] = g[i] > 0 ? Scalar(1) : Scalar(-1);
      else
        level_[i] = Scalar(0);
    }
  }

  /// True when value g of guard i lies more than the zero tolerance on its non-triggering side,
  /// the condition under which update_arming arms a disarmed guard.
  bool out_of_zero(Eigen::Index i, Scalar g) const {
    const auto d = static_cast<CrossingDirection>(dir_[i]);
    if (d == CrossingDirection::Falling) return g > z_;
    if (d == CrossingDirection::Rising) return g < -z_;
    return std::abs(g) > z_;
  }

  /// True when guard i was disarmed (started the mode at zero): its event is immediate.
  bool disarmed(Eigen::Index i) const { return armed_[i] == 0; }

 private:
  Vector level_, sign_;
  Eigen::Array<int, Eigen::Dynamic, 1> armed_, dir_;
  Scalar z_ = 0;
};

/// Final bracket [lo, hi] of a root: phi(lo) >= 0, phi(hi) < 0, hi - lo <= tolerance.
template <class Scalar>
struct RootBracket {
  Scalar lo, hi;
  int evaluations = 0;
};

/// Illinois (modified regula falsi) root finding of phi on [lo, hi] with phi(lo) >= 0 > phi(hi),
/// until hi - lo <= tol. The trial point is kept tol/2 inside the bracket so that the bracket
/// itself closes; a bisection step is taken when three iterations do not halve the bracket.
template <class Scalar, class Phi>
RootBracket<Scalar> illinois_root(Phi&& phi, Scalar lo, Scalar flo, Scalar hi, Scalar fhi,
                                  Scalar tol) {
  using std::abs;
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  tol = std::max(tol, Scalar(4) * eps * std::max(abs(lo), abs(hi)));
  RootBracket<Scalar> r{lo, hi, 0};
  int side = 0;
  Scalar width_ref = hi - lo;
  int since_halved = 0;
  while (r.hi - r.lo > tol && r.evaluations < 400) {
    Scalar c;
    if (since_halved >= 3) {
      c = r.lo + (r.hi - r.lo) / Scalar(2);
    } else {
      c = r.hi - fhi * (r.hi - r.lo) / (fhi - flo);
      if (!(c > r.lo && c < r.hi)) c = r.lo + (r.hi - r.lo) / Scalar(2);
      const Scalar margin = std::min(tol / Scalar(2), (r.hi - r.lo) / Scalar(4));
      c = std::min(std::max(c, r.lo + margin), r.hi - margin);
    }
    const Scalar fc = phi(c);
    ++r.evaluations;
    if (fc < Scalar(0)) {
      r.hi = c;
      fhi = fc;
      if (side == -1) flo /= Scalar(2);
      side = -1;
    } else {
      r.lo = c;
      flo = fc;
      if (side == 1) fhi /= Scalar(2);
      side = 1;
    }
    if (r.hi - r.lo <= width_ref / Scalar(2)) {
      width_ref = r.hi - r.lo;
      since_halved = 0;
    } else {
      ++since_halved;
    }
  }
  return r;
}

/// Safeguarded Newton root finding of phi on [lo, hi] with phi(lo) >= 0 > phi(hi), until
/// hi - lo <= tol, for a phi whose slope comes with its value: `phi(t, slope)` returns phi(t) and
/// sets slope = phi'(t) (an approximation is enough: it only steers the iteration). The first
/// trial point is the root of the cubic Hermite interpolant of the end values and slopes `slo`,
/// `shi` (the secant point when they are not finite); then t_{k+1} = t_k - phi(t_k) / phi'(t_k)
/// while that stays in the bracket and is at most half the previous correction, else a bisection
/// of the bracket (as Numerical Recipes' rtsafe: the bracket is never lost, and at least every
/// second evaluation halves it where Newton is slow, e.g. at a multiple root). Once a correction
/// is below tol / 2 the next point is set tol / 4 past the predicted root, on the far side from
/// t_k, so that the bracket closes around it. Near a simple root that is 2-5 evaluations where
/// the Illinois method takes 9-20 (event location on the closed form of an exact mode,
/// where the slope costs one product).
template <class Scalar, class PhiSlope>
RootBracket<Scalar> newton_root(PhiSlope&& phi, Scalar lo, Scalar flo, Scalar slo, Scalar hi,
                                Scalar fhi, Scalar shi, Scalar tol) {
  using std::abs;
  using std::isfinite;
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  tol = std::max(tol, Scalar(4) * eps * std::max(abs(lo), abs(hi)));
  RootBracket<Scalar> r{lo, hi, 0};
  auto inside = [&](Scalar c) {  // keep a trial point off the bracket's ends
    const Scalar margin = std::min(tol / Scalar(4), (r.hi - r.lo) / Scalar(4));
    return std::min(std::max(c, r.lo + margin), r.hi - margin);
  };
  // First point: the root of the cubic Hermite interpolant p(s), s in [0, 1], by Newton steps on
  // the cubic itself from the secant point (the secant point when they leave [0, 1]).
  const Scalar H = hi - lo;
  const Scalar secant = flo / (flo - fhi);
  const Scalar s_secant = isfinite(secant) ? secant : Scalar(0.5);
  Scalar s = s_secant;
  if (isfinite(slo) && isfinite(shi)) {
    const HermiteCubic<Scalar> p{flo, H * slo, fhi, H * shi};
    for (int k = 0; k < 8; ++k) {
      const Scalar next = s - p(s) / p.derivative(s);
      if (!(next > 0 && next < 1)) {
        s = s_secant;
        break;
      }
      const bool done = abs(next - s) <= eps;
      s = next;
      if (done) break;
    }
  }
  Scalar c = inside(lo + s * H);
  Scalar last_step = H;  // the previous Newton correction (the bracket before the first)
  while (r.hi - r.lo > tol && r.evaluations < 400) {
    Scalar slope = std::numeric_limits<Scalar>::quiet_NaN();
    const Scalar fc = phi(c, slope);
    ++r.evaluations;
    if (fc < Scalar(0)) {
      r.hi = c;
    } else {
      r.lo = c;
    }
    if (r.hi - r.lo <= tol) break;
    const Scalar newton = c - fc / slope;
    const Scalar step = abs(newton - c);
    if (!(isfinite(newton) && newton >= r.lo && newton <= r.hi && step <= last_step / Scalar(2))) {
      c = r.lo + (r.hi - r.lo) / Scalar(2);  // bisection
      last_step = (r.hi - r.lo) / Scalar(2);
      continue;
    }
    last_step = step;
    if (step < tol / Scalar(2)) {
      // Converged: a point tol / 4 past the predicted root, away from c, closes the bracket.
      const Scalar away = newton > c || (newton == c && fc >= Scalar(0)) ? Scalar(1) : Scalar(-1);
      c = inside(newton + away * tol / Scalar(4));
      last_step = r.hi - r.lo;  // the closing point is not a Newton step
    } else {
      c = inside(newton);
    }
  }
  return r;
}

/// Move a root `first` found on a method's dense output to the root of the method's own steps
/// (EventState::Reintegrate): `step_to(tau)` re-takes the step from its start to tau and returns
/// the guard's distance there. The two differ by the dense output's error, nearly constant near
/// the root, so the steps' root lies near first - d(first) / slope (`slope`: the dense guard's
/// distance rate at first): probe a little beyond it, then 4x wider, until the sign changes, and
/// finish by Illinois inside the step's bracket [lo, hi] (d(lo) >= 0 > d(hi)). The last call of
/// step_to is at the returned bracket's hi. This form starts after the step to `first` has been
/// taken, its distance being `d_first`; refine_root_on_steps takes that step first.
template <class Scalar, class StepTo>
RootBracket<Scalar> refine_root_on_steps_from(StepTo&& step_to, Scalar first, Scalar d_first,
                                              Scalar slope, Scalar lo, Scalar d_lo, Scalar hi,
                                              Scalar d_hi, Scalar tol) {
  Scalar stepped_to = first;
  auto probe = [&](Scalar tau) {
    stepped_to = tau;
    return step_to(tau);
  };
  auto narrow = [&](Scalar tau, Scalar d) {  // keep [lo, hi] a bracket: d(lo) >= 0 > d(hi)
    if (d >= Scalar(0)) {
      lo = tau;
      d_lo = d;
    } else {
      hi = tau;
      d_hi = d;
    }
  };
  narrow(first, d_first);
  if (slope < Scalar(0)) {
    // Bracket the steps' root next to first - d_first / slope (a little beyond it, then 4x
    // wider), so that the root finding starts on a bracket of the size of the offset.
    const Scalar towards = d_first >= Scalar(0) ? Scalar(1) : Scalar(-1);
    using std::abs;
    Scalar reach = abs(d_first / slope) * Scalar(1.01) + tol;
    for (int k = 0; k < 6; ++k, reach *= Scalar(4)) {
      const Scalar at = first + towards * reach;
      if (!(at > lo && at < hi)) break;
      const Scalar d = probe(at);
      narrow(at, d);
      if ((d < Scalar(0)) == (towards > Scalar(0))) break;  // the sign changed: [lo, hi] brackets
    }
  }
  const auto br = illinois_root(probe, lo, d_lo, hi, d_hi, tol);
  if (stepped_to != br.hi) probe(br.hi);
  return br;
}

/// refine_root_on_steps_from after the step to `first`.
template <class Scalar, class StepTo>
RootBracket<Scalar> refine_root_on_steps(StepTo&& step_to, Scalar first, Scalar slope, Scalar lo,
                                         Scalar d_lo, Scalar hi, Scalar d_hi, Scalar tol) {
  const Scalar d_first = step_to(first);
  return refine_root_on_steps_from(step_to, first, d_first, slope, lo, d_lo, hi, d_hi, tol);
}

}  // namespace detail
}  // namespace stickslip
