// No heap allocation per step: the number of allocations of a run does not grow with the number
// of steps and events (global operator new is counted in this executable only, and so are Eigen's
// own heap allocations, which go to std::malloc, not operator new).

// Eigen's allocation check (EIGEN_RUNTIME_NO_MALLOC) with malloc "forbidden" calls eigen_assert
// with a message naming the heap allocation at every Eigen allocation: count those instead of
// failing; any other failed Eigen assertion still aborts. Must precede every Eigen include.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
namespace stickslip_test {
inline std::atomic<long> g_eigen_allocations{0};
inline void eigen_assertion(bool ok, const char* text) {
  if (ok) return;
  if (std::strstr(text, "heap allocation is forbidden") != nullptr) {
    ++g_eigen_allocations;
    return;
  }
  std::fprintf(stderr, "Eigen assertion failed: %s\n", text);
  std::abort();
}
}  // namespace stickslip_test
#define EIGEN_RUNTIME_NO_MALLOC
#define eigen_assert(x) ::stickslip_test::eigen_assertion(static_cast<bool>(x), #x)

#include <stickslip/ode.hpp>
// ExactLinearStepper's allocation test is left out of the sanitizer build: it doubles this unit's
// compile time there (33 -> 87 s under Clang's ASan) and the sanitizers check that stepper's memory
// use in ode_exact_test; an allocation count does not depend on the sanitizer.
#ifndef STICKSLIP_SANITIZED
#include <stickslip/ode/exact_linear_stepper.hpp>
#endif

#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "ode/ode_test_systems.hpp"

namespace {
// Every heap allocation: operator new and Eigen's (counted once Eigen's check is switched on).
struct AllAllocations {
  long load() const {
    return stickslip_test::g_allocations.load() + stickslip_test::g_eigen_allocations.load();
  }
} const g_allocations;
// Eigen reports its allocations from here on (the flag is read at each allocation).
const bool g_eigen_counting = [] {
  Eigen::internal::set_is_malloc_allowed(false);
  return true;
}();
}  // namespace

