#pragma once
// One-degree-of-freedom friction oscillators used to validate CoulombContact with the hybrid
// stepper. They use the contact exactly as a model does: the model computes the sliding velocity,
// the normal force and the stick constraint force; CoulombContact gives the friction force, the
// guards, their directions and the transition decision.
//
//   m x'' + k x = F(t) + f,   F(t) = F_b + F_r t + F_0 cos(omega t + phase)
//   v = x' - v_belt           (the body slides on a surface moving at v_belt; 0 = ground)
//   N(t) = N_0 + N_1 cos(omega_N t)
//
// State (x, x', W, D): W = integral of F x' dt (work of the excitation), D = integral of -f v dt
// (friction dissipation). In stick the model holds v = 0 exactly: x' = v_belt, x'' = 0, and
// f = f_required = k x - F(t) (the force that keeps x'' = 0).

#include <stickslip/contact.hpp>
#include <stickslip/ode.hpp>

#include <Eigen/Core>

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace contact_test {

struct SingleDofParameters {
  double mass = 1.0;             // kg
  double stiffness = 1.0;        // N/m, spring to ground
  double force_amplitude = 0.0;  // F_0, N
  double force_frequency = 1.0;  // omega, rad/s
  double force_phase = 0.0;      // rad
  double force_bias = 0.0;       // F_b, N
  double force_rate = 0.0;       // F_r, N/s
  double belt_speed = 0.0;       // v_belt, m/s
  double normal_force = 1.0;     // N_0, N
  double normal_amplitude = 0.0; // N_1, N
  double normal_frequency = 0.0; // omega_N, rad/s
  bool watch_lift_off = true;
};

template <class Law>
class SingleDofOscillator {
 public:
  using Scalar = double;
  using State = Eigen::Vector4d;
  using Mode = stickslip::ContactState;
  using Contact = stickslip::CoulombContact<Law>;

  SingleDofOscillator(const SingleDofParameters& p, Contact contact) : p_(p), contact_(contact) {}

  const SingleDofParameters& parameters() const { return p_; }
  const Contact& contact() const { return contact_; }

  double excitation(double t) const {
    return p_.force_bias + p_.force_rate * t +
           p_.force_amplitude * std::cos(p_.force_frequency * t + p_.force_phase);
  }
  double normal_force(double t) const {
    return p_.normal_force + p_.normal_amplitude * std::cos(p_.normal_frequency * t);
  }
  double sliding_velocity(const State& x) const { return x[1] - p_.belt_speed; }
  double stick_force_required(double t, const State& x) const {
    return p_.stiffness * x[0] - excitation(t);
  }
  double friction_force(const Mode& m, double t, const State& x) const {
    return contact_.friction_force(m, sliding_velocity(x), normal_force(t),
                                   stick_force_required(t, x));
  }
  double mechanical_energy(const State& x) const {
    return 0.5 * p_.mass * x[1] * x[1] + 0.5 * p_.stiffness * x[0] * x[0];
  }

  // The mode consistent with (t, x): what the contact decides at rest or in motion.
  Mode consistent_mode(double t, const State& x) const {
    return contact_.decide(Mode::Stick, sliding_velocity(x), normal_force(t),
                           stick_force_required(t, x));
  }

  void rhs(const Mode& m, double t, const State& x, State& dxdt) const {
    const double F = excitation(t);
    dxdt[0] = x[1];
    dxdt[2] = F * x[1];
    if (Contact::has_stick_state && m == Mode::Stick) {
      dxdt[1] = 0.0;  // v' = 0 exactly: no creep while stuck
      dxdt[3] = 0.0;  // v = 0: no dissipation
      return;
    }
    const double f = friction_force(m, t, x);
    dxdt[1] = (F + f - p_.stiffness * x[0]) / p_.mass;
    dxdt[3] = -f * sliding_velocity(x);
  }

  // The piecewise-linear form (stickslip/ode/linear_part.hpp) of an exact law with a constant
  // normal force and no force ramp; x_L = (x, x'), quadratures (W, D). Stick: x' = v_belt,
  // x'' = 0. Slip: m x'' = F_b + F_0 cos(omega t + phase) + f_k - k x, with the kinetic force
  // f_k of the slip direction, frozen at (t, x): exact for CoulombLaw (constant mu_k); for other
  // exact laws (mu_k(|v|)) the remainder is the change of f_k, and `exact` is false. False for
  // regularised laws, a force ramp, a varying normal force and lift-off.
  bool linear_part(const Mode& m, double t, const State& x,
                   stickslip::LinearPart<double>& lp) const {
    if (!Contact::has_stick_state || p_.force_rate != 0 || p_.normal_amplitude != 0 ||
        m == Mode::LiftOff)
      return false;
    const Eigen::Index nk = p_.force_amplitude != 0 ? 1 : 0;
    lp.A.setZero(2, 2);
    lp.b0.setZero(2);
    lp.omega.assign(static_cast<std::size_t>(nk), p_.force_frequency);
    lp.bc.setZero(2, nk);
    lp.bs.setZero(2, nk);
    lp.Gx.resize(0, 0);
    lp.exact = true;
    if (m == Mode::Stick) {
      lp.b0[0] = p_.belt_speed;
      lp.version = 1;
      return true;
    }
    lp.A << 0, 1, -p_.stiffness / p_.mass, 0;
    lp.b0[1] = (p_.force_bias + friction_force(m, t, x)) / p_.mass;
    if (nk > 0) {  // cos(w t + phase) = cos(phase) cos(w t) - sin(phase) sin(w t)
      lp.bc(1, 0) = p_.force_amplitude * std::cos(p_.force_phase) / p_.mass;
      lp.bs(1, 0) = -p_.force_amplitude * std::sin(p_.force_phase) / p_.mass;
    }
    lp.exact = std::is_same_v<Law, stickslip::CoulombLaw<double>>;
    lp.version = lp.exact ? (m == Mode::SlipPositive ? 2 : 3) : lp.version + 2;
    return true;
  }

  Eigen::Index num_guards(const Mode& m) const {
    return Contact::num_guards(m, p_.watch_lift_off);
  }
  void guards(const Mode& m, double t, const State& x,
              Eigen::Matrix<double, Eigen::Dynamic, 1>& g) const {
    // The stick force (an excitation evaluation) is computed in stick only.
    contact_.guards(m, sliding_velocity(x), normal_force(t),
                    [&] { return stick_force_required(t, x); }, p_.watch_lift_off, g.data());
  }
  stickslip::CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    return Contact::guard_direction(m, i, p_.watch_lift_off);
  }
  stickslip::TransitionAction transition(Mode& m, const stickslip::TriggeredGuards& which, double t,
                                         State& x) const {
    const double N = normal_force(t);
    const double f_required = stick_force_required(t, x);
    // A slip state whose velocity guard fired is at v = 0 as located (the stepper hands over a
    // state on the guard's surface): decide without reading the leftover of v.
    m = Contact::velocity_guard_fired(m, which)
            ? contact_.decide_at_rest(N, f_required)
            : contact_.decide(m, sliding_velocity(x), N, f_required);
    if (Contact::has_stick_state && m == Mode::Stick) x[1] = p_.belt_speed;  // onto v = 0
    if (m == Mode::LiftOff)
      return stickslip::TransitionAction::halt("lift-off: normal force " + std::to_string(N) +
                                               " <= 0");
    return stickslip::TransitionAction::proceed();
  }

 private:
  SingleDofParameters p_;
  Contact contact_;
};

// Observer recording every event (time, modes, state after the transition) and, optionally,
// every accepted step and sample.
struct EventLog : stickslip::NullObserver {
  struct Event {
    double t;
    stickslip::ContactState from, to;
    Eigen::Vector4d x;
  };
  std::vector<Event> events;

  void on_event(const stickslip::EventRecord<double, stickslip::ContactState>& r,
                const Eigen::Vector4d& x) {
    events.push_back({r.t, r.from, r.to, x});
  }
};

}  // namespace contact_test
