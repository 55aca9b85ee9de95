// Fuzz harness: the composed model end to end, FrictionDampedSystem + simulate on a fuzzed frame
// with fuzzed dampers, loads, model options and run options.
// Layout of an input: the frame (fuzz_frames.hpp); num_modes integer; Rayleigh alpha, beta; damper
// count choice(4) and per damper (member choice(2), X0, m, k, N0, law choice(3) with its
// parameters as in contact_fuzz.cpp, share, side flag, initial state choice(3), inertial flag);
// load count choice(3) and per load (member choice(2), coordinate, direction choice(5), amplitude,
// omega, phase); model options (constant normal load, moving contact, convective terms, watch
// lift-off, energy audit: flags; end policy choice(3)); run options (integrator choice(3),
// fixed_step, rtol, atol, max_steps integer, check_stability_limit flag); t_end; state-size
// choice(8) and mode-size choice(8) (6: one short, 7: one long, else right).
//
// Work bound: <= 8 modes, <= 3 dampers, max_steps <= 2000. Rules checked besides the exception
// types:
//  * a state or a DamperStates of the wrong size must be refused: a run that
//    returns normally with one is a violation (before the fix it reads past the buffer, which
//    ASan reports, or returns Success with wrong physics);
//  * without dampers and loads, the modal equations are q'' = -c q' - omega^2 q with the basis'
//    damping coefficients c = damping_coefficients() (closed form; Rayleigh alpha must reach a
//    rigid-body mode), to 1e-12 of the terms' size;
//  * Success means t = t_end, a finite state and, with the audit on, a finite energy residual;
//    other statuses carry a message.
#include "fuzz/fuzz_frames.hpp"
#include "fuzz/fuzz_laws.hpp"

#include <stickslip/model.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace model_fuzz {

using namespace stickslip;
using stickslip_fuzz::require;
using stickslip_fuzz::str;
using System = FrictionDampedSystem<double>;

using stickslip_fuzz::read_law;

/// One short (6), one long (7) or right (else).
Eigen::Index size_error(unsigned c) { return c == 6 ? -1 : (c == 7 ? 1 : 0); }

void check_free_modal_equations(System& sys, const ModalBasis<double>& basis) {
  const Eigen::Index n = sys.num_modes();
  System::State x = sys.initial_state(), dx(x.size());
  for (Eigen::Index j = 0; j < n; ++j) {
    x[j] = 1e-3 * double(j + 1);
    x[n + j] = 1e-2 * double(n - j);
  }
  sys.rhs(sys.requested_mode(), 0.0, x, dx);
  const auto& c = basis.damping_coefficients();
  const auto& w = basis.omega();
  for (Eigen::Index j = 0; j < n; ++j) {
    const double damping = c(j) * x[n + j], stiffness = w(j) * w(j) * x[j];
    const double expected = -damping - stiffness;
    if (!std::isfinite(expected)) continue;
    require(std::abs(dx[n + j] - expected) <= 1e-12 * (std::abs(damping) + std::abs(stiffness)),
            "mode " + std::to_string(j) + " (omega = " + str(w(j)) + ", c = " + str(c(j)) + "): q'' = " +
                str(dx[n + j]) + ", -c q' - omega^2 q = " + str(expected));
  }
}

