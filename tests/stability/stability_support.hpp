#pragma once
// Shared helper of the stability tests (docs/stability.md): run a composed FrictionDampedSystem
// with given integrator options and report what a user would see (status, message, final time,
// finiteness) plus the model's own checks, measured independently of the model's bookkeeping:
//  * the energy-audit residual relative to the largest energy term of the run,
//  * the sliding velocity of stuck dampers recomputed from the state, V = x' - q'^T psi_u(X),
//    with psi_u taken from component 3 (MemberShapes) directly,
//  * the stick capacity |f| <= mu_s N of stuck dampers and the slip direction sign(V) of
//    slipping ones, at every accepted step.
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace stability {

using namespace model_test;  // System, TScene, make_t_frame, paper_load, Index

/// What one run produced.
struct Outcome {
  bool threw = false;           ///< the run threw (message holds what())
  bool consistent_start = true; ///< make_consistent succeeded
  Status status = Status::Success;
  System::StopReason stop_reason = System::StopReason::None;
  std::string message;
  double t = 0;
  bool finite = true;           ///< final state all finite
  System::State x;
  DamperStates mode;
  StepperStats stats;
  long contact_events = 0;
  double energy_residual = 0;   ///< final |residual| [J]
  double max_energy_residual = 0;  ///< largest |residual| over the accepted steps [J]
  double energy_scale = 0;      ///< largest |term| of the balance over the run [J]
  double max_stuck_V = 0;       ///< largest |x' - q'^T psi_u(X)| of a stuck damper [m/s]
  double max_capacity_excess = 0;  ///< largest |f| - mu_s N of a stuck damper [N]
  /// Largest rate of the stick margin mu_s N - |f| of a stuck damper between consecutive checks
  /// [N/s] (a lower bound of its peak rate): an event is located to the event-time tolerance, so
  /// the state handed over is past the capacity by at most this rate times that tolerance.
  double max_stick_margin_rate = 0;
  double max_wrong_slip_V = 0;  ///< largest sliding speed against the slip state's sign [m/s]
  double max_slip_V = 0;        ///< largest |V| while slipping [m/s]
  double max_slip_Vdot = 0;     ///< largest |V'| while slipping [m/s^2]
  double min_N = std::numeric_limits<double>::infinity();  ///< smallest normal force seen [N]

  /// Largest residual over the run relative to the energy scale; the scale is floored at 1e-12 J
  /// (the round-off level of the energies of these scenes, 1e-4 .. 1e4 J), so that a scene that
  /// stays at rest does not divide round-off by round-off.
  double relative_residual() const { return max_energy_residual / std::max(energy_scale, 1e-12); }
};

/// Observer computing the checks of Outcome at every accepted step.
class Checker : public NullObserver {
 public:
  Checker(System& sys, const FrameModel<double>& frame, const ModalBasis<double>& basis, double E0,
          Outcome& out)
      : sys_(sys), E0_(E0), out_(out) {
    for (const auto& d : sys.dampers())
      if (!shapes_.count(d.member))
        shapes_.emplace(d.member, std::make_unique<MemberShapes<double>>(frame, d.member, basis, EndPolicy::Extrapolate));
  }

  bool on_step(double t, const System::State& x, const DamperStates& mode) {
    check(t, x, mode);
    return true;
  }

 private:
  void check(double t, const System::State& x, const DamperStates& mode) {
    if (!x.allFinite()) return;  // reported through the status
    const Index n = sys_.num_modes();
    const auto& e = sys_.evaluate(mode, t, x);
    for (Index i = 0; i < sys_.num_dampers(); ++i) {
      const auto& d = sys_.dampers()[static_cast<std::size_t>(i)];
      const double N = e.N[i], f = e.f[i];
      out_.min_N = std::min(out_.min_N, N);
      if (mode[i] != ContactState::Stick) last_margin_.erase(i);
      if (mode[i] == ContactState::Stick) {
        const double X = e.X[i];
        auto v = shapes_.at(d.member)->evaluate(X);
        const double V = x[sys_.xd_offset() + i] - x.segment(n, n).dot(v.psi_u);
        out_.max_stuck_V = std::max(out_.max_stuck_V, std::abs(V));
        const double mu_s = std::get<CoulombLaw<double>>(d.law).mu_s();
        const double margin = mu_s * N - std::abs(f);
        out_.max_capacity_excess = std::max(out_.max_capacity_excess, -margin);
        const auto prev = last_margin_.find(i);
        if (prev != last_margin_.end() && prev->second.first < t)  // stuck at the previous check too
          out_.max_stick_margin_rate = std::max(out_.max_stick_margin_rate,
                                                std::abs(margin - prev->second.second) / (t - prev->second.first));
        last_margin_[i] = {t, margin};
      } else {
        const double sign = mode[i] == ContactState::SlipPositive ? 1.0 : -1.0;
        out_.max_slip_V = std::max(out_.max_slip_V, std::abs(e.V[i]));
        out_.max_slip_Vdot = std::max(out_.max_slip_Vdot, std::abs(e.Vdot[i]));
        out_.max_wrong_slip_V = std::max(out_.max_wrong_slip_V, -sign * e.V[i]);
      }
    }
    if (sys_.options().energy_audit) {
      const auto b = sys_.energy_balance(mode, t, x, E0_);
      // The scale also holds the modal energy itself: E - E0 can stay ~0 while kinetic and strain
      // energy trade with the preload's potential.
      const auto q = x.head(n), qd = x.segment(n, n);
      const double modal = 0.5 * (qd.squaredNorm() + q.dot(sys_.omega_squared().cwiseProduct(q)));
      for (double term : {b.mechanical - E0_, modal, b.external_work, b.viscous_dissipation,
                          b.friction_dissipation, b.slope_work})
        out_.energy_scale = std::max(out_.energy_scale, std::abs(term));
      out_.max_energy_residual = std::isfinite(b.residual)
                                     ? std::max(out_.max_energy_residual, std::abs(b.residual))
                                     : std::numeric_limits<double>::infinity();
    }
  }

  System& sys_;
  double E0_;
  Outcome& out_;
  std::map<Index, std::unique_ptr<MemberShapes<double>>> shapes_;
  std::map<Index, std::pair<double, double>> last_margin_;  // damper -> (t, stick margin) while stuck
};

/// Bound on the capacity excess of a stuck damper at an accepted step: 1e-7 N, 10 N x rtol (a
/// fresh step's local error in the contact forces), or 10 x (event-time tolerance 1e-12 s) x the
/// measured rate of the stick margin (the located state is past the switching surface by at most
/// the margin's rate times the event-time tolerance; 10 covers the peak rate between checks).
inline double capacity_excess_bound(const Outcome& o, double rtol = 0) {
  return std::max({1e-7, 10.0 * rtol, 10.0 * 1e-12 * o.max_stick_margin_rate});
}

/// Runs `sys` from `x0` (default: rest) in its requested mode, made consistent, to t_end.
/// The run goes on even when make_consistent fails (consistent_start records it), so that a test
/// can show what a user who ignores it gets.
inline Outcome run(System& sys, const FrameModel<double>& frame, const ModalBasis<double>& basis,
                   double t_end, const RunOptions<double>& options,
                   System::State x0 = System::State(), DamperStates mode = DamperStates()) {
  Outcome out;
  try {
    if (x0.size() == 0) x0 = sys.initial_state();
    if (mode.size() == 0) mode = sys.requested_mode();
    out.consistent_start = sys.make_consistent(mode, 0.0, x0);
    if (!out.consistent_start) out.stop_reason = sys.stop_reason();
    const double E0 = sys.mechanical_energy(mode, 0.0, x0);
    Checker checker(sys, frame, basis, E0, out);
    checker.on_step(0.0, x0, mode);
    const std::size_t events_before = sys.events().size();
    auto r = simulate(sys, mode, 0.0, x0, t_end, options, checker);
    out.status = r.status;
    out.message = r.message;
    out.t = r.t;
    out.x = r.x;
    out.mode = r.mode;
    out.stats = r.stats;
    out.finite = r.x.allFinite();
    out.contact_events = static_cast<long>(sys.events().size() - events_before);
    if (r.status == Status::StoppedBySystem) out.stop_reason = sys.stop_reason();
    if (out.finite && sys.options().energy_audit) {
      const auto b = sys.energy_balance(r.mode, r.t, r.x, E0);
      out.energy_residual = std::abs(b.residual);
    }
  } catch (const std::exception& ex) {
    out.threw = true;
    out.message = ex.what();
  }
  return out;
}

/// Options of one integrator with the given step/tolerances.
inline RunOptions<double> options_for(Integrator integrator, double rtol = 1e-8, double atol = 1e-12,
                                      double fixed_step = 1e-6) {
  RunOptions<double> o;
  o.integrator = integrator;
  o.stepper.rtol = rtol;
  o.stepper.atol = atol;
  o.stepper.fixed_step = fixed_step;
  return o;
}

/// The time printed in a status message ("... at t = <time> ..."), or NaN when there is none.
inline double time_in_message(const std::string& message) {
  const std::string key = "at t = ";
  const auto p = message.find(key);
  if (p == std::string::npos) return std::numeric_limits<double>::quiet_NaN();
  return std::stod(message.substr(p + key.size()));
}

/// A damper on `member` at X0 with mass m, spring k, preload N0, Coulomb (mu_s, mu_k), share 1/2.
inline PointDamper<double> damper(Index member, double X0, double m, double k, double N0,
                                  double mu_s = 0.35, double mu_k = 0.3) {
  return PointDamper<double>(member, X0, m, k, N0, CoulombLaw<double>(mu_s, mu_k), 0.5);
}

/// Human-readable summary for failure messages.
inline std::string describe(const Outcome& o) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                " t=%.6g steps=%ld rejected=%ld events=%ld rel.residual=%.3g scale=%.3g J "
                "stuck|V|=%.3g capacity excess=%.3g N (margin rate %.3g N/s) wrong-sign V=%.3g (|V|<=%.3g, |V'|<=%.3g) "
                "min N=%.6g",
                o.t, o.stats.accepted_steps, o.stats.rejected_steps, o.contact_events,
                o.relative_residual(), o.energy_scale, o.max_stuck_V, o.max_capacity_excess, o.max_stick_margin_rate,
                o.max_wrong_slip_V, o.max_slip_V, o.max_slip_Vdot, o.min_N);
  return std::string(to_string(o.status)) + (o.threw ? " (threw)" : "") + buf + " message='" +
         o.message + "'";
}

}  // namespace stability
