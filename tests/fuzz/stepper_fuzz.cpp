// Fuzz harness: HybridStepper (RungeKutta4, DormandPrince54, Rosenbrock23) on a small user system,
// a one-degree-of-freedom stick-slip oscillator written with CoulombContact<CoulombLaw> (the belt /
// Den Hartog oscillator of tests/contact/single_dof_systems.hpp, written again here):
//   m x'' + k x = F0 cos(omega t) + f,  v = x' - v_belt,  N constant,
// stick: v = 0 held exactly (x' = v_belt), f = f_required = k x - F0 cos(omega t).
//
// Layout of an input: m, k, F0, omega, v_belt, N, mu_s, mu_k; method choice(3), event location
// choice(2); fixed_step, rtol, atol, output_interval, min_step; max_steps integer, zeno_max_events
// integer, zeno_window; t0, span (t_end = t0 + span); x0, v0; initial mode choice(3).
//
// Work per input is bounded by max_steps (kept in [1, 20000]; values <= 0 pass to the validation)
// and by the sample count (2e5). Rules checked besides the exception types:
//  * time advances: every accepted step and every sample lies strictly after the previous one
//    (a step that leaves t unchanged is the start of a hang; only a step ending at an event may
//    have zero length), and no more steps than max_steps;
//  * zeno_max_events >= 1e9 is refused (its ring buffer took 8 GB);
//  * Success means t = t_end and a finite state; another status carries a message;
//  * at every event (state after the transition, f_required at the event): a contact that
//    sticks has |f_required| <= mu_s N; a stuck contact starts slipping against f_required; a
//    slip that reverses direction needs |f_required| >= mu_s N (otherwise v reached 0 with the
//    force inside the capacity: a stick read as a reversal). Margins 1e-6 of
//    mu_s N: the event is located to ~1e-12 s, and the force moves by |df/dt| * 1e-12 in that time.
#include "fuzz/fuzz_input.hpp"

#include <stickslip/contact.hpp>
#include <stickslip/ode.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>

namespace stepper_fuzz {

using namespace stickslip;
using stickslip_fuzz::require;
using stickslip_fuzz::str;

struct Parameters {
  double m, k, F0, omega, v_belt, N, mu_s, mu_k;
};

class Oscillator {
 public:
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = ContactState;

  Oscillator(const Parameters& p) : p_(p), contact_(CoulombLaw<double>(p.mu_s, p.mu_k)) {}

  double excitation(double t) const { return p_.F0 * std::cos(p_.omega * t); }
  double velocity(const State& x) const { return x[1] - p_.v_belt; }
  double required(double t, const State& x) const { return p_.k * x[0] - excitation(t); }
  double capacity() const { return p_.mu_s * p_.N; }

  void rhs(const Mode& m, double t, const State& x, State& dxdt) const {
    dxdt[0] = x[1];
    if (m == Mode::Stick) {
      dxdt[1] = 0;
      return;
    }
    const double f = contact_.friction_force(m, velocity(x), p_.N, required(t, x));
    dxdt[1] = (excitation(t) + f - p_.k * x[0]) / p_.m;
  }
  Eigen::Index num_guards(const Mode& m) const { return Contact::num_guards(m, false); }
  void guards(const Mode& m, double t, const State& x, Eigen::VectorXd& g) const {
    contact_.guards(m, velocity(x), p_.N, required(t, x), false, g.data());
  }
  CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    return Contact::guard_direction(m, i, false);
  }
  TransitionAction transition(Mode& m, const TriggeredGuards&, double t, State& x) const {
    m = contact_.decide(m, velocity(x), p_.N, required(t, x));
    if (m == Mode::Stick) x[1] = p_.v_belt;
    if (m == Mode::LiftOff) return TransitionAction::halt("lift-off at t = " + str(t));
    return TransitionAction::proceed();
  }

 private:
  using Contact = CoulombContact<CoulombLaw<double>>;
  Parameters p_;
  Contact contact_;
};

class Checker : public NullObserver {
 public:
  Checker(const Oscillator& sys, double t0, long max_steps)
      : sys_(sys), last_step_(t0), last_sample_(-std::numeric_limits<double>::infinity()),
        max_steps_(max_steps) {}

