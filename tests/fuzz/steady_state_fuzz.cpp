// Fuzz harness: the steady-state layer (Shooting::forced and its Floquet multipliers,
// floquet_multipliers, poincare_sections, Continuation) on the one-degree-of-freedom friction
// oscillator of tests/contact/single_dof_systems.hpp with CoulombLaw:
//   m x'' + k x = F0 cos(omega t) + f,  v = x' - v_belt,  N constant;  state (x, x', W, D) with
//   W = integral of F x' dt and D = integral of -f v dt.
//
// Layout of an input: m, k, F0, omega, v_belt, N, mu_s, mu_k; start mode choice(3) (stick, slip+,
// slip-); guess x0, v0; t0; subharmonic order choice(3) (T = (1 + c) 2 pi / omega); stepper rtol,
// atol, max_steps integer; shooting tolerance, max_iterations integer, monodromy choice(2),
// control_sensitivities flag, fd_step; action choice(3): 0 shooting, 1 Poincare sections
// (transient periods integer, max_period integer), 2 continuation in omega (relative half-range,
// initial_step, max_points integer, chord_iterations integer, section_margin).
//
// Work bound: max_steps <= 5000 per run, <= 6 Newton iterations, <= 4 continuation points,
// <= 10 transient and <= 8 recorded periods. Rules checked besides the exception types:
//  * a Converged orbit (Shooting or a continuation point) closes: one period re-run from its
//    (mode, t0, x0, period) with the same options ends with Success in its start mode and
//    max_i |x_i(T) - x_i(0)| over (x, x') within Shooting::tolerance_at(x0) (the criterion the
//    orbit claims to meet; with the sensitivities out of the error control the re-run takes the
//    last Newton run's steps, so only a stale or misreported x0 fails it; with them in, the plain
//    run's steps are no shorter and its x(T) differs by the integration error);
//  * on that re-run, without belt (v = x'), the energy identity of the run closes:
//    [W] - [D] = [m x'^2 / 2 + k x^2 / 2] to 1e3 (rtol scale + atol), scale = |[W]| + |[D]| + both
//    energies: the quadratures are integrated with the state under the same error control, so a
//    violation means a wrong orbit or event handling, not integration error;
//  * a Converged orbit's monodromy and multipliers are finite, and floquet_multipliers on its
//    monodromy gives the same max modulus;
//  * Poincare sections are finite; a Periodic verdict has k in [1, max_period].
#include "contact/single_dof_systems.hpp"
#include "fuzz/fuzz_input.hpp"

#include <stickslip/steady_state.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace steady_state_fuzz {

using namespace stickslip;
using stickslip_fuzz::require;
using stickslip_fuzz::str;
using Law = CoulombLaw<double>;
using Base = contact_test::SingleDofOscillator<Law>;

/// The oscillator with a settable forcing frequency (Continuation's parameter).
struct Oscillator : Base {
  Oscillator(const contact_test::SingleDofParameters& p, Law law) : Base(p, Contact(law)), law_(law) {}
  void set_frequency(double w) {
    contact_test::SingleDofParameters p = parameters();
    p.force_frequency = w;
    static_cast<Base&>(*this) = Base(p, Contact(law_));
  }
  Law law_;
};

constexpr double kTwoPi = 6.283185307179586;

bool all_finite(const Eigen::VectorXcd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i].real()) || !std::isfinite(v[i].imag())) return false;
  return true;
}

/// The rules on a Converged orbit (see the file comment).
void check_orbit(Oscillator& sys, const Shooting<Oscillator>& shooting, const PeriodicOrbit<Oscillator>& o,
                 const char* who) {
  const std::string at = std::string(who) + " (t0 = " + str(o.t0) + ", T = " + str(o.period) + "): ";
  require(o.x0.allFinite() && std::isfinite(o.period) && o.period > 0, at + "non-finite orbit");
  require(o.monodromy.allFinite(), at + "non-finite monodromy");
  require(all_finite(o.floquet.multipliers) && std::isfinite(o.floquet.max_modulus), at + "non-finite multipliers");
  if (o.monodromy.size() > 0) {
    const auto again = floquet_multipliers(o.monodromy, false, shooting.options().multiplier_tolerance);
    require(again.max_modulus == o.floquet.max_modulus,
            at + "max |mu| " + str(o.floquet.max_modulus) + ", floquet_multipliers " + str(again.max_modulus));
  }
  const PeriodRun<Oscillator> run = run_period(sys, o.mode, o.t0, o.x0, o.period, shooting.options(), false);
  require(run.ok(), at + "the re-run of the period fails: " + run.message);
  require(run.mode_end == o.mode, at + "the re-run ends in another mode");
  Eigen::VectorXd r;
  const double residual = shooting.residual(run.x_end, o.x0, r), tol = shooting.tolerance_at(o.x0);
  require(residual <= tol, at + "re-run residual " + str(residual) + " > tolerance " + str(tol) +
                               " (reported " + str(o.residual) + ")");
  if (sys.parameters().belt_speed == 0) {
    const double dW = run.x_end[2] - o.x0[2], dD = run.x_end[3] - o.x0[3];
    const double E0 = sys.mechanical_energy(o.x0), E1 = sys.mechanical_energy(run.x_end);
    const double scale = std::abs(dW) + std::abs(dD) + E0 + E1;
    const auto& so = shooting.options().stepper;
    const double gap = std::abs(dW - dD - (E1 - E0));
    if (std::isfinite(scale))
      require(gap <= 1e3 * (so.rtol * scale + so.atol),
              at + "energy identity [W] - [D] - [E] = " + str(dW - dD - (E1 - E0)) + " for scale " + str(scale));
  }
}

