#pragma once
// Shared by the ExactLinearStepper tests: the guard-free part of a hybrid system with one mode.

#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>

namespace ode_exact_test {

/// No guards, no transitions: a system with a single mode (int) inherits these.
template <class State>
struct Unguarded {
  Eigen::Index num_guards(const int&) const { return 0; }
  void guards(const int&, double, const State&, Eigen::VectorXd&) const {}
  stickslip::CrossingDirection guard_direction(const int&, Eigen::Index) const {
    return stickslip::CrossingDirection::Either;
  }
  stickslip::TransitionAction transition(int&, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    return stickslip::TransitionAction::proceed();
  }
};

}  // namespace ode_exact_test
