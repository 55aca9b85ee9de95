#pragma once
// Small hybrid systems with closed-form solutions, shared by the ode tests.

#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace stickslip::test {

/// Ball over a floor: y' = v, v' = -g; guard y (Falling); impact v -> -e v.
/// Dropped from rest at height h0 at t = 0: impacts at t_1 = sqrt(2 h0 / g) and
/// t_{k+1} = t_k + 2 e^k v_1 / g with v_1 = g t_1.
struct BouncingBall {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  double gravity = 9.81;
  double restitution = 0.8;
  void rhs(const Mode&, double, const State& x, State& dxdt) const { dxdt << x[1], -gravity; }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const { g[0] = x[0]; }
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return CrossingDirection::Falling;
  }
  TransitionAction transition(Mode& m, const TriggeredGuards&, double, State& x) const {
    x[1] = -restitution * x[1];
    ++m;  // the mode counts the bounces
    return TransitionAction::proceed();
  }
  /// Closed-form time of impact k (1-based) when dropped from rest at height h0 at t = 0.
  double impact_time(int k, double h0) const {
    const double t1 = std::sqrt(2.0 * h0 / gravity);
    const double v1 = gravity * t1;
    double t = t1;
    for (int j = 1; j < k; ++j) t += 2.0 * std::pow(restitution, j) * v1 / gravity;
    return t;
  }
};

}  // namespace stickslip::test

namespace stickslip::test {

/// Harmonic oscillator x'' = -omega^2 x from x(0) = 1, x'(0) = 0: x = cos(omega t). Guard x with a
/// chosen direction; the transition only counts. Zeros at t_k = (k - 1/2) pi / omega.
struct Oscillator {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  double omega = 3.0;
  CrossingDirection direction = CrossingDirection::Either;
  double nan_after = std::numeric_limits<double>::infinity();  ///< rhs returns NaN for t > this
  void rhs(const Mode&, double t, const State& x, State& dxdt) const {
    dxdt << x[1], -omega * omega * x[0];
    if (t > nan_after) dxdt[1] = std::numeric_limits<double>::quiet_NaN();
  }
  bool guarded = true;  ///< false: no guard (a plain ODE; nothing but the stepper's own checks)
  Eigen::Index num_guards(const Mode&) const { return guarded ? 1 : 0; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const {
    if (guarded) g[0] = x[0];
  }
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const { return direction; }
  TransitionAction transition(Mode& m, const TriggeredGuards&, double, State&) const {
    ++m;
    return TransitionAction::proceed();
  }
};

}  // namespace stickslip::test

namespace stickslip::test {

/// Linear system x' = A x + b(t) without guards (one mode), N states (fixed or dynamic).
template <int N>
struct LinearSystem {
  using Scalar = double;
  using State = Eigen::Matrix<double, N, 1>;
  using Mode = int;
  using Matrix = Eigen::Matrix<double, N, N>;
  Matrix a;
  void rhs(const Mode&, double, const State& x, State& dxdt) const { dxdt.noalias() = a * x; }
  Eigen::Index num_guards(const Mode&) const { return 0; }
  void guards(const Mode&, double, const State&, Eigen::VectorXd&) const {}
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return CrossingDirection::Either;
  }
  TransitionAction transition(Mode&, const TriggeredGuards&, double, State&) const {
    return TransitionAction::proceed();
  }
};

/// LinearSystem that also supplies its exact Jacobian (used by Rosenbrock23 instead of
/// finite differences).
template <int N>
struct LinearSystemWithJacobian : LinearSystem<N> {
  void jacobian(const int&, double, const typename LinearSystem<N>::State&,
                typename LinearSystem<N>::Matrix& j) const {
    j = this->a;
  }
};

/// Uniform motion x' = 1 (x = t) with guards g_i = w_i x - c_i. Each firing of guard i toggles bit
/// i of the mode; while the bit is set the guard watches the opposite direction (Rising <->
/// Falling, Either -> Falling), so a crossed guard does not fire again until it turns back.
struct Ramp {
  using Scalar = double;
  using State = Eigen::Matrix<double, 1, 1>;
  using Mode = unsigned;
  std::vector<double> weight, level;
  std::vector<CrossingDirection> direction;
  void rhs(const Mode&, double, const State&, State& dxdt) const { dxdt[0] = 1.0; }
  Eigen::Index num_guards(const Mode&) const { return static_cast<Eigen::Index>(level.size()); }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const {
    for (std::size_t i = 0; i < level.size(); ++i)
      g[static_cast<Eigen::Index>(i)] = weight[i] * x[0] - level[i];
  }
  CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    const auto k = static_cast<std::size_t>(i);
    if (!(m & (1u << k))) return direction[k];
    return direction[k] == CrossingDirection::Falling ? CrossingDirection::Rising
                                                      : CrossingDirection::Falling;
  }
  TransitionAction transition(Mode& m, const TriggeredGuards& which, double, State&) const {
    for (Eigen::Index i : which) m ^= 1u << static_cast<unsigned>(i);
    return TransitionAction::proceed();
  }
};

}  // namespace stickslip::test

