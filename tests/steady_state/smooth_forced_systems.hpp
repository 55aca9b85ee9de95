#pragma once
// Smooth harmonically forced oscillators (one mode, no guards) for the continuation tests:
//   M x'' + C x' + K x + k3 (x .^ 3) = f cos(omega t),   state (x, x').
// With k3 = 0 the linear multi-DOF scene (closed-form receptance); with one DOF and k3 != 0 the
// Duffing oscillator.

#include <stickslip/ode.hpp>

#include <Eigen/Core>
#include <Eigen/LU>  // inverse

#include <cmath>

namespace steady_state_test {

/// The event interface of a smooth system (Mode int, no guards): a base for test systems.
template <class State>
struct WithoutEvents {
  Eigen::Index num_guards(const int&) const { return 0; }
  void guards(const int&, double, const State&, Eigen::Matrix<double, Eigen::Dynamic, 1>&) const {}
  stickslip::CrossingDirection guard_direction(const int&, Eigen::Index) const {
    return stickslip::CrossingDirection::Either;
  }
  stickslip::TransitionAction transition(int&, const stickslip::TriggeredGuards&, double, State&) const {
    return stickslip::TransitionAction::proceed();
  }
};

template <int Dofs>
class ForcedOscillator {
 public:
  using Scalar = double;
  using State = Eigen::Matrix<double, 2 * Dofs, 1>;
  using Mode = int;
  using Square = Eigen::Matrix<double, Dofs, Dofs>;
  using Vector = Eigen::Matrix<double, Dofs, 1>;

  Square M = Square::Identity(), C = Square::Zero(), K = Square::Identity();
  Vector f = Vector::Unit(0);
  double k3 = 0;
  double omega = 1;

  void rhs(const Mode&, double t, const State& x, State& dxdt) const {
    const auto q = x.template head<Dofs>();
    const auto v = x.template tail<Dofs>();
    const Vector force = f * std::cos(omega * t) - C * v - K * q - k3 * q.array().cube().matrix();
    dxdt.template head<Dofs>() = v;
    dxdt.template tail<Dofs>() = M.inverse() * force;  // closed-form inverse for Dofs <= 4
  }
  Eigen::Index num_guards(const Mode&) const { return 0; }
  void guards(const Mode&, double, const State&, Eigen::Matrix<double, Eigen::Dynamic, 1>&) const {}
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Either;
  }
  stickslip::TransitionAction transition(Mode&, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    return stickslip::TransitionAction::proceed();
  }
};

}  // namespace steady_state_test
