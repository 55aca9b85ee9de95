// Tests of compute_modes against closed-form beam frequencies (Euler-Bernoulli theory, e.g.
// Blevins, "Formulas for natural frequency and mode shape", tables 8-1 and 8-16).

#include "beam/beam_test_support.hpp"
#include "stickslip/modal.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

namespace {

using namespace stickslip;
using namespace stickslip_test;

// Roots beta_n L of cos(bL) cosh(bL) = -1 (clamped-free beam).
constexpr std::array<double, 5> kCantileverBetaL{1.875104069, 4.694091133, 7.854757438,
                                                 10.99554073, 14.13716839};

Eigen::VectorXd cantilever_omegas(int elements, ModalSolver solver, int modes = 5,
                                  MassType mass = MassType::Consistent) {
  const auto frame = cantilever(1.0, elements).assemble(mass);
  ModalOptions<double> options;
  options.num_modes = modes;
  options.solver = solver;
  return compute_modes(frame, options).omega();
}

double cantilever_reference(int n, double L = 1.0) {
  const double bl = kCantileverBetaL[static_cast<std::size_t>(n)];
  return bl * bl * bending_unit(slender_steel(), L);
}

TEST(ComputeModes, CantileverFirstFiveBendingFrequenciesWithin0p1Percent) {
  // 20 Hermite elements: the discretisation error of mode 5 (beta h ~ 0.7) is ~1e-4 relative;
  // the task asks for 0.1 %, which leaves a factor ~10 margin.
  for (ModalSolver solver : {ModalSolver::Dense, ModalSolver::Sparse}) {
    const Eigen::VectorXd omega = cantilever_omegas(20, solver);
    for (int n = 0; n < 5; ++n) {
      const double ref = cantilever_reference(n);
      EXPECT_NEAR(omega(n) / ref, 1.0, 1e-3) << "mode " << n + 1 << ", solver " << to_string(solver);
      // The FE frequency of a conforming consistent-mass model is an upper bound (Rayleigh-Ritz).
      EXPECT_GT(omega(n), ref * (1.0 - 1e-12)) << "mode " << n + 1;
    }
  }
}

TEST(ComputeModes, CantileverFrequencyErrorConvergesAtFourthOrder) {
  // Cubic Hermite elements: eigenvalue error O(h^(2(p+1-m))) = O(h^4) for p = 3, m = 2 (Strang
  // & Fix), so frequencies converge at order 4. Meshes 4, 8, 16 keep the error well above
  // round-off (smallest ~1e-7); the order is asymptotic, so mode 3 on the coarse mesh is still
  // pre-asymptotic and gets the 0.3 margin (measured values are printed).
  const int meshes[] = {4, 8, 16};
  for (int mode = 0; mode < 3; ++mode) {
    double err[3];
    for (int k = 0; k < 3; ++k)
      err[k] = cantilever_omegas(meshes[k], ModalSolver::Dense)(mode) / cantilever_reference(mode) - 1.0;
    const double order_fine = std::log2(err[1] / err[2]);
    std::printf("mode %d: rel. errors %.3e %.3e %.3e, orders %.3f %.3f\n", mode + 1, err[0], err[1],
                err[2], std::log2(err[0] / err[1]), order_fine);
    EXPECT_NEAR(order_fine, 4.0, 0.3) << "mode " << mode + 1;
  }
}

}  // namespace
