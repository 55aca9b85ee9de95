#pragma once
// The problems as stickslip hybrid systems (the pattern of tests/contact/single_dof_systems.hpp:
// the model computes v, N and f_req; CoulombContact gives the guards, their directions and the
// transition), integrated by HybridStepper<System, Method>.

#include <stickslip/contact.hpp>
#include <stickslip/ode.hpp>
#include <stickslip/ode/exact_linear_stepper.hpp>

#include <Eigen/Core>

#include <cmath>
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
  /// The linear part of mode m (stickslip/ode/linear_part.hpp), exact in every mode (Coulomb
  /// friction, constant N): x' = v, v' = M^-1 (F cos(w t + phi) - K x - C v + f e_j) with
  /// f = -sgn mu_k N in slip and row j zero in stick; cos(w t + phi) = cos(phi) cos(w t) -
  /// sin(phi) sin(w t); the contact's guards, affine in (x, v) and the forcing.
  bool linear_part(const Mode& m, double, const State&, stickslip::LinearPart<double>& lp) const {
    const Eigen::Index n = 2 * N;
    const bool forced = chain_.F.cwiseAbs().maxCoeff() > 0.0;
    lp.A.setZero(n, n);
    lp.A.topRightCorner(N, N).setIdentity();
    lp.A.bottomLeftCorner(N, N) = -(chain_.m.cwiseInverse().asDiagonal() * chain_.K);
    lp.A.bottomRightCorner(N, N) = -(chain_.m.cwiseInverse().asDiagonal() * chain_.C);
    lp.b0.setZero(n);
    lp.omega.assign(forced ? 1u : 0u, p_.force_frequency);
    lp.bc.setZero(n, forced ? 1 : 0);
    lp.bs.setZero(n, forced ? 1 : 0);
    if (forced) {
      lp.bc.bottomRows(N) = std::cos(p_.force_phase) * chain_.F.cwiseQuotient(chain_.m);
      lp.bs.bottomRows(N) = -std::sin(p_.force_phase) * chain_.F.cwiseQuotient(chain_.m);
    }
    const Eigen::Index j = N + chain_.j;
    if (m == Mode::Stick) {
      lp.A.row(j).setZero();
      if (forced) lp.bc(j, 0) = lp.bs(j, 0) = 0.0;
    } else {
      lp.b0[j] = -static_cast<double>(stickslip::slip_sign(m)) * chain_.slip_force / chain_.m[chain_.j];
    }
    // Affine guards (the contact's): stick g = mu_s N -/+ f_req with f_req = K_j x + C_j v -
    // F_j cos(w t + phi); slip g = v_j - v_b.
    const Eigen::Index K = forced ? 1 : 0;
    if (m == Mode::Stick) {
      lp.Gx.resize(2, n);
      lp.Gx.row(0) << -chain_.K.row(chain_.j), -chain_.C.row(chain_.j);
      lp.Gx.row(1) = -lp.Gx.row(0);
      lp.g0.setConstant(2, chain_.capacity);
      lp.gc.setZero(2, K);
      lp.gs.setZero(2, K);
      if (forced) {
        const double fj = chain_.F[chain_.j];
        lp.gc.col(0) << fj * std::cos(p_.force_phase), -fj * std::cos(p_.force_phase);
        lp.gs.col(0) << -fj * std::sin(p_.force_phase), fj * std::sin(p_.force_phase);
      }
    } else {
      lp.Gx.setZero(1, n);
      lp.Gx(0, j) = 1.0;
      lp.g0.setConstant(1, -p_.belt_speed);
      lp.gc.setZero(1, K);
      lp.gs.setZero(1, K);
    }
    lp.exact = true;
    lp.version = m == Mode::Stick ? 1 : 2;  // A of the two slip directions is the same
    return true;
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

/// Tag for run_library: ExactLinearStepper (the modal-exact method) instead of a HybridStepper
/// method; tolerance is then unused (every mode of the chains is exact).
struct ModalExact {};

template <class System, class Method>
struct StepperFor {
  using type = stickslip::HybridStepper<System, Method>;
};
template <class System>
struct StepperFor<System, ModalExact> {
  using type = stickslip::ExactLinearStepper<System>;
};

template <int N, class Method>
RunOutcome run_library_n(const ChainParameters& p, double tolerance) {
  LibraryChain<N> sys(p);
  stickslip::StepperOptions<double> opt;
  opt.rtol = opt.atol = tolerance;
  opt.max_steps = 5'000'000;
  typename StepperFor<LibraryChain<N>, Method>::type stepper(sys, opt);
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
  out.event_state_rhs = r.stats.event_state_rhs_evaluations;
  out.restart_rhs = r.stats.restart_rhs_evaluations;
  return out;
}

/// The library with `Method` (DormandPrince54, Rosenbrock23, ...) at rtol = atol = tolerance.
template <class Method>
RunOutcome run_library(const ChainParameters& p, double tolerance) {
  return p.dofs == 1 ? run_library_n<1, Method>(p, tolerance)
                     : run_library_n<2, Method>(p, tolerance);
}

}  // namespace peers
