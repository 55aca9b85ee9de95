#pragma once
// Systems used by the ode benchmarks.

#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>

#include <chrono>
#include <cmath>

namespace stickslip::bench {

/// Seconds per call of `run`, averaged over as many calls as fit in at least 0.1 s.
template <class Run>
double seconds_per_run(Run&& run) {
  long runs = 0;
  double elapsed = 0;
  const auto start = std::chrono::steady_clock::now();
  do {
    run();
    ++runs;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } while (elapsed < 0.1);
  return elapsed / static_cast<double>(runs);
}

/// Chain of n/2 unit masses with unit springs (fixed ends): x = (q, q'), q'' = -K q, K
/// tridiagonal (2, -1). O(n) right-hand side; no guards.
template <int N>
struct SpringChain {
  using Scalar = double;
  using State = Eigen::Matrix<double, N, 1>;
  using Mode = int;
  Eigen::Index n = N;
  void rhs(const Mode&, double, const State& x, State& d) const {
    const Eigen::Index m = x.size() / 2;
    for (Eigen::Index i = 0; i < m; ++i) {
      d[i] = x[m + i];
      double f = -2.0 * x[i];
      if (i > 0) f += x[i - 1];
      if (i + 1 < m) f += x[i + 1];
      d[m + i] = f;
    }
  }
  Eigen::Index num_guards(const Mode&) const { return 0; }
  void guards(const Mode&, double, const State&, Eigen::VectorXd&) const {}
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return CrossingDirection::Either;
  }
  TransitionAction transition(Mode&, const TriggeredGuards&, double, State&) const {
    return TransitionAction::proceed();
  }
};

/// Elastic bouncing ball (restitution 1): one impact every 2 sqrt(2 h0 / g).
struct ElasticBall {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  void rhs(const Mode&, double, const State& x, State& d) const { d << x[1], -9.81; }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const { g[0] = x[0]; }
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return CrossingDirection::Falling;
  }
  TransitionAction transition(Mode& m, const TriggeredGuards&, double, State& x) const {
    x[1] = -x[1];
    ++m;
    return TransitionAction::proceed();
  }
};

/// Mass-spring on a belt moving at v_b, Coulomb friction mu_s > mu_k (m = k = N = 1):
/// stick: x' = v_b; slip (v = x' < v_b): x'' = -x + mu_k. State (x, v), mode 0 = stick, 1 = slip.
/// Stick ends when x = mu_s (spring force reaches the static limit); slip ends when v = v_b.
/// Closed form (phase-plane circle about x = mu_k): slip from (mu_s, v_b) with a = mu_s - mu_k
/// lasts 2 pi - 2 atan(a / v_b), ends at x = mu_k - a, and the stick that follows lasts 2 a / v_b.
struct BeltOscillator {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  double mu_s = 0.4, mu_k = 0.3, v_b = 0.1;
  void rhs(const Mode& m, double, const State& x, State& d) const {
    if (m == 0) {
      d << v_b, 0.0;
    } else {
      d << x[1], -x[0] + mu_k;
    }
  }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode& m, double, const State& x, Eigen::VectorXd& g) const {
    g[0] = m == 0 ? x[0] - mu_s : x[1] - v_b;
  }
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return CrossingDirection::Rising;
  }
  TransitionAction transition(Mode& m, const TriggeredGuards&, double, State& x) const {
    if (m == 1 && std::abs(x[0]) <= mu_s) {
      m = 0;
      x[1] = v_b;  // exact reset on entering stick
    } else {
      m = 1;
    }
    return TransitionAction::proceed();
  }
  double slip_duration() const { return 2.0 * std::acos(-1.0) - 2.0 * std::atan((mu_s - mu_k) / v_b); }
  double stick_duration() const { return 2.0 * (mu_s - mu_k) / v_b; }
  /// k-th switch time (k = 0: first stick -> slip) from x = 0, v = v_b in stick at t = 0.
  double switch_time(int k) const {
    const double first = mu_s / v_b, period = slip_duration() + stick_duration();
    return first + (k / 2) * period + (k % 2) * slip_duration();
  }
  /// Exact state at t.
  State exact(double t) const {
    const double first = mu_s / v_b;
    if (t < first) return State(v_b * t, v_b);
    const double period = slip_duration() + stick_duration();
    const double tau = std::fmod(t - first, period);
    const double a = mu_s - mu_k;
    if (tau < slip_duration()) {
      return State(mu_k + a * std::cos(tau) + v_b * std::sin(tau),
                   -a * std::sin(tau) + v_b * std::cos(tau));
    }
    return State(mu_k - a + v_b * (tau - slip_duration()), v_b);
  }
};

}  // namespace stickslip::bench