void run(stickslip_fuzz::Input& in) {
  stickslip_fuzz::FuzzFrame f = stickslip_fuzz::build_frame(in);
  ModalOptions<double> mo;
  mo.num_modes = static_cast<Eigen::Index>(stickslip_fuzz::bounded_count(in.integer(1, 4), 8));
  mo.solver = ModalSolver::Dense;
  const double alpha = in.real(0.0, 20.0), beta = in.real(0.0, 1e-5);
  const ModalBasis<double> basis = compute_modes(f.frame.assemble(), mo).with_rayleigh_damping(alpha, beta);

  auto pick_member = [&] { return f.members[in.choice(static_cast<unsigned>(f.members.size()))]; };
  std::vector<System::Damper> dampers;
  const unsigned nd = in.choice(4);
  for (unsigned i = 0; i < nd; ++i) {
    const auto member = pick_member();
    const double L = f.frame.member(member).length;
    const double X0 = in.real(0.0, L), m = in.real(1e-3, 1.0), k = in.real(0.0, 1e5), N0 = in.real(0.0, 100.0);
    FrictionLawVariant<double> law = read_law(in);
    const double share = in.real(0.1, 1.0);
    System::Damper d(member, X0, m, k, N0, law, share);
    d.side = in.flag() ? -1.0 : 1.0;
    d.initial_state = static_cast<ContactState>(in.choice(3));
    d.normal_load = in.flag() ? NormalLoad::Inertial : NormalLoad::Constant;
    dampers.push_back(d);
  }
  std::vector<System::Load> loads;
  const unsigned nl = in.choice(3);
  for (unsigned i = 0; i < nl; ++i) {
    const auto member = pick_member();
    loads.push_back(stickslip_fuzz::read_load(in, member, f.frame.member(member).length, 100.0, 1e4));
  }
  ModelOptions<double> options;
  options.normal_load = in.flag() ? NormalLoad::Constant : NormalLoad::Inertial;
  options.moving_contact = in.flag();
  options.convective_terms = in.flag();
  options.watch_lift_off = in.flag();
  options.energy_audit = in.flag();
  options.end_policy = static_cast<EndPolicy>(in.choice(3));
  RunOptions<double> run;
  run.integrator = static_cast<Integrator>(in.choice(3));
  run.stepper.fixed_step = in.real(1e-7, 1e-4);
  run.stepper.rtol = in.real(1e-10, 1e-3);
  run.stepper.atol = in.real(1e-12, 1e-6);
  const long long max_steps = in.integer(1, 2000);
  run.stepper.max_steps = static_cast<long>(std::clamp<long long>(max_steps, -1, 2000));
  run.check_stability_limit = !in.flag();
  const double t_end = in.real(0.0, 0.01);
  const Eigen::Index state_error = size_error(in.choice(8)), mode_error = size_error(in.choice(8));

  System sys(f.frame, basis, dampers, loads, options);
  if (nd == 0 && nl == 0) check_free_modal_equations(sys, basis);

  System::State x0 = sys.initial_state();
  x0.conservativeResize(x0.size() + state_error);
  if (state_error > 0) x0.tail(state_error).setZero();
  DamperStates mode = sys.requested_mode();
  if (mode_error != 0) {
    DamperStates other(sys.num_dampers() + mode_error);  // throws for -1 dampers
    for (Eigen::Index i = 0; i < std::min(other.size(), mode.size()); ++i) other[i] = mode[i];
    mode = other;
  }
  const bool consistent = sys.make_consistent(mode, 0.0, x0);
  static_cast<void>(consistent);  // a run started anyway must end with a status, as for a user
  NullObserver none;
  const auto r = simulate(sys, mode, 0.0, x0, t_end, run, none);
  require(state_error == 0 && mode_error == 0,
          "simulate accepted a state of size " + std::to_string(x0.size()) + " and " +
              std::to_string(mode.size()) + " damper states for a system of state size " +
              std::to_string(sys.initial_state().size()) + " and " + std::to_string(sys.num_dampers()) +
              " dampers (status " + to_string(r.status) + ")");
  if (r.status == Status::Success) {
    require(r.t == t_end, "Success at t = " + str(r.t) + " != t_end = " + str(t_end));
    require(r.x.allFinite(), "Success with a non-finite state");
    if (options.energy_audit)
      require(std::isfinite(sys.energy_balance(r.mode, r.t, r.x, 0.0).residual),
              "Success with a non-finite energy residual");
  } else {
    require(!r.message.empty(), std::string("status ") + to_string(r.status) + " without a message");
  }
}

}  // namespace model_fuzz

STICKSLIP_FUZZ_ENTRY(model, model_fuzz::run)
