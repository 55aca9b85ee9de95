// Fuzz harness: FrictionDampedSystem scenes with separation (Separation::Separate, restitution,
// landing speed), member-end walls (MemberEnd::Wall, wall restitution), the other member ends and
// the end policies, run by simulate with the energy audit on.
//
// Frame: an L-frame of steel (E = 2.06e11 Pa, rho = 7800 kg/m^3, A = 6e-5 m^2, I = 2e-11 m^4, the
// paper's blade section): a vertical member of length L1 clamped at its root, a horizontal arm of
// length L2 from its tip, each of `elements` equal elements.
// Layout of an input: L1, L2, elements integer, num_modes integer; damper count choice(3) and per
// damper (member choice(2), X0, m, k, N0, law choice(3) with its parameters as in
// model_fuzz.cpp, share, side flag, initial state, normal load flag, contact point flag,
// separation, restitution, landing speed, start end, finish end, wall restitution); load count
// choice(3) and per load (member choice(2), coordinate, direction choice(5), amplitude, omega,
// phase); model options (normal load flag, moving contact, convective terms, watch lift-off
// flags; end policy); run options (integrator choice(4), fixed_step, rtol, atol, max_steps
// integer); t_end. Enum values are one byte each (enum_byte): mostly valid, 8 of 256 byte values
// out of range (initial state: stick or slip, LiftOff / Separated for 8 byte values).
//
// Work bound: <= 8 elements per member, <= 4 modes, <= 2 dampers, max_steps <= 5000. Rules:
//  * an exception from building or running the scene is std::invalid_argument (a named input
//    error); anything else, std::domain_error included, is a violation (compute_modes may throw
//    domain_error before the scene is built: allowed there);
//  * an out-of-range enum value (initial state, separation, member end, end policy) is refused:
//    a system built with one is a violation;
//  * Success means t = t_end and a finite state and energy balance;
//  * on a Success run of an adaptive integrator (DormandPrince54, Rosenbrock23, Exponential) the
//    energy audit closes: |residual| <= 1e3 rtol scale + 1e3 atol, scale = the largest audit term
//    or |E0|. The terms are quadratures integrated with the state under the same local error
//    control (each step's error <= rtol |y| + atol per component, and a few hundred to a few
//    thousand steps here: the global error stays within ~1e3 local errors), and the impact and
//    wall losses are booked exactly at their events; a residual beyond that is energy created or
//    lost by the model, not integration error. RK4 (no error control) is not audited.
#include "fuzz/fuzz_input.hpp"
#include "fuzz/fuzz_laws.hpp"

#include <stickslip/model.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace separation_fuzz {

using namespace stickslip;
using stickslip_fuzz::require;
using stickslip_fuzz::str;
using System = FrictionDampedSystem<double>;

using stickslip_fuzz::read_law;

/// An enum value from one byte b: b < 240: b % common (the values a scene usually has);
/// 240 <= b < 248: b % all (every enumerator, e.g. the refused initial states LiftOff, Separated);
/// b >= 248: b itself, out of range (to be refused).
unsigned enum_byte(stickslip_fuzz::Input& in, unsigned common, unsigned all) {
  const unsigned b = in.byte();
  return b < 240 ? b % common : (b < 248 ? b % all : b);
}

