#pragma once
// A point mass on a surface that moves normally, with contact that opens and closes: the test
// system of the Separated state, the gap guard and NewtonImpact. It uses the contact exactly as a
// model does (CoulombContact for the contact states, NewtonImpact and coulomb_impulse at impact).
//
//   normal (y, up):      m y'' = -m g + N,  surface w(t) = A sin(Omega t + phase)
//   tangential (x):      m x'' = f          (the surface does not move tangentially)
//   in contact:          y = w, y' = w', N = m (g + w''(t)),  f from CoulombContact (f_required = 0)
//   separated:           N = 0, f = 0, gap y - w >= 0 (guard, Falling: impact)
//
// State (x, x', y, y', D_impact, D_friction, W_surface): D_impact sums the kinetic energy lost in
// impacts (normal and tangential), D_friction = int -f x' dt, W_surface the work of the surface on
// the body (int N y' dt, plus L w' per impact). Energy balance:
//   m (x'^2 + y'^2)/2 + m g y + D_impact + D_friction - W_surface = const.

#include <stickslip/contact.hpp>
#include <stickslip/ode.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace contact_test {

struct BouncingMassParameters {
  double mass = 1.0;         // kg
  double gravity = 9.81;     // m/s^2, the acceleration pressing the mass onto the surface
  double amplitude = 0.0;    // A, m (0: a rigid plate at rest)
  double frequency = 1.0;    // Omega, rad/s
  double phase = 0.0;        // rad
  bool record_apex = false;  // a guard y' (Falling) in flight records the apex (once per flight)
};

template <class Law>
class BouncingMass {
 public:
  using Scalar = double;
  using State = Eigen::Matrix<double, 7, 1>;
  using Mode = stickslip::ContactState;
  using Contact = stickslip::CoulombContact<Law>;
  using Impact = stickslip::NewtonImpact<double>;

  struct ImpactRecord {
    double t;
    double v_n;      // relative normal velocity before
    double impulse;  // normal impulse
    bool lands;
  };
  struct Point {
    double t, y;
  };

  BouncingMass(const BouncingMassParameters& p, Contact contact, Impact impact)
      : p_(p), contact_(std::move(contact)), impact_(impact) {}

  std::vector<ImpactRecord> impacts;
  std::vector<Point> apexes;
  std::vector<double> lift_offs;
  long bounces = 0, landings = 0;

  double w(double t) const { return p_.amplitude * std::sin(p_.frequency * t + p_.phase); }
  double w_dot(double t) const {
    return p_.amplitude * p_.frequency * std::cos(p_.frequency * t + p_.phase);
  }
  double w_ddot(double t) const {
    return -p_.amplitude * p_.frequency * p_.frequency * std::sin(p_.frequency * t + p_.phase);
  }
  double normal_force(double t) const { return p_.mass * (p_.gravity + w_ddot(t)); }
  double energy(const State& x) const {
    return 0.5 * p_.mass * (x[1] * x[1] + x[3] * x[3]) + p_.mass * p_.gravity * x[2];
  }
  // Energy balance residual (constant in time): see the file comment.
  double balance(const State& x) const { return energy(x) + x[4] + x[5] - x[6]; }

  // At rest on the surface at t (in contact, stuck).
  State on_surface(double t) const {
    State x = State::Zero();
    x[2] = w(t);
    x[3] = w_dot(t);
    return x;
  }

  void rhs(const Mode& m, double t, const State& x, State& dxdt) const {
    dxdt.setZero();
    dxdt[0] = x[1];
    dxdt[2] = x[3];
    if (!stickslip::is_in_contact(m)) {
      dxdt[3] = -p_.gravity;
      return;
    }
    const double N = normal_force(t);
    dxdt[3] = w_ddot(t);  // the constraint y = w
    dxdt[6] = N * x[3];
    if (m == Mode::Stick) return;  // x' = 0 held
    const double f = contact_.friction_force(m, x[1], N, 0.0);
    dxdt[1] = f / p_.mass;
    dxdt[5] = -f * x[1];
  }

  Eigen::Index num_guards(const Mode& m) const {
    if (m == Mode::Separated) return p_.record_apex ? 2 : 1;
    return Contact::num_guards(m, true);
  }
  void guards(const Mode& m, double t, const State& x, Eigen::VectorXd& g) const {
    if (m == Mode::Separated) {
      Contact::gap_guard(x[2] - w(t), g.data());
      if (p_.record_apex) g[1] = past_apex_ ? 1.0 : x[3];  // one apex per flight
      return;
    }
    contact_.guards(m, x[1], normal_force(t), 0.0, true, g.data());
  }
  stickslip::CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    if (m == Mode::Separated && i == 1) return stickslip::CrossingDirection::Falling;  // apex
    return Contact::guard_direction(m, i, true);
  }

  stickslip::TransitionAction transition(Mode& m, const stickslip::TriggeredGuards& which,
                                         double t, State& x) {
    if (m == Mode::Separated) {
      if (std::find(which.begin(), which.end(), Eigen::Index{0}) == which.end()) {
        apexes.push_back({t, x[2]});
        past_apex_ = true;  // a guard left at y' < 0 would fire again at once (docs/ode.md)
        return stickslip::TransitionAction::proceed();
      }
      land_or_bounce(m, t, x);
      return stickslip::TransitionAction::proceed();
    }
    const double N = normal_force(t);
    m = Contact::velocity_guard_fired(m, which) ? contact_.decide_at_rest(N, 0.0)
                                                : contact_.decide(m, x[1], N, 0.0);
    if (m == Mode::LiftOff) {  // the contact opens: free flight
      m = Mode::Separated;
      lift_offs.push_back(t);
      past_apex_ = x[3] < 0.0;
    }
    if (m == Mode::Stick) x[1] = 0.0;
    return stickslip::TransitionAction::proceed();
  }

 private:
  void land_or_bounce(Mode& m, double t, State& x) {
    const double inverse_mass = 1.0 / p_.mass;
    const double v_n = x[3] - w_dot(t);
    const auto normal = impact_.impact(v_n, inverse_mass);
    const auto tangential =
        stickslip::coulomb_impulse(contact_.law(), x[1], inverse_mass, normal.impulse);
    impacts.push_back({t, v_n, normal.impulse, normal.lands});
    x[1] = tangential.velocity_after;
    x[3] += normal.impulse * inverse_mass;
    x[4] += normal.energy_loss + tangential.energy_loss;
    x[6] += normal.impulse * w_dot(t);  // the surface's work on the body at the impact
    if (!normal.lands) {
      ++bounces;
      past_apex_ = false;
      return;
    }
    ++landings;
    const double N = normal_force(t);
    const Mode next = tangential.state == Mode::Stick ? contact_.decide_at_rest(N, 0.0)
                                                      : contact_.decide(m, x[1], N, 0.0);
    if (next == Mode::LiftOff) return;  // the surface accelerates away faster than g: flies on
    m = next;
    x[2] = w(t);  // onto the surface
    x[3] = w_dot(t);
    if (m == Mode::Stick) x[1] = 0.0;
  }

  BouncingMassParameters p_;
  Contact contact_;
  Impact impact_;
  bool past_apex_ = false;
};

}  // namespace contact_test
