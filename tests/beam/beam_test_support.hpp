#pragma once
// Shared helpers of the beam and modal tests: reference sections, small frame builders and an
// exception-message check.

#include "stickslip/beam.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace stickslip_test {

using stickslip::Dof;
using stickslip::FrameModel;
using Section = stickslip::SectionProperties<double>;

/// Steel strip, slender enough (L/r ~ 316 for L = 1 m) that the first axial frequency of a 1 m
/// cantilever (8.2e3 rad/s) lies above its fifth bending frequency (3.3e3 rad/s).
inline Section slender_steel() { return Section{2.1e11, 7800.0, 1e-4, 1e-9}; }

/// sqrt(EI / (rho A L^4)) [rad/s], the bending frequency unit of a beam of length L.
inline double bending_unit(const Section& s, double L) {
  return std::sqrt(s.E * s.I / (s.rho * s.A * L * L * L * L));
}

/// A cantilever of length L along the direction (cos a, sin a) from the origin, clamped at node
/// 0, tip at node 1, meshed into n equal elements.
inline FrameModel<double> cantilever(double L, int n, const Section& s = slender_steel(),
                                     double angle = 0.0) {
  FrameModel<double> model;
  const auto root = model.add_node(0.0, 0.0);
  const auto tip = model.add_node(L * std::cos(angle), L * std::sin(angle));
  model.add_member(root, tip, s, n);
  model.clamp(root);
  return model;
}

/// Expect `statement` to throw std::invalid_argument whose what() contains `fragment`.
#define EXPECT_INVALID_ARGUMENT(statement, fragment)                                          \
  do {                                                                                        \
    try {                                                                                     \
      statement;                                                                              \
      ADD_FAILURE() << "expected std::invalid_argument from: " #statement;                    \
    } catch (const std::invalid_argument& e) {                                                \
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)                      \
          << "message \"" << e.what() << "\" lacks \"" << (fragment) << "\"";                  \
    }                                                                                         \
  } while (false)

}  // namespace stickslip_test