namespace stickslip::test {

/// Nonlinear scalar equation x' = -x^2 (no guards): x(t) = x0 / (1 + x0 t).
struct Riccati {
  using Scalar = double;
  using State = Eigen::Matrix<double, 1, 1>;
  using Mode = int;
  void rhs(const Mode&, double, const State& x, State& dxdt) const { dxdt[0] = -x[0] * x[0]; }
  Eigen::Index num_guards(const Mode&) const { return 0; }
  void guards(const Mode&, double, const State&, Eigen::VectorXd&) const {}
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return CrossingDirection::Either;
  }
  TransitionAction transition(Mode&, const TriggeredGuards&, double, State&) const {
    return TransitionAction::proceed();
  }
  static double exact(double t, double x0) { return x0 / (1.0 + x0 * t); }
};

}  // namespace stickslip::test

namespace stickslip::test {

/// Mass-spring on a belt moving at v_b with Coulomb friction mu_s > mu_k (m = k = N = 1), written
/// as a plain hybrid system: mode 0 stick (x' = v_b, x'' = 0; two guards, the capacity margins
/// mu_s - x and mu_s + x, both Falling), mode 1 slip (x'' = -x + mu_k; one guard, the sliding
/// velocity x' - v_b, Rising). The guard count changes at every event. Closed form: from x = 0
/// in stick, stick ends at x = mu_s (t = mu_s / v_b); slip from (mu_s, v_b) with a = mu_s - mu_k
/// lasts 2 pi - 2 atan(a / v_b) and ends at x = mu_k - a; the stick that follows lasts 2 a / v_b.
/// The transition records how far the state it receives is from the surface of the guard that
/// fired (|g| there).
struct StickSlipBelt {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  double mu_s = 0.4, mu_k = 0.3, v_b = 0.1;
  double max_surface_distance = 0;  ///< max |g_fired| over the states handed to transition
  void rhs(const Mode& m, double, const State& x, State& d) const {
    if (m == 0) {
      d << v_b, 0.0;
    } else {
      d << x[1], -x[0] + mu_k;
    }
  }
  Eigen::Index num_guards(const Mode& m) const { return m == 0 ? 2 : 1; }
  void guards(const Mode& m, double, const State& x, Eigen::VectorXd& g) const {
    if (m == 0) {
      g[0] = mu_s - x[0];
      g[1] = mu_s + x[0];
    } else {
      g[0] = x[1] - v_b;
    }
  }
  CrossingDirection guard_direction(const Mode& m, Eigen::Index) const {
    return m == 0 ? CrossingDirection::Falling : CrossingDirection::Rising;
  }
  TransitionAction transition(Mode& m, const TriggeredGuards& which, double, State& x) {
    for (Eigen::Index i : which) {
      const double g = m == 1 ? x[1] - v_b : (i == 0 ? mu_s - x[0] : mu_s + x[0]);
      max_surface_distance = std::max(max_surface_distance, std::abs(g));
    }
    if (m == 1) {
      m = 0;
      x[1] = v_b;  // exact reset on entering stick
    } else {
      m = 1;
    }
    return TransitionAction::proceed();
  }
  double slip_duration() const {
    return 2.0 * std::acos(-1.0) - 2.0 * std::atan((mu_s - mu_k) / v_b);
  }
  double stick_duration() const { return 2.0 * (mu_s - mu_k) / v_b; }
  /// Exact state at t, from x = 0, x' = v_b in stick at t = 0.
  State exact(double t) const {
    const double first = mu_s / v_b;
    if (t < first) return State(v_b * t, v_b);
    const double period = slip_duration() + stick_duration();
    const double tau = std::fmod(t - first, period);
    const double a = mu_s - mu_k;
    if (tau < slip_duration())
      return State(mu_k + a * std::cos(tau) + v_b * std::sin(tau),
                   -a * std::sin(tau) + v_b * std::cos(tau));
    return State(mu_k - a + v_b * (tau - slip_duration()), v_b);
  }
};

}  // namespace stickslip::test
