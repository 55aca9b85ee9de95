// Checked inputs of the model (issue #18): state and mode sizes at the entry points (item 7) and
// the basis' modal damping coefficients, Rayleigh damping of rigid-body modes included (item 10).
#include "contact/contact_test_util.hpp"
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace model_inputs_test {  // named: the model test files share one (unity) translation unit
namespace {

using namespace model_test;
using contact_test::expect_invalid_argument;

// Item 7: a state of the wrong size read past the heap buffer (Release) and a DamperStates with
// the wrong damper count ran to Success with wrong physics. Both are now rejected with the
// expected and the given sizes, before any step of simulate() and at every solve.
TEST(ModelInputs, WrongStateOrModeSizeIsRejectedWithBothSizes) {
  const TScene s = make_t_frame(4, 6, 2);
  System sys(s.frame, s.basis, paper_dampers(s, 10.0), paper_load(s));
  const System::State x0 = sys.initial_state();
  const std::string expected = std::to_string(sys.state_size());
  RunOptions<double> run;
  NullObserver observer;

  const System::State short_x = x0.head(x0.size() - 3);
  expect_invalid_argument([&] { simulate(sys, sys.requested_mode(), 0.0, short_x, 1e-3, run, observer); },
                 {"simulate", "state x", std::to_string(short_x.size()).c_str(), expected.c_str()});
  expect_invalid_argument([&] { simulate(sys, DamperStates(1), 0.0, x0, 1e-3, run, observer); },
                 {"simulate", "mode", "1 states", "num_dampers() = 2"});

  // Directly through the hybrid-system interface (what HybridStepper calls): rhs and
  // make_consistent. A longer state is used here so that the unchecked code did not read past
  // the buffer (it returned silently instead).
  System::State long_x = System::State::Zero(x0.size() + 2), dxdt;
  expect_invalid_argument([&] { sys.rhs(sys.requested_mode(), 0.0, long_x, dxdt); },
                 {"FrictionDampedSystem::evaluate", std::to_string(long_x.size()).c_str(), expected.c_str()});
  DamperStates three(3);
  System::State x = x0;
  expect_invalid_argument([&] { sys.make_consistent(three, 0.0, x); },
                 {"FrictionDampedSystem::make_consistent", "3 states", "num_dampers() = 2"});

  // The right sizes still run.
  EXPECT_TRUE(simulate(sys, sys.requested_mode(), 0.0, x0, 1e-3, run, observer).ok());
}

// Item 10: the model recomputed the damping as 2 zeta omega, which is 0 for a rigid-body mode, so
// Rayleigh damping alpha M lost its effect on rigid motion. A free-free beam has three rigid-body
// modes (omega = 0): with C = alpha M each obeys q'' + alpha q' = 0, so from q(0) = 0, q'(0) = v
// the closed form is q'(t) = v e^{-alpha t}, q(t) = v (1 - e^{-alpha t}) / alpha.
TEST(ModelInputs, RayleighAlphaDampsRigidBodyModesAsExpMinusAlphaT) {
  FrameModel<double> frame;
  const SectionProperties<double> sec{2.06e11, 7800.0, 6e-5, 2e-11};
  const Index a = frame.add_node(0.0, 0.0), b = frame.add_node(0.2, 0.0);
  const Index member = frame.add_member(a, b, sec, 4);
  ModalOptions<double> mo;
  mo.num_modes = 4;
  const double alpha = 10.0;
  const ModalBasis<double> basis = compute_modes(frame.assemble(), mo).with_rayleigh_damping(alpha, 0.0);
  ASSERT_EQ(basis.num_rigid_body_modes(), 3);

  // One frictionless, unpressed damper (mu = 0, no stick state, constant normal load N0 = 0) at
  // a fixed contact: it exerts no force on the beam, so the modal equations stay decoupled.
  ModelOptions<double> options;
  options.moving_contact = false;
  options.normal_load = NormalLoad::Constant;
  std::vector<PointDamper<double>> dampers;
  dampers.emplace_back(member, 0.1, 0.01, 1e3, 0.0, RegularisedLaw<double>(0.0, 1e-3), 0.5);
  System sys(frame, basis, dampers, {}, options);

  // The system's linear rates include -alpha for each damped rigid-body mode.
  int rigid_rates = 0;
  for (const auto& r : sys.linear_rates()) rigid_rates += (r.real() == -alpha && r.imag() == 0.0);
  EXPECT_EQ(rigid_rates, 3);

  System::State x0 = sys.initial_state();
  const double v[3] = {1e-2, -5e-3, 2e-3};
  for (Index j = 0; j < 3; ++j) x0[sys.qd_offset() + j] = v[j];
  RunOptions<double> run;
  run.stepper.rtol = 1e-10;
  run.stepper.atol = 1e-14;
  NullObserver observer;
  const double t_end = 0.3;  // 3 time constants: e^{-3} = 0.05
  const auto result = simulate(sys, sys.requested_mode(), 0.0, x0, t_end, run, observer);
  ASSERT_TRUE(result.ok()) << result.message;
  const double decay = std::exp(-alpha * t_end);
  for (Index j = 0; j < 3; ++j) {
    // Tolerance: the adaptive 5(4) pair at rtol 1e-10 over ~dozens of steps keeps the global
    // error of this smooth decay far below 1e-8 relative; the bug (no decay) is off by a factor 20.
    EXPECT_NEAR(result.x[sys.qd_offset() + j], v[j] * decay, 1e-8 * std::abs(v[j])) << "mode " << j;
    EXPECT_NEAR(result.x[sys.q_offset() + j], v[j] * (1 - decay) / alpha, 1e-8 * std::abs(v[j]) / alpha)
        << "mode " << j;
  }
  // The energy audit's viscous dissipation uses the same c_j: the balance closes (relative to
  // the initial kinetic energy, at the integrator's tolerance).
  const double E0 = sys.mechanical_energy(sys.requested_mode(), 0.0, x0);
  const auto balance = sys.energy_balance(result.mode, result.t, result.x, E0);
  EXPECT_NEAR(balance.residual, 0.0, 1e-7 * E0);
}

}  // namespace
}  // namespace model_inputs_test