void run(stickslip_fuzz::Input& in) {
  const SectionProperties<double> steel{2.06e11, 7800.0, 6e-5, 2e-11};
  const double L1 = in.real(0.02, 0.5), L2 = in.real(0.005, 0.2);
  const auto elements = static_cast<Eigen::Index>(std::clamp<long long>(in.integer(1, 8), -1, 8));
  ModalOptions<double> mo;
  mo.num_modes = static_cast<Eigen::Index>(std::clamp<long long>(in.integer(1, 4), -1, 4));
  mo.solver = ModalSolver::Dense;
  FrameModel<double> frame;
  const auto root = frame.add_node(0.0, 0.0), corner = frame.add_node(0.0, L1), end = frame.add_node(L2, L1);
  const MemberId members[2] = {frame.add_member(root, corner, steel, elements),
                               frame.add_member(corner, end, steel, elements)};
  frame.clamp(root);
  const ModalBasis<double> basis = compute_modes(frame.assemble(), mo);

  // From here on every exception must be an invalid_argument.
  try {
    std::vector<System::Damper> dampers;
    const unsigned nd = in.choice(3);
    for (unsigned i = 0; i < nd; ++i) {
      const MemberId member = members[in.choice(2)];
      const double L = frame.member(member).length;
      const double X0 = in.real(0.0, L), m = in.real(1e-3, 0.1), k = in.real(0.0, 1e4), N0 = in.real(0.0, 50.0);
      FrictionLawVariant<double> law = read_law(in);
      const double share = in.real(0.1, 1.0);
      System::Damper d(member, X0, m, k, N0, law, share);
      d.side = in.flag() ? -1.0 : 1.0;
      d.initial_state = static_cast<ContactState>(enum_byte(in, 3, 5));
      d.normal_load = in.flag() ? NormalLoad::Constant : NormalLoad::Inertial;
      d.contact_point = in.flag() ? ContactPoint::Fixed : ContactPoint::Moving;
      d.separation = static_cast<Separation>(enum_byte(in, 2, 2));
      d.restitution = in.real(0.0, 1.0);
      d.landing_speed = in.real(0.0, 1e-3);
      d.start_end = static_cast<MemberEnd>(enum_byte(in, 4, 4));
      d.finish_end = static_cast<MemberEnd>(enum_byte(in, 4, 4));
      d.wall_restitution = in.real(0.0, 1.0);
      dampers.push_back(d);
    }
    std::vector<System::Load> loads;
    const unsigned nl = in.choice(3);
    for (unsigned i = 0; i < nl; ++i) {
      const MemberId member = members[in.choice(2)];
      loads.push_back(stickslip_fuzz::read_load(in, member, frame.member(member).length, 200.0, 5e3));
    }
    ModelOptions<double> options;
    options.normal_load = in.flag() ? NormalLoad::Constant : NormalLoad::Inertial;
    options.moving_contact = in.flag();
    options.convective_terms = in.flag();
    options.watch_lift_off = in.flag();
    options.energy_audit = true;
    options.end_policy = static_cast<EndPolicy>(enum_byte(in, 3, 3));
    RunOptions<double> run;
    run.integrator = static_cast<Integrator>(in.choice(4));
    run.stepper.fixed_step = in.real(1e-7, 1e-4);
    run.stepper.rtol = in.real(1e-10, 1e-3);
    run.stepper.atol = in.real(1e-12, 1e-6);
    run.stepper.max_steps = static_cast<long>(std::clamp<long long>(in.integer(1, 5000), -1, 5000));
    const double t_end = in.real(0.0, 0.01);

    // An enum value outside its type's enumerators must be refused (by name) where it enters.
    bool out_of_range = static_cast<unsigned>(options.end_policy) > static_cast<unsigned>(EndPolicy::Extrapolate);
    for (const auto& d : dampers)
      out_of_range = out_of_range || static_cast<unsigned>(d.initial_state) > static_cast<unsigned>(ContactState::Separated) ||
                     static_cast<unsigned>(d.separation) > static_cast<unsigned>(Separation::Separate) ||
                     static_cast<unsigned>(d.start_end) > static_cast<unsigned>(MemberEnd::Wall) ||
                     static_cast<unsigned>(d.finish_end) > static_cast<unsigned>(MemberEnd::Wall);
    System sys(frame, basis, dampers, loads, options);
    require(!out_of_range, "FrictionDampedSystem accepted an out-of-range enum value (initial_state, separation, "
                           "start_end, finish_end or end_policy)");
    System::State x0 = sys.initial_state();
    DamperStates mode = sys.requested_mode();
    const bool consistent = sys.make_consistent(mode, 0.0, x0);
    static_cast<void>(consistent);  // a run started anyway must end with a status, as for a user
    const double E0 = sys.mechanical_energy(mode, 0.0, x0);
    NullObserver none;
    const auto r = simulate(sys, mode, 0.0, x0, t_end, run, none);
    if (r.status != Status::Success) {
      require(!r.message.empty(), std::string("status ") + to_string(r.status) + " without a message");
      return;
    }
    require(r.t == t_end, "Success at t = " + str(r.t) + " != t_end = " + str(t_end));
    require(r.x.allFinite(), "Success with a non-finite state");
    const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
    require(std::isfinite(bal.residual), "Success with a non-finite energy residual");
    if (run.integrator == Integrator::RungeKutta4) return;
    const double scale = std::max({std::abs(bal.mechanical), std::abs(bal.external_work), bal.viscous_dissipation,
                                   bal.friction_dissipation, std::abs(bal.slope_work), bal.impact_loss, std::abs(E0)});
    const double bound = 1e3 * (run.stepper.rtol * scale + run.stepper.atol);
    require(std::abs(bal.residual) <= bound,
            "energy audit residual " + str(bal.residual) + " (relative " + str(bal.residual / scale) + ") > " +
                str(bound) + " = 1e3 (rtol scale + atol) at t = " + str(r.t) + " (E = " + str(bal.mechanical) +
                ", E0 = " + str(E0) + ", W_ext = " + str(bal.external_work) + ", D_visc = " +
                str(bal.viscous_dissipation) + ", D_fric = " + str(bal.friction_dissipation) + ", W_slope = " +
                str(bal.slope_work) + ", D_imp = " + str(bal.impact_loss) + ")");
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const stickslip_fuzz::Violation&) {
    throw;
  } catch (const std::exception& e) {
    throw stickslip_fuzz::Violation(std::string("an exception other than invalid_argument: ") + e.what());
  }
}

}  // namespace separation_fuzz

STICKSLIP_FUZZ_ENTRY(separation, separation_fuzz::run)
