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

namespace contact_test {

// A damper on a one-mode structure whose contact opens and closes: the pieces of the contact
// component (CoulombContact, frictional_impact) used as the composed model would use them, written
// out for one mass-normalised mode q with shape values a (normal) and b (tangential) at a fixed
// contact point. The damper (mass m) is pressed onto the structure by a preload P and held
// tangentially by a spring k.
//
//   q'' + 2 zeta omega q' + omega^2 q = F0 cos(Omega t) - a N - b f
//   m y'' = -P + N                 (y: the damper's normal coordinate; in contact y = a q)
//   m x'' = -k x + f               (x: tangential; sliding velocity V = x' - b q')
//
// In contact N and q'' (and f in stick, V' = 0) follow from the constraint rows; separated, N = f
// = 0 and the gap y - a q >= 0 is the guard. At impact the relative velocities
// (y' - a q', x' - b q') change by W L with W = I/m + [a b]^T [a b] (frictional_impact); the
// damper receives L, the mode -(a L_n + b L_t).
//
// State (q, q', x, x', y, y', D_impact, D_friction, D_viscous, W_ext).
class DamperOnOneMode {
 public:
  using Scalar = double;
  using State = Eigen::Matrix<double, 10, 1>;
  using Mode = stickslip::ContactState;
  using Law = stickslip::CoulombLaw<double>;
  using Contact = stickslip::CoulombContact<Law>;

  struct Parameters {
    double omega = 2.0 * 3.14159265358979323846 * 10.0, zeta = 0.01;
    double force = 3.0, forcing_frequency = 0.9 * 2.0 * 3.14159265358979323846 * 10.0;
    double a = 1.0, b = 0.3;           // mode shape at the contact, normal and tangential
    double m = 0.1, k = 100.0, P = 1.0;
  };
  struct Forces {
    double qdd, N, f;
  };
  // An impact as seen from outside: the states just before and after the transition.
  struct ImpactRecord {
    double t;
    State before, after;
    bool lands;
  };

  DamperOnOneMode(const Parameters& p, Law law, stickslip::NewtonImpact<double> impact)
      : p_(p), contact_(law), impact_(impact) {}

  std::vector<ImpactRecord> impacts;
  std::vector<double> lift_offs;

  const Parameters& parameters() const { return p_; }
  double load(double t) const { return p_.force * std::cos(p_.forcing_frequency * t); }
  double r(double t, const State& x) const {
    return load(t) - p_.omega * p_.omega * x[0] - 2.0 * p_.zeta * p_.omega * x[1];
  }
  double sliding_velocity(const State& x) const { return x[3] - p_.b * x[1]; }
  double energy(const State& x) const {
    return 0.5 * x[1] * x[1] + 0.5 * p_.omega * p_.omega * x[0] * x[0] +
           0.5 * p_.m * (x[3] * x[3] + x[5] * x[5]) + 0.5 * p_.k * x[2] * x[2] + p_.P * x[4];
  }
  // Constant in time: energy + losses - external work.
  double balance(const State& x) const { return energy(x) + x[6] + x[7] + x[8] - x[9]; }
  // The generalised momentum that an impulse between damper and mode cannot change:
  // q' + m (a y' + b x') (the mode receives -(a L_n + b L_t), the damper L).
  double contact_momentum(const State& x) const {
    return x[1] + p_.m * (p_.a * x[5] + p_.b * x[3]);
  }

  // Contact forces in a contact state: N = P + m a q'' (normal row); stick f = k x + m b q''
  // (V' = 0), slip f = -sigma mu_k N; q'' = r - a N - b f.
  Forces forces(const Mode& m, double t, const State& x) const {
    const double rr = r(t, x), a = p_.a, b = p_.b, mass = p_.m;
    if (m == Mode::Stick) {
      Eigen::Matrix3d A;
      A << 1.0, a, b,  // q'' + a N + b f = r
          -mass * a, 1.0, 0.0,      // N - m a q'' = P
          -mass * b, 0.0, 1.0;      // f - m b q'' = k x
      const Eigen::Vector3d s = A.partialPivLu().solve(Eigen::Vector3d(rr, p_.P, p_.k * x[2]));
      return {s[0], s[1], s[2]};
    }
    const double mu_sigma = contact_.law().kinetic_coefficient(0.0) * stickslip::slip_sign(m);
    const double N = (p_.P + mass * a * rr) / (1.0 + mass * a * (a - b * mu_sigma));
    const double f = -mu_sigma * N;
    return {rr - a * N - b * f, N, f};
  }