namespace {

using stickslip::HybridStepper;
using stickslip::StepperOptions;

template <class Method, class System>
long allocations_of_run(System& sys, const typename System::State& x0, double t_end,
                        stickslip::EventLocation loc, long& steps, long& events) {
  StepperOptions<double> opt;
  opt.event_location = loc;
  opt.fixed_step = 1e-3;
  opt.output_interval = 0.01;
  HybridStepper<System, Method> stepper(sys, opt);
  stepper.integrate(0, 0.0, x0, 0.01);  // sizes the workspace
  const long before = g_allocations.load();
  const auto r = stepper.integrate(0, 0.0, x0, t_end);
  const long count = g_allocations.load() - before;
  EXPECT_EQ(r.status, stickslip::Status::Success) << r.message;
  steps = r.stats.accepted_steps;
  events = r.stats.events;
  return count;
}

template <class Method>
void expect_allocations_independent_of_run_length() {
  stickslip::test::BouncingBall ball;  // fixed-size state (Vector2d)
  ball.restitution = 0.9;
  for (auto loc : {stickslip::EventLocation::DenseRootFinding, stickslip::EventLocation::Bisection}) {
    long s1 = 0, e1 = 0, s2 = 0, e2 = 0;
    const Eigen::Vector2d x0(1.0, 0.0);
    const long short_run = allocations_of_run<Method>(ball, x0, 1.0, loc, s1, e1);
    const long long_run = allocations_of_run<Method>(ball, x0, 8.0, loc, s2, e2);
    EXPECT_GT(s2, 4 * s1);
    EXPECT_GT(e2, 4 * e1);
    EXPECT_EQ(short_run, long_run) << Method::name << ", steps " << s1 << " vs " << s2;
  }
}

TEST(NoAllocationPerStep, RungeKutta4) { expect_allocations_independent_of_run_length<stickslip::RungeKutta4>(); }
TEST(NoAllocationPerStep, DormandPrince54) {
  expect_allocations_independent_of_run_length<stickslip::DormandPrince54>();
}
TEST(NoAllocationPerStep, Rosenbrock23) {
  expect_allocations_independent_of_run_length<stickslip::Rosenbrock23>();
}

TEST(NoAllocationPerStep, Rosenbrock23Reuse) {
  expect_allocations_independent_of_run_length<stickslip::Rosenbrock23Reuse>();
}

// Stick has two guards, slip one; every event changed the guard count and
// reallocated the stepper's guard vectors and the guard monitor's arrays. After a first run that
// has visited both counts, runs of any length allocate the same (nothing per event).
template <class Method>
void expect_no_allocation_per_mode_change(stickslip::EventLocation loc) {
  stickslip::test::StickSlipBelt belt;
  StepperOptions<double> opt;
  opt.event_location = loc;
  opt.fixed_step = 1e-2;
  HybridStepper<stickslip::test::StickSlipBelt, Method> stepper(belt, opt);
  const Eigen::Vector2d x0(0.0, belt.v_b);
  stepper.integrate(0, 0.0, x0, 10.0);  // stick, slip, stick: both guard counts seen
  auto allocations = [&](double t_end, long& events) {
    const long before = g_allocations.load();
    const auto r = stepper.integrate(0, 0.0, x0, t_end);
    const long count = g_allocations.load() - before;
    EXPECT_TRUE(r.ok()) << r.message;
    events = r.stats.events;
    return count;
  };
  long e1 = 0, e2 = 0;
  const long short_run = allocations(10.0, e1);
  const long long_run = allocations(100.0, e2);
  EXPECT_GT(e2, 4 * e1);
  EXPECT_EQ(short_run, long_run) << Method::name << ", events " << e1 << " vs " << e2;
}

TEST(NoAllocationPerEvent, GuardCountChangesBetweenModes) {
  for (auto loc : {stickslip::EventLocation::DenseRootFinding, stickslip::EventLocation::Bisection}) {
    expect_no_allocation_per_mode_change<stickslip::RungeKutta4>(loc);
    expect_no_allocation_per_mode_change<stickslip::DormandPrince54>(loc);
    expect_no_allocation_per_mode_change<stickslip::Rosenbrock23>(loc);
  }
}

TEST(NoAllocationPerStep, DynamicStateAllocatesOnlyPerRun) {
  // A dynamic-size linear system (4 states): the run's allocations (result, workspace reuse)
  // do not depend on how many steps it takes.
  stickslip::test::LinearSystem<Eigen::Dynamic> sys;
  sys.a = Eigen::MatrixXd::Zero(4, 4);
  sys.a.topRightCorner(2, 2).setIdentity();
  sys.a.bottomLeftCorner(2, 2) = -4.0 * Eigen::Matrix2d::Identity();
  const Eigen::VectorXd x0 = Eigen::VectorXd::Ones(4);
  long s1 = 0, e1 = 0, s2 = 0, e2 = 0;
  const auto loc = stickslip::EventLocation::DenseRootFinding;
  const long a1 = allocations_of_run<stickslip::Rosenbrock23>(sys, x0, 1.0, loc, s1, e1);
  const long a2 = allocations_of_run<stickslip::Rosenbrock23>(sys, x0, 10.0, loc, s2, e2);
  EXPECT_GT(s2, 4 * s1);
  EXPECT_EQ(a1, a2);
  // Rosenbrock23Reuse adds the linearisation check (a matrix-vector product) to each step.
  const long c1 = allocations_of_run<stickslip::Rosenbrock23Reuse>(sys, x0, 1.0, loc, s1, e1);
  const long c2 = allocations_of_run<stickslip::Rosenbrock23Reuse>(sys, x0, 10.0, loc, s2, e2);
  EXPECT_GT(s2, 4 * s1);
  EXPECT_EQ(c1, c2);
  const long b1 = allocations_of_run<stickslip::DormandPrince54>(sys, x0, 1.0, loc, s1, e1);
  const long b2 = allocations_of_run<stickslip::DormandPrince54>(sys, x0, 10.0, loc, s2, e2);
  EXPECT_GT(s2, 4 * s1);
  EXPECT_EQ(b1, b2);
}


#ifndef STICKSLIP_SANITIZED
// ExactLinearStepper: an oscillator whose stiffness follows a drifting point X, as a
// slipping contact's does, x'' = -w^2 (1 + a X) x, X' = v, with a guard on x (every zero
// crossing an event that keeps the mode). Its linear part freezes X (A_m changes at every
// refresh, exact = false: Lawson steps under error control, so step lengths vary), samples come
// from the dense output (a backward propagator exp(-h Â) per new step length), events are located
// on it. Every new length or Â costs Padé exponentials; they and everything else must reuse the
// stepper's workspace: after a first run, a run 5x longer (more steps, refreshes, exponentials
// and events) allocates exactly as much (the result's own vectors and message).
class DriftingStiffness {
 public:
  using Scalar = double;
  using State = Eigen::Vector3d;
  using Mode = int;
  static constexpr double w = 40.0, a = 0.5, v = 0.05;

