// Checked inputs of the model: state and mode sizes at the entry points and
// the basis' modal damping coefficients, Rayleigh damping of rigid-body modes included.
#include "contact/contact_test_util.hpp"
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>
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

// Enum fields holding a value that is no enumerator (a cast from an integer): a contact with
// initial_state ContactState(5) slid through a MemberEnd::Wall and the run ended Success. Every
// enum that enters the model is refused where it enters, naming the parameter.
TEST(ModelInputs, EnumValuesThatAreNoEnumeratorsAreRefusedNamingTheParameter) {
  const TScene s = make_t_frame(4, 6, 2);
  const auto build = [&](auto change_damper, auto change_load, auto change_options) {
    std::vector<PointDamper<double>> dampers = paper_dampers(s, 10.0);
    std::vector<PointLoad<double>> loads = paper_load(s);
    ModelOptions<double> options;
    change_damper(dampers[1]);
    change_load(loads[0]);
    change_options(options);
    System sys(s.frame, s.basis, dampers, loads, options);
  };
  const auto none = [](auto&) {};
  expect_invalid_argument([&] { build([](auto& d) { d.initial_state = static_cast<ContactState>(5); }, none, none); },
                          {"PointDamper[1]", "initial_state", "ContactState", "5"});
  expect_invalid_argument([&] { build([](auto& d) { d.start_end = static_cast<MemberEnd>(7); }, none, none); },
                          {"PointDamper[1]", "start_end", "MemberEnd", "7"});
  expect_invalid_argument([&] { build([](auto& d) { d.finish_end = static_cast<MemberEnd>(4); }, none, none); },
                          {"PointDamper[1]", "finish_end", "MemberEnd", "4"});
  expect_invalid_argument([&] { build([](auto& d) { d.separation = static_cast<Separation>(2); }, none, none); },
                          {"PointDamper[1]", "separation", "Separation", "2"});
  expect_invalid_argument([&] { build([](auto& d) { d.normal_load = static_cast<NormalLoad>(-1); }, none, none); },
                          {"PointDamper[1]", "normal_load", "NormalLoad", "-1"});
  expect_invalid_argument([&] { build([](auto& d) { d.contact_point = static_cast<ContactPoint>(2); }, none, none); },
                          {"PointDamper[1]", "contact_point", "ContactPoint", "2"});
  expect_invalid_argument([&] { build(none, [](auto& l) { l.direction = static_cast<LoadDirection>(5); }, none); },
                          {"PointLoad[0]", "direction", "LoadDirection", "5"});
  expect_invalid_argument([&] { build(none, none, [](auto& o) { o.normal_load = static_cast<NormalLoad>(2); }); },
                          {"FrictionDampedSystem", "options.normal_load", "NormalLoad", "2"});
  expect_invalid_argument([&] { build(none, none, [](auto& o) { o.end_policy = static_cast<EndPolicy>(3); }); },
                          {"FrictionDampedSystem", "options.end_policy", "EndPolicy", "3"});
  // the last enumerators themselves are accepted
  EXPECT_NO_THROW(build([](auto& d) { d.finish_end = MemberEnd::Wall; d.contact_point = ContactPoint::Moving; },
                        [](auto& l) { l.direction = LoadDirection::Moment; },
                        [](auto& o) { o.end_policy = EndPolicy::Extrapolate; }));

  // The mode: at every entry point (simulate, make_consistent, evaluate), and its walls.
  System sys(s.frame, s.basis, paper_dampers(s, 10.0), paper_load(s));
  System::State x0 = sys.initial_state();
  DamperStates bad = sys.requested_mode();
  bad[1] = static_cast<ContactState>(5);
  expect_invalid_argument([&] { simulate(sys, bad, 0.0, x0, 1e-3); }, {"simulate", "mode[1]", "ContactState", "5"});
  expect_invalid_argument([&] { sys.make_consistent(bad, 0.0, x0); },
                          {"make_consistent", "mode[1]", "ContactState", "5"});
  expect_invalid_argument([&] { sys.evaluate(bad, 0.0, x0); }, {"evaluate", "mode[1]", "ContactState"});
  expect_invalid_argument([&] { DamperStates(2, static_cast<ContactState>(9)); }, {"DamperStates", "state", "9"});
  DamperStates walls(2);
  expect_invalid_argument([&] { walls.set_wall(0, static_cast<WallRest>(3)); }, {"set_wall", "WallRest", "3"});
  RunOptions<double> run;
  run.integrator = static_cast<Integrator>(5);  // (4 is Integrator::Auto)
  expect_invalid_argument([&] { simulate(sys, sys.requested_mode(), 0.0, x0, 1e-3, run); },
                          {"simulate", "options.integrator", "Integrator", "5"});
}