  void rhs(const Mode& m, double t, const State& x, State& dxdt) const {
    dxdt.setZero();
    dxdt[0] = x[1];
    dxdt[2] = x[3];
    dxdt[4] = x[5];
    dxdt[8] = 2.0 * p_.zeta * p_.omega * x[1] * x[1];
    dxdt[9] = load(t) * x[1];
    if (m == Mode::Separated) {
      dxdt[1] = r(t, x);
      dxdt[3] = -p_.k * x[2] / p_.m;
      dxdt[5] = -p_.P / p_.m;
      return;
    }
    const Forces F = forces(m, t, x);
    dxdt[1] = F.qdd;
    dxdt[3] = (F.f - p_.k * x[2]) / p_.m;
    dxdt[5] = p_.a * F.qdd;  // y = a q
    dxdt[7] = m == Mode::Stick ? 0.0 : -F.f * sliding_velocity(x);
  }

  Eigen::Index num_guards(const Mode& m) const {
    return m == Mode::Separated ? 1 : Contact::num_guards(m, true);
  }
  void guards(const Mode& m, double t, const State& x, Eigen::VectorXd& g) const {
    if (m == Mode::Separated) {
      Contact::gap_guard(x[4] - p_.a * x[0], g.data());
      return;
    }
    const Forces F = forces(m, t, x);
    contact_.guards(m, sliding_velocity(x), F.N, F.f, true, g.data());
  }
  stickslip::CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    return Contact::guard_direction(m, i, true);
  }

  stickslip::TransitionAction transition(Mode& m, const stickslip::TriggeredGuards& which,
                                         double t, State& x) {
    if (m == Mode::Separated) {
      impact(m, t, x);
      return stickslip::TransitionAction::proceed();
    }
    if (Contact::velocity_guard_fired(m, which) || m == Mode::Stick) {
      m = at_rest(t, x);
    } else {
      m = contact_.decide(m, sliding_velocity(x), forces(m, t, x).N, 0.0);
    }
    if (m == Mode::LiftOff) {
      m = Mode::Separated;
      lift_offs.push_back(t);
    }
    return stickslip::TransitionAction::proceed();
  }

 private:
  // Stick if the stick forces hold (N > 0, |f| <= mu_s N), else slip against the excess force
  // (CoulombContact::decide_at_rest with the stick solve's forces); a new stick gets V = 0.
  Mode at_rest(double t, State& x) const {
    x[3] = p_.b * x[1];
    const Forces F = forces(Mode::Stick, t, x);
    return contact_.decide_at_rest(F.N, F.f);
  }

  void impact(Mode& m, double t, State& x) {
    const double a = p_.a, b = p_.b, mass = p_.m;
    Eigen::Matrix2d W;
    W << 1.0 / mass + a * a, a * b, a * b, 1.0 / mass + b * b;
    const Eigen::Vector2d v(x[5] - a * x[1], sliding_velocity(x));
    const auto hit = stickslip::frictional_impact(impact_, contact_.law(), W, v);
    STICKSLIP_ASSERT(hit.resolved);
    ImpactRecord rec{t, x, x, hit.lands};
    x[5] += hit.impulse[0] / mass;
    x[3] += hit.impulse[1] / mass;
    x[1] -= a * hit.impulse[0] + b * hit.impulse[1];
    x[6] += hit.energy_loss;
    if (hit.lands) {
      x[4] = a * x[0];  // onto the surface (the gap is past zero by the event tolerance only)
      x[5] = a * x[1];
      const Mode next = hit.state == Mode::Stick
                            ? at_rest(t, x)
                            : contact_.decide(hit.state, sliding_velocity(x),
                                              forces(hit.state, t, x).N, 0.0);
      if (next != Mode::LiftOff) m = next;
    }
    rec.after = x;
    impacts.push_back(rec);
  }

  Parameters p_;
  Contact contact_;
  stickslip::NewtonImpact<double> impact_;
};

}  // namespace contact_test
