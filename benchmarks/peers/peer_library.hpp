#pragma once
// The problems as stickslip hybrid systems (the pattern of tests/contact/single_dof_systems.hpp:
// the model computes v, N and f_req; CoulombContact gives the guards, their directions and the
// transition), integrated by HybridStepper<System, Method>.

#include <stickslip/contact.hpp>
#include <stickslip/ode.hpp>

#include <Eigen/Core>

#include <vector>

#include "peers/peer_problems.hpp"
#include "peers/peer_run.hpp"

namespace peers {

template <int N>
class LibraryChain {
 public:
  using Scalar = double;
  using State = Eigen::Matrix<double, 2 * N, 1>;
  using Mode = ContactState;
  using Contact = stickslip::CoulombContact<stickslip::CoulombLaw<double>>;
  using Vec = typename Chain<N>::Vec;

  explicit LibraryChain(const ChainParameters& p)
      : p_(p), chain_(p), contact_(stickslip::CoulombLaw<double>(p.mu_s, p.mu_k)) {}

  double sliding_velocity(const State& x) const { return x[N + chain_.j] - p_.belt_speed; }
  double stick_force(double t, const State& x) const {
    return chain_.stick_force(t, x.template head<N>(), x.template tail<N>());
  }

  void rhs(const Mode& m, double t, const State& x, State& dxdt) const {
    dxdt.template head<N>() = x.template tail<N>();
    Vec a;
    chain_.acceleration(m, t, x.template head<N>(), x.template tail<N>(), a);
    dxdt.template tail<N>() = a;
  }
  Eigen::Index num_guards(const Mode& m) const { return Contact::num_guards(m, false); }
  void guards(const Mode& m, double t, const State& x, Eigen::VectorXd& g) const {
    contact_.guards(m, sliding_velocity(x), p_.normal_force, stick_force(t, x), false, g.data());
  }
  stickslip::CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    return Contact::guard_direction(m, i, false);
  }
  stickslip::TransitionAction transition(Mode& m, const stickslip::TriggeredGuards&, double t,
                                         State& x) const {
    m = contact_.decide(m, sliding_velocity(x), p_.normal_force, stick_force(t, x));
    if (m == Mode::Stick) x[N + chain_.j] = p_.belt_speed;
    return stickslip::TransitionAction::proceed();
  }

 private:
  const ChainParameters& p_;
  Chain<N> chain_;
  Contact contact_;
};

struct LibraryEventLog : stickslip::NullObserver {
  std::vector<Event>* events;
  void on_event(const stickslip::EventRecord<double, ContactState>& r) {
    events->push_back({r.t, r.from, r.to});
  }
};

template <int N, class Method>
RunOutcome run_library_n(const ChainParameters& p, double tolerance) {
  LibraryChain<N> sys(p);
  stickslip::StepperOptions<double> opt;
  opt.rtol = opt.atol = tolerance;
  opt.max_steps = 5'000'000;
  stickslip::HybridStepper<LibraryChain<N>, Method> stepper(sys, opt);
  typename LibraryChain<N>::State x0;
  x0 << p.x0.head<N>(), p.v0.head<N>();
  const Chain<N> chain(p);
  const ContactState mode =
      decide_mode(p, p.v0[p.friction_dof] - p.belt_speed,
                  chain.stick_force(0.0, p.x0.head<N>(), p.v0.head<N>()));
  RunOutcome out;
  LibraryEventLog log;
  log.events = &out.events;
  const auto r = stepper.integrate(mode, 0.0, x0, p.t_end, log);
  out.ok = r.ok();
  out.message = r.message;
  out.final_state = r.x;
  out.steps = r.stats.accepted_steps + r.stats.rejected_steps;
  out.rhs_evaluations = r.stats.rhs_evaluations;
  return out;
}

/// The library with `Method` (DormandPrince54, Rosenbrock23, ...) at rtol = atol = tolerance.
template <class Method>
RunOutcome run_library(const ChainParameters& p, double tolerance) {
  return p.dofs == 1 ? run_library_n<1, Method>(p, tolerance)
                     : run_library_n<2, Method>(p, tolerance);
}

}  // namespace peers