  bool on_step(double t, const Oscillator::State&, const ContactState&) {
    // A step that ends at an event located at its own start may have zero length.
    require(t > last_step_ || (t == last_step_ && event_since_step_),
            "accepted step did not advance t: " + str(last_step_) + " -> " + str(t));
    last_step_ = t;
    event_since_step_ = false;
    require(++steps_ <= max_steps_, "more accepted steps than max_steps");
    return true;
  }
  bool on_sample(double t, const Oscillator::State&, const ContactState&) {
    require(t > last_sample_, "sample time did not advance: " + str(last_sample_) + " -> " + str(t));
    last_sample_ = t;
    require(++samples_ <= 200000, "more than 2e5 samples (unbounded sampling loop)");
    return true;
  }
  void on_event(const EventRecord<double, ContactState>& r, const Oscillator::State& x) {
    event_since_step_ = true;
    const double f = sys_.required(r.t, x), cap = sys_.capacity();
    if (!(std::isfinite(f) && std::isfinite(cap) && cap > 0)) return;
    const std::string at = std::string(to_string(r.from)) + " -> " + to_string(r.to) + " at t = " +
                           str(r.t) + " with f_required = " + str(f) + ", mu_s N = " + str(cap) +
                           ", v = " + str(sys_.velocity(x));
    if (r.to == ContactState::Stick)
      require(std::abs(f) <= cap * (1 + 1e-6), "stuck beyond the capacity: " + at);
    if (r.from == ContactState::Stick && is_slipping(r.to))
      require(slip_sign(r.to) == (f > 0 ? -1 : 1), "slip from stick along f_required: " + at);
    if (is_slipping(r.from) && is_slipping(r.to) && r.from != r.to)
      require(std::abs(f) >= cap * (1 - 1e-6), "stick read as a velocity reversal: " + at);
  }

 private:
  const Oscillator& sys_;
  double last_step_, last_sample_;
  long max_steps_;
  long steps_ = 0, samples_ = 0;
  bool event_since_step_ = false;
};

template <class Method>
void integrate(Oscillator& sys, const StepperOptions<double>& opt, ContactState mode, double t0,
               const Oscillator::State& x0, double t_end) {
  HybridStepper<Oscillator, Method> stepper(sys, opt);
  // a Zeno cap of 1e9 events cost 8 GB of ring buffer; such caps must be refused
  // by name (checked here, before integrate would allocate).
  require(opt.zeno_max_events < 1000000000L,
          "zeno_max_events = " + std::to_string(opt.zeno_max_events) + " accepted (no stated limit)");
  Checker checker(sys, t0, opt.max_steps);
  const auto r = stepper.integrate(mode, t0, x0, t_end, checker);
  if (r.status == Status::Success) {
    require(r.t == t_end, "Success at t = " + str(r.t) + " != t_end = " + str(t_end));
    require(r.x.allFinite(), "Success with a non-finite state");
  } else {
    require(!r.message.empty(), std::string("status ") + to_string(r.status) + " without a message");
  }
}

void run(stickslip_fuzz::Input& in) {
  Parameters p{};
  p.m = in.real(0.1, 10.0);
  p.k = in.real(0.0, 100.0);
  p.F0 = in.real(0.0, 10.0);
  p.omega = in.real(0.0, 10.0);
  p.v_belt = in.real(-1.0, 1.0);
  p.N = in.real(0.0, 10.0);
  p.mu_s = in.real(0.0, 1.0);
  p.mu_k = in.real(0.0, 1.0);
  const unsigned method = in.choice(3);
  StepperOptions<double> opt;
  opt.event_location = in.flag() ? EventLocation::Bisection : EventLocation::DenseRootFinding;
  opt.fixed_step = in.real(1e-4, 0.5);
  opt.rtol = in.real(1e-10, 1e-2);
  opt.atol = in.real(1e-12, 1e-4);
  opt.output_interval = in.real(0.0, 1.0);
  opt.min_step = in.real(1e-15, 1e-12);
  const long long max_steps = in.integer(1, 20000);
  opt.max_steps = max_steps <= 0 ? static_cast<long>(std::max<long long>(max_steps, -1))
                                 : static_cast<long>(std::min<long long>(max_steps, 20000));
  const long long zeno = in.integer(1, 2000);
  opt.zeno_max_events = static_cast<long>(std::clamp<long long>(
      zeno, std::numeric_limits<long>::min(), std::numeric_limits<long>::max()));
  opt.zeno_window = in.real(0.0, 1e-3);
  const double t0 = in.real(0.0, 10.0), span = in.real(0.0, 20.0);
  const double t_end = t0 + span;
  Oscillator::State x0(in.real(-1.0, 1.0), in.real(-1.0, 1.0));
  const auto mode = static_cast<ContactState>(in.choice(3));
  if (mode == ContactState::Stick) x0[1] = p.v_belt;
  Oscillator sys(p);
  switch (method) {
    case 0: integrate<RungeKutta4>(sys, opt, mode, t0, x0, t_end); break;
    case 1: integrate<DormandPrince54>(sys, opt, mode, t0, x0, t_end); break;
    default: integrate<Rosenbrock23>(sys, opt, mode, t0, x0, t_end); break;
  }
}

}  // namespace stepper_fuzz

STICKSLIP_FUZZ_ENTRY(stepper, stepper_fuzz::run)