  void rhs(const Mode&, double, const State& x, State& dxdt) const {
    dxdt << x[1], -w * w * (1 + a * x[2]) * x[0], v;
  }
  bool linear_part(const Mode&, double, const State& x, stickslip::LinearPart<double>& lp) {
    lp.A.setZero(3, 3);
    lp.A(0, 1) = 1;
    lp.A(1, 0) = -w * w * (1 + a * x[2]);
    lp.b0.setZero(3);
    lp.b0[2] = v;
    lp.omega.clear();
    lp.exact = false;
    lp.version = ++version_;
    return true;
  }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const { g[0] = x[0]; }
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Either;
  }
  stickslip::TransitionAction transition(Mode&, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    return stickslip::TransitionAction::proceed();
  }

 private:
  std::uint64_t version_ = 0;
};

struct SampleCount : stickslip::NullObserver {
  long samples = 0;
  bool on_sample(double, const Eigen::Vector3d&, const int&) {
    ++samples;
    return true;
  }
};

TEST(NoAllocationPerStep, ExactLinearStepperLawsonStepsSamplesEventsAndRefreshes) {
  DriftingStiffness sys;
  StepperOptions<double> opt;
  opt.rtol = 1e-8;
  opt.atol = 1e-12;
  opt.output_interval = 0.013;
  stickslip::ExactLinearStepper<DriftingStiffness> stepper(sys, opt);
  const Eigen::Vector3d x0(1e-2, 0.0, 0.0);
  SampleCount log;
  stepper.integrate(0, 0.0, x0, 2.0, log);  // sizes the workspace
  struct Run {
    long allocations, steps, events, exponentials, refreshes, samples;
  };
  const auto run = [&](double t_end) {
    log.samples = 0;
    const long count_before = g_allocations.load();
    const auto r = stepper.integrate(0, 0.0, x0, t_end, log);
    const long count = g_allocations.load() - count_before;
    EXPECT_TRUE(r.ok()) << r.message;
    return Run{count, r.stats.accepted_steps, r.stats.events,
               stepper.work().propagator_exponentials, stepper.work().linear_part_refreshes,
               log.samples};
  };
  const Run short_run = run(2.0), long_run = run(10.0);
  std::printf("ExactLinearStepper: %ld / %ld allocations, %ld / %ld steps, %ld / %ld events, "
              "%ld / %ld Padé exponentials, %ld / %ld refreshes, %ld / %ld samples\n",
              short_run.allocations, long_run.allocations, short_run.steps, long_run.steps,
              short_run.events, long_run.events, short_run.exponentials, long_run.exponentials,
              short_run.refreshes, long_run.refreshes, short_run.samples, long_run.samples);
  EXPECT_GT(long_run.steps, 4 * short_run.steps);
  EXPECT_GT(long_run.events, 4 * short_run.events);
  EXPECT_GT(long_run.exponentials, 4 * short_run.exponentials);
  EXPECT_GT(long_run.refreshes, 4 * short_run.refreshes);
  EXPECT_EQ(short_run.allocations, long_run.allocations);
}
#endif  // STICKSLIP_SANITIZED
}  // namespace
