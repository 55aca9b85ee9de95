#pragma once
/// \file friction_damped_records.hpp
/// \brief What FrictionDampedSystem reports about a run: its contact switches and impacts, why
/// it stopped, a non-finite load, the forces of one evaluation, how the last solve was done, and
/// the energy audit. FrictionDampedSystem names each of them as a member type (e.g.
/// FrictionDampedSystem<double>::Evaluation is DamperEvaluation<double>).

#include "stickslip/contact/contact_state.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

namespace stickslip {

/// One contact switch, logged by `transition`.
template <class Scalar>
struct DamperContactEvent {
  /// Time of the switch: the located event, or the time given to make_consistent().
  Scalar t;
  /// Index of the damper that switched (0 .. num_dampers() - 1).
  Eigen::Index damper;
  /// Its state before the switch.
  ContactState from;
  /// Its state after the switch.
  ContactState to;
};

/// One impact of a separated damper on its member (docs/model_separation.md, "Separation"), or of a moving
/// contact on a wall at a member end ("Member ends"), logged by `transition`: the impulses and
/// relative velocities.
template <class Scalar>
struct DamperImpactEvent {
  Scalar t;               ///< time of the impact (the located gap event)
  Eigen::Index damper;           ///< index of the damper
  Scalar normal_impulse;  ///< L_n >= 0, pushing the damper off the member
  Scalar tangential_impulse;  ///< L_t on the damper along u (the member receives -L_t psi_u)
  Scalar normal_velocity;     ///< v_n = gap' before the impact (< 0: approaching)
  Scalar normal_velocity_after;  ///< gap' after: -e v_n (bounce) or 0 (landing)
  Scalar sliding_velocity;       ///< V before the impact
  Scalar sliding_velocity_after; ///< V after
  Scalar energy_loss;     ///< kinetic energy lost, booked in the audit's impact term
  ContactState to;        ///< Separated (bounce) or the contact state of the landing
  /// True for the impact of a moving contact on a MemberEnd::Wall (then only the tangential
  /// impulse and sliding velocities are set; `to` is the damper's state after it).
  bool wall = false;
};

/// Why the system stopped a run (kept with the damper and the time).
/// NonFiniteLoad: a point load's value was not finite at the start (make_consistent).
enum class DamperStopReason { None, LiftOff, LeftMember, NoConsistentState, NonFiniteLoad };

/// The most recent evaluation in which a point load's value F_l(t) was not finite (a
/// time_function returning NaN or an infinity): load_fault().
template <class Scalar>
struct LoadFault {
  Eigen::Index load = -1;  ///< index of the load (-1: none since construction)
  Scalar t = std::numeric_limits<Scalar>::quiet_NaN();      ///< the time of that evaluation
  Scalar value = std::numeric_limits<Scalar>::quiet_NaN();  ///< the value F_l(t)
  long count = 0;   ///< evaluations with a non-finite load value since construction
};

/// Forces and kinematics of the dampers at one (mode, t, x), from the coupled solve.
template <class Scalar>
struct DamperEvaluation {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;  ///< per-damper or modal values
  Vector qdd;    ///< modal accelerations
  Vector N;      ///< normal forces on the member [N]
  Vector f;      ///< friction forces on the dampers along u [N] (minus that on the member)
  Vector V;      ///< sliding velocities of dampers relative to the member [m/s]
  Vector Vdot;   ///< their time derivatives
  Vector xdd;    ///< damper accelerations
  Vector X;      ///< contact coordinates
  Vector slope;  ///< member slope q^T psi_w'(X) at the contacts
  Vector y;      ///< damper displacements along the contact normal, y = q^T psi_w(X) (eq 17); y_d in flight
  /// Gap y_member - y_d of a separated damper (>= 0 in flight, its guard), 0 in contact.
  Vector gap;
  /// Reaction of the wall on a damper resting against it along u [N] (DamperStates::wall;
  /// docs/model_separation.md "Resting at a wall"), 0 otherwise: the contact's tangential force is
  /// f + wall_force, f the friction share (at most mu_s N towards the wall).
  Vector wall_force;
  /// False when a force or acceleration is not finite (an overflowing state): rhs()
  /// then returns NaN for the stepper's finiteness check.
  bool finite = true;
};

/// How the last acceleration solve was done (docs/model_solve.md, "acceleration solve"): for cost
/// studies, and for tests that must reach every form.
struct DamperSolveInfo {
  Eigen::Index unknowns = 0;       ///< U, the forces solved for (0: every force known)
  bool mode_space = false;  ///< the n x n mode-space form, else the U x U capacitance form
  Eigen::Index system_size = 0;    ///< order of the factorised matrix (2, 4, 6, 8 when padded; else n or U)
  bool reused = false;      ///< the factorisation was kept from an earlier call
  /// Corrections of iterative refinement from an earlier factorisation of a slightly different
  /// matrix (0: none; the solve was direct, ModelOptions::refine_stale_factorisation).
  int refinements = 0;
  /// A system of order 4, 6 or 8 was solved with the pivoted LU: its block elimination failed
  /// the backward-error check (docs/model_solve.md, "acceleration solve"; rare, for matrices whose
  /// leading block is nearly singular).
  bool pivoted = false;
};

/// Terms of the energy balance  E(t) - E(t0) = W_ext - D_visc - D_fric + W_slope - D_imp.
template <class Scalar>
struct DamperEnergyBalance {
  Scalar mechanical;   ///< E(t): modal kinetic + strain + dampers' kinetic, spring, preload potential
  /// W_ext = integral of sum_l F_l(t) psi_l^T q' dt, work of the point loads.
  Scalar external_work;
  /// D_visc = integral of q'^T c q' dt >= 0, dissipated by modal damping.
  Scalar viscous_dissipation;
  /// D_fric = -integral of sum_i f_i V_i dt >= 0, dissipated by friction.
  Scalar friction_dissipation;
  Scalar slope_work;   ///< work of the normal forces as the contacts slide over a sloped member
  /// D_imp: kinetic energy lost in the impacts of separated dampers (0 without Separate dampers).
  Scalar impact_loss = Scalar(0);
  Scalar residual;     ///< (E(t) - E0) - (W_ext - D_visc - D_fric + W_slope - D_imp)
  /// False when the audit cannot close for this scene: a moving contact may go on past a member
  /// end (an end of kind MemberEnd::Extend) under EndPolicy::Clamp, where the shapes keep the
  /// end's value but also its slope and curvature, so the slope and convective terms do work
  /// the potential does not see (docs/howto/forces_events_energy.md). The residual then
  /// measures the integration only for runs whose contacts stayed on their members; with
  /// EndPolicy::Extrapolate the audit applies past the ends too.
  bool applies = true;
  /// |residual| / max(|E|, |W_ext|, D_visc, D_fric, |W_slope|, D_imp): the closing error relative
  /// to the audit's largest term (|residual| when every term is 0). Meant for a run that starts
  /// from rest (E0 = 0); with E0 != 0 compare against |E0| too.
  Scalar relative_residual() const {
    using std::abs;
    const Scalar scale = std::max({abs(mechanical), abs(external_work), viscous_dissipation,
                                   friction_dissipation, abs(slope_work), impact_loss});
    return scale > Scalar(0) ? abs(residual) / scale : abs(residual);
  }
};

}  // namespace stickslip
