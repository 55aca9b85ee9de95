#pragma once
// Shared helpers of the moving_load tests: seeded random member data and an Eigen comparison.

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <sstream>

#include "stickslip/moving_load/member_nodal_modes.hpp"

namespace stickslip {
namespace test {

/// EXPECT that a and b have the same size and max |a - b| <= tol; prints the difference.
#define EXPECT_EIGEN_NEAR(a, b, tol) EXPECT_PRED_FORMAT3(::stickslip::test::eigen_near, a, b, tol)

template <class A, class B, class T>
::testing::AssertionResult eigen_near(const char* ea, const char* eb, const char*, const A& a,
                                      const B& b, T tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    return ::testing::AssertionFailure() << ea << " is " << a.rows() << "x" << a.cols() << ", "
                                         << eb << " is " << b.rows() << "x" << b.cols();
  const double diff = a.size() == 0 ? 0.0 : static_cast<double>((a - b).cwiseAbs().maxCoeff());
  if (diff <= static_cast<double>(tol)) return ::testing::AssertionSuccess();
  std::ostringstream os;
  os.precision(17);
  os << "max |" << ea << " - " << eb << "| = " << diff << " > " << tol << "\n"
     << ea << " = " << a.transpose() << "\n" << eb << " = " << b.transpose();
  return ::testing::AssertionFailure() << os.str();
}

/// Random member data: `elements` elements of random lengths in [0.5, 1.5] * L / elements
/// (rescaled so the last station is exactly `length`), random nodal components in [-1, 1]
/// (theta scaled by 1/length so slopes and displacements are of similar size), random direction.
inline MemberNodalModes<double> random_member(std::mt19937_64& rng, Eigen::Index elements,
                                              Eigen::Index modes, double length,
                                              Eigen::Index member_id = 0) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), size(0.5, 1.5), angle(-3.14, 3.14);
  MemberNodalModes<double> d;
  d.member = member_id;
  d.stations.resize(elements + 1);
  d.stations(0) = 0.0;
  for (Eigen::Index k = 1; k <= elements; ++k) d.stations(k) = d.stations(k - 1) + size(rng);
  d.stations *= length / d.stations(elements);
  d.stations(elements) = length;
  const auto fill = [&](Eigen::MatrixXd& m, double scale) {
    m.resize(elements + 1, modes);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = scale * unit(rng);
  };
  fill(d.u, 1.0);
  fill(d.w, 1.0);
  fill(d.theta, 1.0 / length);
  const double phi = angle(rng);
  d.cos = std::cos(phi);
  d.sin = std::sin(phi);
  return d;
}

/// A fixed seed, printed so that a failure can be reproduced.
inline std::uint64_t announced_seed(std::uint64_t seed) {
  std::cout << "[ seed     ] " << seed << std::endl;
  return seed;
}

}  // namespace test
}  // namespace stickslip
