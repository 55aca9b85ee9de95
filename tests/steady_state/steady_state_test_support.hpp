#pragma once
// Helpers shared by the steady-state tests.

#include "contact/single_dof_systems.hpp"

#include <stickslip/steady_state.hpp>

#include <gtest/gtest.h>

#include <Eigen/Core>

namespace steady_state_test {

using Law = stickslip::CoulombLaw<double>;
using Oscillator = contact_test::SingleDofOscillator<Law>;
using Contact = stickslip::CoulombContact<Law>;
using S = stickslip::ContactState;
using Matrix = Eigen::MatrixXd;

// Shooting options for the single-DOF oscillators: (x, x') periodic, the quadratures (W, D) not.
inline stickslip::ShootingOptions<double> oscillator_options() {
  stickslip::ShootingOptions<double> o;
  o.periodic = stickslip::ShootingOptions<double>::first(2);
  return o;
}

// Sizes equal and max |a - b| <= tol, printing both.
inline void expect_matrix_near(const Matrix& a, const Matrix& b, double tol, const char* what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), tol) << what << "\n" << a << "\nvs\n" << b;
}

}  // namespace steady_state_test