// A run's inputs are checked before the first evaluation and named: a NaN t0 was reported as an
// inconsistent start with t = nan, a non-finite x0 as "MemberShapes::evaluate: eps = nan", a
// LiftOff start mode as a lift-off with N = 4.19, and a load whose time_function returned NaN as
// a lift-off.
TEST(ModelInputs, RunInputsAreCheckedBeforeTheFirstEvaluationAndNamed) {
  const TScene s = make_t_frame(4, 6, 2);
  System sys(s.frame, s.basis, paper_dampers(s, 10.0), paper_load(s));
  const System::State x0 = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid_argument([&] { simulate(sys, mode, nan, x0, 1e-3); }, {"simulate", "t0", "finite", "nan"});
  expect_invalid_argument([&] { simulate(sys, mode, 0.0, x0, nan); }, {"simulate", "t_end", "finite"});
  expect_invalid_argument([&] { simulate(sys, mode, 0.0, x0, -1.0); }, {"simulate", "t_end", ">= t0"});
  System::State bad_x = x0;
  bad_x[sys.contact_offset() + 1] = nan;  // a contact coordinate: the shapes would see it first
  const std::string entry = "x0[" + std::to_string(sys.contact_offset() + 1) + "]";
  expect_invalid_argument([&] { simulate(sys, mode, 0.0, bad_x, 1e-3); }, {"simulate", entry.c_str(), "finite"});
  expect_invalid_argument([&] { sys.make_consistent(mode, nan, bad_x); }, {"make_consistent", "t must be finite"});
  System::State x_copy = bad_x;
  expect_invalid_argument([&] { sys.make_consistent(mode, 0.0, x_copy); }, {"make_consistent", "x[", "finite"});
  DamperStates lifted = mode;
  lifted[0] = ContactState::LiftOff;
  expect_invalid_argument([&] { simulate(sys, lifted, 0.0, x0, 1e-3); }, {"simulate", "mode[0]", "lift_off"});
  expect_invalid_argument([&] { sys.make_consistent(lifted, 0.0, x_copy = x0); }, {"make_consistent", "mode[0]", "lift_off"});

  // A load whose value turns NaN during the run (from t = 2 ms): a NonFiniteState status naming
  // the load, never a lift-off; NaN from the start: make_consistent reports NonFiniteLoad.
  std::vector<PointLoad<double>> loads = paper_load(s);
  loads[0].amplitude = 0;
  loads[0].time_function = [](double t) { return t < 2e-3 ? 20.0 * std::sin(200.0 * t) : std::nan(""); };
  for (Integrator method : {Integrator::DormandPrince54, Integrator::Rosenbrock23, Integrator::Exponential}) {
    System nan_load(s.frame, s.basis, paper_dampers(s, 10.0), loads);
    DamperStates m = nan_load.requested_mode();
    System::State x = nan_load.initial_state();
    ASSERT_TRUE(nan_load.make_consistent(m, 0.0, x));
    RunOptions<double> run;
    run.integrator = method;
    const auto r = simulate(nan_load, m, 0.0, x, 5e-3, run);
    EXPECT_EQ(r.status, Status::NonFiniteState) << to_string(method) << ": " << r.message;
    EXPECT_NE(r.message.find("PointLoad[0] is not finite"), std::string::npos) << to_string(method) << ": " << r.message;
    EXPECT_NE(nan_load.stop_reason(), System::StopReason::LiftOff) << to_string(method);
    EXPECT_LE(r.t, 2e-3) << to_string(method);
  }
  loads[0].time_function = [](double) { return std::nan(""); };
  System nan_start(s.frame, s.basis, paper_dampers(s, 10.0), loads);
  DamperStates m = nan_start.requested_mode();
  System::State x = nan_start.initial_state();
  EXPECT_FALSE(nan_start.make_consistent(m, 0.0, x));
  EXPECT_EQ(nan_start.stop_reason(), System::StopReason::NonFiniteLoad);
  EXPECT_EQ(nan_start.stop_damper(), 0);
}

// Options that can never act are refused: Separate with a constant normal load (N never reaches
// zero) or with lift-off not watched (nothing detects N = 0) was accepted and never separated.
TEST(ModelInputs, SeparationThatCanNeverActIsRefusedNamingTheOption) {
  const TScene s = make_t_frame(4, 6, 2);
  std::vector<PointDamper<double>> dampers = paper_dampers(s, 10.0);
  dampers[1].separation = Separation::Separate;
  EXPECT_NO_THROW(System(s.frame, s.basis, dampers, paper_load(s)));
  ModelOptions<double> options;
  options.watch_lift_off = false;
  expect_invalid_argument([&] { System(s.frame, s.basis, dampers, paper_load(s), options); },
                          {"PointDamper[1]", "separation = Separate", "watch_lift_off"});
  options = {};
  options.normal_load = NormalLoad::Constant;
  expect_invalid_argument([&] { System(s.frame, s.basis, dampers, paper_load(s), options); },
                          {"PointDamper[1]", "separation = Separate", "inertial normal load"});
  dampers[1].normal_load = NormalLoad::Constant;
  expect_invalid_argument([&] { System(s.frame, s.basis, dampers, paper_load(s)); },
                          {"PointDamper[1]", "separation = Separate", "inertial normal load"});
}

}  // namespace
}  // namespace model_inputs_test
