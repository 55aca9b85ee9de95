// The usage example of docs/modal.md, compiled and run (keep the two in sync).

#include <gtest/gtest.h>

// --- begin docs/modal.md example ---
#include <stickslip/beam.hpp>
#include <stickslip/modal.hpp>

#include <iostream>

double blade_platform_first_frequency_hz() {
  using namespace stickslip;
  const SectionProperties<double> steel{2.06e11, 7800.0, 6e-5, 2e-11};  // E, rho, A, I
  FrameModel<double> model;
  const auto root = model.add_node(0.0, 0.0);
  const auto tip = model.add_node(0.0, 0.2);
  const auto left = model.add_node(-0.02, 0.2), right = model.add_node(0.02, 0.2);
  model.add_member(root, tip, steel, 20);  // blade, 20 elements
  model.add_member(left, tip, steel, 4);   // platform wings, rigidly joined at the tip
  model.add_member(tip, right, steel, 4);
  model.clamp(root);

  const AssembledFrame<double> frame = model.assemble();  // sparse K, M over free DOFs
  ModalOptions<double> options;
  options.num_modes = 6;
  const ModalBasis<double> modes = compute_modes(frame, options).with_rayleigh_damping(0.0, 1e-5);

  std::cout << "f1 = " << modes.frequencies_hz()(0) << " Hz, tip X in mode 1: "
            << modes.nodal(tip, Dof::X)(0) << '\n';
  return modes.frequencies_hz()(0);
}
// --- end docs/modal.md example ---

TEST(UsageExample, RunsAndGivesTheBladeFrequency) {
  // The rigid-platform estimate is 30.80 Hz (compute_modes_test.cpp); 0.1 %.
  EXPECT_NEAR(blade_platform_first_frequency_hz() / 30.797, 1.0, 1e-3);
}
