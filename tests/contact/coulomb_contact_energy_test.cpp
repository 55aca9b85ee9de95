// Energy audit of the forced friction oscillator: work of the excitation = friction dissipation
// + change of mechanical energy, through stick-slip transitions and a time-varying normal force.
//
//   W(t) = int F x' dt,  D(t) = int -f v dt,  E = m x'^2/2 + k x^2/2,  W - D - (E - E0) = 0.
//
// W and D are integrated as extra states, E is evaluated from x, x'. The balance is exact for the
// ODE in every mode; numerically it holds to the integration error, and it breaks by m v^2/2 at
// every transition whose projection onto v = 0 happens at a non-negligible v, or whenever the
// friction force used in the momentum equation differs from the one in the power.

#include "contact/single_dof_systems.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace contact_coulomb_contact_energy_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::EventLog;
using contact_test::SingleDofOscillator;
using contact_test::SingleDofParameters;
using S = stickslip::ContactState;

SingleDofParameters stick_slip_oscillator() {
  SingleDofParameters p;
  p.mass = 1.0;
  p.stiffness = 10.0;
  p.force_amplitude = 5.0;
  p.force_frequency = 1.5;
  p.normal_force = 8.0;
  p.normal_amplitude = 3.0;  // eqs. 23-24: N varies in time
  p.normal_frequency = 3.0;
  return p;
}

struct AuditLog : EventLog {
  const void* sys = nullptr;
  double max_imbalance = 0, scale = 0, last_D = 0;
  bool dissipation_decreased = false;
  long stick_steps = 0;
};

template <class Law>
void audit(const Law& law, bool expect_sticking) {
  using Sys = SingleDofOscillator<Law>;
  Sys sys(stick_slip_oscillator(), stickslip::CoulombContact<Law>(law));
  const Eigen::Vector4d x0(0.1, 0.0, 0.0, 0.0);
  const double E0 = sys.mechanical_energy(x0);
  struct Log : AuditLog {
    const Sys* s;
    double E0;
    bool on_step(double, const Eigen::Vector4d& x, const S& m) {
      const double imbalance = x[2] - x[3] - (s->mechanical_energy(x) - E0);
      max_imbalance = std::max(max_imbalance, std::abs(imbalance));
      scale = std::max({scale, std::abs(x[2]), x[3]});
      if (x[3] < last_D - 1e-14) dissipation_decreased = true;
      last_D = x[3];
      if (m == S::Stick) ++stick_steps;
      return true;
    }
  } log;
  log.s = &sys;
  log.E0 = E0;
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-10;
  opt.atol = 1e-13;
  opt.max_step = 0.02;  // frozen state while stuck, moving guards: see the lift-off test
  stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys, opt);
  const auto r = stepper.integrate(sys.consistent_mode(0.0, x0), 0.0, x0, 40.0, log);
  ASSERT_TRUE(r.ok()) << r.message;
  if (expect_sticking) {
    long sticks = 0;
    for (const auto& e : log.events) sticks += e.to == S::Stick ? 1 : 0;
    EXPECT_GE(sticks, 10) << "the audit must cross stick-slip transitions";
    EXPECT_GT(log.stick_steps, 0);
  }
  EXPECT_GT(r.x[3], 0.1 * r.x[2]) << "friction must dissipate a real share of the input";
  EXPECT_FALSE(log.dissipation_decreased);
  // Tolerance 1e-8 of the energy scale: DP54 at rtol 1e-10 accumulates ~1e-10 per unit of
  // energy per step over ~1e3-1e4 steps and a few hundred events; one projection error of
  // m v_tol^2 / 2 ~ 1e-16 per stick entry is negligible. A wrong sign or mismatched force in
  // one mode breaks the balance at O(1) of the scale.
  EXPECT_LT(log.max_imbalance, 1e-8 * log.scale)
      << "W = " << r.x[2] << ", D = " << r.x[3] << ", events " << log.events.size();
}

TEST(EnergyAudit, CoulombStickSlipBalancesWorkDissipationAndEnergy) {
  audit(stickslip::CoulombLaw<double>(0.5, 0.3), true);
}

TEST(EnergyAudit, CoulombEqualCoefficientsBalance) {
  audit(stickslip::CoulombLaw<double>(0.4, 0.4), true);
}

TEST(EnergyAudit, StribeckStickSlipBalances) {
  audit(stickslip::StribeckLaw<double>(0.5, 0.3, 0.05), true);
}

TEST(EnergyAudit, RegularisedLawBalances) {
  audit(stickslip::RegularisedLaw<double>(0.4, 1e-3, stickslip::RegularisedShape::Tanh), false);
  audit(stickslip::RegularisedLaw<double>(0.4, 1e-3, stickslip::RegularisedShape::LinearSaturated),
        false);
}

}  // namespace
}  // namespace contact_coulomb_contact_energy_test
