#pragma once
// Shared by the ExactLinearStepper tests: the guard-free part of a hybrid system with one mode.

#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

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

/// Errors err[i] of steps h, h/2, h/4, ...: each halving must gain the Lawson method's order 5,
/// asserted in [4.5, 6.5] (a first-order splitting error or a wrong tableau entry gives <= 2).
inline void expect_order_five(const std::vector<double>& err, const char* label) {
  for (std::size_t i = 0; i + 1 < err.size(); ++i) {
    const double order = std::log2(err[i] / err[i + 1]);
    std::printf("%s: errors %.3e -> %.3e: order %.2f\n", label, err[i], err[i + 1], order);
    EXPECT_GT(order, 4.5) << label << ", step pair " << i;
    EXPECT_LT(order, 6.5) << label << ", step pair " << i;
  }
}

}  // namespace ode_exact_test
