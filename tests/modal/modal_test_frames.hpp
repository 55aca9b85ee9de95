#pragma once
// Shared frames and checks of the modal tests.

#include "stickslip/beam.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <utility>
#include <string>

namespace stickslip_test {

/// One node without members carrying m = 2 kg, J = 0.5 kg m^2 and grounded springs
/// k_X = 800 N/m, k_Y = 1800 N/m, k_Rz = 50 N m/rad: three uncoupled oscillators with
/// omega = sqrt(k/m) = 20, 30 and 10 rad/s exactly (K = diag(800, 1800, 50), M = diag(2, 2, 0.5)).
inline stickslip::FrameModel<double> grounded_oscillators() {
  stickslip::FrameModel<double> model;
  const auto n = model.add_node(0.3, 0.4);
  model.add_point_mass(n, 2.0);
  model.add_rotary_inertia(n, 0.5);
  model.add_spring(n, stickslip::Dof::X, 800.0);
  model.add_spring(n, stickslip::Dof::Y, 1800.0);
  model.add_spring(n, stickslip::Dof::Rz, 50.0);
  return model;
}

/// The paper's blade-platform T-frame (section 4): blade 0.2 m clamped at the root, platform
/// 0.04 m centred on the blade tip, E = 2.06e11 Pa, rho = 7800 kg/m^3, A = 6e-5 m^2,
/// I = 2e-11 m^4; 20 + 2 x 4 elements.
struct BladePlatformFrame {
  stickslip::FrameModel<double> model;
  decltype(std::declval<stickslip::FrameModel<double>&>().add_node(0.0, 0.0)) tip;
  stickslip::SectionProperties<double> section{2.06e11, 7800.0, 6e-5, 2e-11};
};

inline BladePlatformFrame blade_platform_frame() {
  BladePlatformFrame f;
  auto& m = f.model;
  const auto root = m.add_node(0.0, 0.0);
  f.tip = m.add_node(0.0, 0.2);
  const auto left = m.add_node(-0.02, 0.2), right = m.add_node(0.02, 0.2);
  m.add_member(root, f.tip, f.section, 20);
  m.add_member(left, f.tip, f.section, 4);
  m.add_member(f.tip, right, f.section, 4);
  m.clamp(root);
  return f;
}

/// Expect `statement` to throw std::domain_error whose what() contains `fragment`.
#define EXPECT_DOMAIN_ERROR(statement, fragment)                                             \
  do {                                                                                        \
    try {                                                                                     \
      statement;                                                                              \
      ADD_FAILURE() << "expected std::domain_error from: " #statement;                       \
    } catch (const std::domain_error& e) {                                                   \
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)                      \
          << "message \"" << e.what() << "\" lacks \"" << (fragment) << "\"";                  \
    }                                                                                         \
  } while (false)

}  // namespace stickslip_test