void run(stickslip_fuzz::Input& in) {
  contact_test::SingleDofParameters p;
  p.mass = in.real(0.1, 10.0);
  p.stiffness = in.real(0.1, 100.0);
  p.force_amplitude = in.real(0.0, 10.0);
  p.force_frequency = in.real(0.1, 10.0);
  p.belt_speed = in.real(0.0, 1.0);
  p.normal_force = in.real(0.0, 10.0);
  const double mu_s = in.real(0.0, 1.0), mu_k = in.real(0.0, 1.0);
  const auto mode = static_cast<ContactState>(in.choice(3));
  Oscillator::State x0;
  x0 << in.real(-1.0, 1.0), in.real(-1.0, 1.0), 0.0, 0.0;
  const double t0 = in.real(0.0, 10.0);
  const double order = 1.0 + in.choice(3);

  ShootingOptions<double> so;
  so.periodic = ShootingOptions<double>::first(2);
  so.stepper.rtol = in.real(1e-12, 1e-6);
  so.stepper.atol = in.real(1e-14, 1e-8);
  so.stepper.max_steps = static_cast<long>(std::clamp<long long>(in.integer(1, 5000), -1, 5000));
  so.tolerance = in.real(1e-12, 1e-6);
  so.max_iterations = static_cast<int>(std::clamp<long long>(in.integer(1, 6), -1, 6));
  so.monodromy = static_cast<MonodromyMethod>(in.choice(2));
  so.control_sensitivities = in.flag();
  so.fd_step = in.real(1e-9, 1e-3);
  so.samples_per_period = 16;

  Oscillator sys(p, Law(mu_s, mu_k));  // throws invalid_argument for a bad law
  const double T = order * kTwoPi / p.force_frequency;
  switch (in.choice(3)) {
    case 0: {
      Shooting<Oscillator> shooting(sys, so);
      const auto orbit = shooting.forced(mode, t0, x0, T);
      if (orbit.ok()) check_orbit(sys, shooting, orbit, "Shooting::forced");
      else require(!orbit.message.empty(), std::string("shooting status ") + to_string(orbit.status) + " without a message");
      break;
    }
    case 1: {
      PoincareOptions<double> po;
      po.transient_periods = static_cast<int>(std::clamp<long long>(in.integer(0, 10), -1, 10));
      po.max_period = static_cast<int>(std::clamp<long long>(in.integer(1, 4), -1, 4));
      po.record_periods = std::max(2 * po.max_period, 2);
      po.periodic = so.periodic;
      po.stepper = so.stepper;
      const auto sections = poincare_sections(sys, mode, t0, x0, T, po);
      if (sections.status == PoincareStatus::IntegrationFailed) break;
      for (const auto& x : sections.states) require(x.allFinite(), "non-finite Poincare section");
      if (sections.status == PoincareStatus::Periodic)
        require(sections.period >= 1 && sections.period <= po.max_period,
                "Periodic with k = " + std::to_string(sections.period));
      break;
    }
    default: {
      ContinuationOptions<double> co;
      const double w = p.force_frequency, half = in.real(1e-3, 0.5);
      co.parameter_min = w * (1 - half);
      co.parameter_max = w * (1 + half);
      co.max_step = w * half;
      co.min_step = co.max_step * 1e-6;
      co.initial_step = std::clamp(in.real(0.0, co.max_step), co.min_step, co.max_step);
      co.max_points = static_cast<int>(std::clamp<long long>(in.integer(1, 4), -1, 4));
      co.max_corrector_iterations = 4;
      co.chord_iterations = static_cast<int>(std::clamp<long long>(in.integer(0, 3), -1, 3));
      co.section_margin = in.real(0.0, 0.1);
      Continuation<Oscillator> cont(
          sys, [](Oscillator& s, double v) { s.set_frequency(v); },
          [order](double v) { return order * kTwoPi / v; }, so, co);
      const auto result = cont.run(mode, t0, x0, w);
      if (result.status == ContinuationStatus::StepTooSmall || result.status == ContinuationStatus::StartFailed)
        require(!result.message.empty(), std::string("continuation status ") + to_string(result.status) +
                                             " without a message");
      Shooting<Oscillator> shooting(sys, so);
      for (const auto& point : result.points) {
        require(std::isfinite(point.parameter), "non-finite continuation parameter");
        if (!point.orbit.ok()) continue;
        sys.set_frequency(point.parameter);
        check_orbit(sys, shooting, point.orbit, "continuation point");
      }
      break;
    }
  }
}

}  // namespace steady_state_fuzz

STICKSLIP_FUZZ_ENTRY(steady_state, steady_state_fuzz::run)
