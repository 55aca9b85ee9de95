#pragma once
/// \file friction_damped_system.hpp
/// \brief A frame's retained modes + any number of sliding point-contact friction dampers +
/// external point loads, as a hybrid system for HybridStepper (the paper's eqs 11-29,
/// generalised to N dampers on any members). The algebra is written out in docs/model.md.

#include "stickslip/beam.hpp"
#include "stickslip/contact.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/modal.hpp"
#include "stickslip/model/damper_states.hpp"
#include "stickslip/model/detail/enum_checks.hpp"
#include "stickslip/model/detail/law_visit.hpp"
#include "stickslip/model/detail/small_solve.hpp"
#include "stickslip/model/model_options.hpp"
#include "stickslip/model/point_damper.hpp"
#include "stickslip/model/point_load.hpp"
#include "stickslip/moving_load.hpp"
#include "stickslip/ode/hybrid_system.hpp"
#include "stickslip/ode/linear_part.hpp"
#include "stickslip/ode/step_rate.hpp"

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace stickslip {

namespace detail {

/// "2.56 kHz": the frequency omega / (2 pi) of an angular frequency omega [rad/s], 3 digits.
template <class Scalar>
std::string format_frequency(Scalar omega) {
  const double f = static_cast<double>(omega) / (2 * 3.14159265358979323846);
  const char* unit = f >= 1e6 ? " MHz" : (f >= 1e3 ? " kHz" : " Hz");
  const double scaled = f >= 1e6 ? f / 1e6 : (f >= 1e3 ? f / 1e3 : f);
  std::ostringstream os;
  os.precision(3);
  os << scaled << unit;
  return os.str();
}

inline bool is_slipping(ContactState s) noexcept {
  return s == ContactState::SlipPositive || s == ContactState::SlipNegative;
}
inline int slip_sign(ContactState s) noexcept {
  return s == ContactState::SlipPositive ? 1 : (s == ContactState::SlipNegative ? -1 : 0);
}
}  // namespace detail

/// Friction-damped modal system: a hybrid system (see stickslip/ode/hybrid_system.hpp).
///
/// Continuous state, in this order (offsets from the accessors):
///   q (n modal coordinates) | q' (n) | x_i (damper displacements along u, D) | x_i' (D)
///   | X_i (contact coordinates along the member, D, only with a moving contact)
///   | y_d, y_d' (flight coordinates of the S dampers that may separate: S + S, only when S > 0)
///   | W_ext, D_visc, D_fric, W_slope (energy-audit integrals, only with the audit on), D_imp
///   (impact losses, only with the audit on and S > 0 or a MemberEnd::Wall).
/// Discrete mode: DamperStates, one ContactState per damper.
///
/// Equations (paper eqs 11-25 generalised; m_i, k_i effective = share x mass/stiffness):
///   q'' + c q' + omega^2 q = sum_l F_l(t) psi_l + sum_i (N_i a_i - f_i b_i)               (25)
/// (c_j = ModalBasis::damping_coefficients(): 2 zeta_j omega_j, or alpha + beta omega_j^2)
///   m_i x_i'' + k_i x_i = f_i                                                            (11)
///   N_i = N0_i - m_i y_i'',  y_i'' = a_i^T q'' + 2 q'^T a_i' V_i + q^T a_i'' V_i^2 + s_i V_i' (19, 23)
///   V_i = X_i' = x_i' - q'^T b_i  (sliding velocity of the damper relative to the member)
/// with a_i = psi_w(X_i), b_i = psi_u(X_i), a' = psi_w', a'' = psi_w'', s_i = q^T psi_w'(X_i).
/// Slip: f_i = -sign(V_i) mu_k N_i (15-16); stick: V_i = 0 and f_i is the constraint force.
/// Separated (PointDamper::separation = Separate, after N_i reached 0): N_i = f_i = 0,
///   m_i y_d'' = N0_i (the preload pushes the damper back towards the member), guard
///   gap = y_i - y_d >= 0; at gap = 0 an impact (frictional_impact through the member's
///   impulse response) bounces or lands it (docs/model_separation.md, "Separation").
/// All unknowns (q'', N, f, x'') are solved together: known forces (constant N, f = -mu N of a
/// slipping damper) are eliminated, and the U <= 2D remaining ones solved in the cheaper of the
/// capacitance (Woodbury) form, a U x U system, and the mode-space form of the
/// identity-plus-low-rank matrix of eqs 26-29; the factorisation is kept over a stick phase
/// (docs/model_solve.md, "acceleration solve").
///
/// `Modes` fixes the number of retained modes at compile time (default Eigen::Dynamic: any
/// number, given by the basis): the hot loops of the solve then work on fixed-size views, which
/// for a few modes costs less than the loop and call overhead of dynamic sizes (docs/model_solve.md).
/// The state, outputs and interface are the same for either choice.
template <class Scalar_, class Law_ = FrictionLawVariant<Scalar_>, int Modes = Eigen::Dynamic>
class FrictionDampedSystem {
  static_assert(Modes == Eigen::Dynamic || Modes > 0, "FrictionDampedSystem: Modes must be > 0 or Dynamic");

 public:
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Friction law of every damper: one law type, or a std::variant of laws (default FrictionLawVariant).
  using Law = Law_;
  /// Number of retained modes fixed at compile time, or Eigen::Dynamic (template parameter `Modes`).
  static constexpr int modes_at_compile_time = Modes;
  /// Continuous state, of state_size() entries (layout in the class description).
  using State = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Dynamic column vector (modal vectors, per-damper values).
  using Vector = State;
  /// Dynamic matrix.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  /// Discrete mode: one ContactState per damper.
  using Mode = DamperStates;
  /// Index and size type (Eigen's).
  using Index = Eigen::Index;
  /// A damper of the scene.
  using Damper = PointDamper<Scalar, Law>;
  /// An external point load of the scene.
  using Load = PointLoad<Scalar>;
  /// Point values of the modes along one member (component 3).
  using Shapes = MemberShapes<Scalar>;
  /// Guard values of a mode, num_guards(mode) entries.
  using GuardVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// One contact switch, logged by `transition`.
  struct ContactEvent {
    /// Time of the switch: the located event, or the time given to make_consistent().
    Scalar t;
    /// Index of the damper that switched (0 .. num_dampers() - 1).
    Index damper;
    /// Its state before the switch.
    ContactState from;
    /// Its state after the switch.
    ContactState to;
  };

  /// One impact of a separated damper on its member (docs/model_separation.md, "Separation"), or of a moving
  /// contact on a wall at a member end ("Member ends"), logged by `transition`: the impulses and
  /// relative velocities.
  struct ImpactEvent {
    Scalar t;               ///< time of the impact (the located gap event)
    Index damper;           ///< index of the damper
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
  enum class StopReason { None, LiftOff, LeftMember, NoConsistentState, NonFiniteLoad };

  /// The most recent evaluation in which a point load's value F_l(t) was not finite (a
  /// time_function returning NaN or an infinity): load_fault().
  struct LoadFault {
    Index load = -1;  ///< index of the load (-1: none since construction)
    Scalar t = std::numeric_limits<Scalar>::quiet_NaN();      ///< the time of that evaluation
    Scalar value = std::numeric_limits<Scalar>::quiet_NaN();  ///< the value F_l(t)
    long count = 0;   ///< evaluations with a non-finite load value since construction
  };

  /// Forces and kinematics of the dampers at one (mode, t, x), from the coupled solve.
  struct Evaluation {
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
  struct SolveInfo {
    Index unknowns = 0;       ///< U, the forces solved for (0: every force known)
    bool mode_space = false;  ///< the n x n mode-space form, else the U x U capacitance form
    Index system_size = 0;    ///< order of the factorised matrix (2, 4, 6, 8 when padded; else n or U)
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
  struct EnergyBalance {
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

  /// Builds the system; throws std::invalid_argument on a bad damper, load or option.
  FrictionDampedSystem(const FrameModel<Scalar>& model, const ModalBasis<Scalar>& basis,
                       std::vector<Damper> dampers, std::vector<Load> loads = {},
                       ModelOptions<Scalar> options = {});

  // ---- layout ---------------------------------------------------------------------------------
  /// n, the number of retained modes.
  Index num_modes() const noexcept { return n_; }
  /// D, the number of dampers.
  Index num_dampers() const noexcept { return D_; }
  /// Offset of the modal coordinates q (n entries): 0.
  Index q_offset() const noexcept { return 0; }
  /// Offset of the modal velocities q' (n entries): n.
  Index qd_offset() const noexcept { return n_; }
  /// Offset of the damper displacements x_i along u (D entries): 2n.
  Index x_offset() const noexcept { return 2 * n_; }
  /// Offset of the damper velocities x_i' (D entries): 2n + D.
  Index xd_offset() const noexcept { return 2 * n_ + D_; }
  /// Offset of the contact coordinates (-1 without a moving contact).
  Index contact_offset() const noexcept { return options_.moving_contact ? 2 * n_ + 2 * D_ : -1; }
  /// Offset of the flight coordinates (-1 when no damper may separate): y_d of the S dampers that
  /// may separate (S entries, in damper order, slot flight_slot(i)), then their y_d' (S).
  Index flight_offset() const noexcept {
    return num_separable_ > 0 ? 2 * n_ + 2 * D_ + (options_.moving_contact ? D_ : 0) : -1;
  }
  /// S, the number of dampers that may separate (PointDamper::separation = Separate with an
  /// inertial normal load and lift-off watched).
  Index num_separable() const noexcept { return num_separable_; }
  /// Slot of damper i among the flight coordinates (0 .. S - 1), -1 when it cannot separate.
  Index flight_slot(Index i) const { return flight_slot_[static_cast<std::size_t>(i)]; }
  /// Offset of the energy-audit integrals (-1 without the audit).
  Index energy_offset() const noexcept {
    return options_.energy_audit ? 2 * n_ + 2 * D_ + (options_.moving_contact ? D_ : 0) + 2 * num_separable_ : -1;
  }
  /// Number of energy-audit integrals: 0 without the audit, 4 (W_ext, D_visc, D_fric, W_slope),
  /// 5 when a damper may separate or has a MemberEnd::Wall (D_imp, the impact losses, last).
  Index audit_size() const noexcept { return options_.energy_audit ? (has_impacts_ ? 5 : 4) : 0; }
  /// 2n + 2D, plus D with a moving contact, plus 2S flight coordinates, plus audit_size().
  Index state_size() const noexcept {
    return 2 * n_ + 2 * D_ + (options_.moving_contact ? D_ : 0) + 2 * num_separable_ + audit_size();
  }
  /// The modelling switches the system was built with.
  const ModelOptions<Scalar>& options() const noexcept { return options_; }
  /// The dampers, in the order of the state and of the mode.
  const std::vector<Damper>& dampers() const noexcept { return dampers_; }
  /// The external point loads.
  const std::vector<Load>& loads() const noexcept { return loads_; }
  /// Squared natural frequencies omega_j^2 of the retained modes [rad^2/s^2] (eq 25).
  const Vector& omega_squared() const noexcept { return omega2_; }
  /// The rates an explicit fixed step must resolve, each with what it belongs to (StepRate;
  /// upper half-plane of each conjugate pair; docs/howto/pick_an_integrator.md "Step rates"):
  ///  * every retained mode of eq 25, lambda = omega (-zeta + i sqrt(1 - zeta^2)) with
  ///    zeta = c / (2 omega) (two real rates omega (-zeta +- sqrt(zeta^2 - 1)) when zeta >= 1;
  ///    -c for a damped rigid-body mode): "mode j (f Hz)", j from 1;
  ///  * every damper's free oscillator x'' = -k x / m of eq 11 while it slips (and a regularised
  ///    law's saturated branch), lambda = i sqrt(k / m): "damper i slip oscillator sqrt(k/m)";
  ///  * every damper with a regularised law (no stick state, f = -mu(V) N): its slip equation
  ///    linearised at V = 0 with N = N0 (the preload, also for an inertial normal load),
  ///    \f$ \lambda^2 + 2\sigma\lambda + k/m = 0,\ 2\sigma = \mu'(0) N_0 / m + \sum_j \mu_j'(0)
  ///    N_{0j} \beta_j \f$, where beta_j bounds |psi_u|^2 (the member's modal inertia along u) at
  ///    damper j's contacts and the sum runs over the regularised dampers (they couple through the
  ///    member): "damper i regularised friction slope ...". Exact on a rigid member (beta = 0:
  ///    m x'' + mu'(0) N0 x' + k x = 0); 2 sigma bounds every real rate of the linearised system.
  ///  * every damper that may separate: its flight y_d'' = N0 / m, rate 0 (a separated
  ///    damper's tangential oscillator is the slip oscillator above; the member without its
  ///    contact forces has the modes' rates): "damper i flight ...".
  /// Stuck dampers need no rates of their own: in any stick pattern and at any contact point the
  /// structure's squared frequencies are Rayleigh quotients
  /// (q^T Omega^2 q + sum k (b^T q)^2) / (q^T q + sum m (b^T q)^2 + ...), mediants of the omega_j^2
  /// and the k_i / m_i, so they never exceed the largest of these rates (undamped). Used by
  /// simulate() to refuse a fixed RK4 step above the stability limit, naming the binding rate.
  std::vector<StepRate<Scalar>> step_rates() const;

  /// The eigenvalues of step_rates() without their names.
  std::vector<std::complex<Scalar>> linear_rates() const {
    std::vector<std::complex<Scalar>> rates;
    for (const auto& r : step_rates()) rates.push_back(r.lambda);
    return rates;
  }
  /// Modal row vector of the displacement of point `eps` of `member` along `direction`
  /// (GlobalX/GlobalY/Axial/Transverse; Moment gives the rotation): displacement = psi . q.
  /// The member must carry a damper or a load; throws std::invalid_argument otherwise.
  Vector point_shape(MemberId member, Scalar eps, LoadDirection direction) const {
    for (std::size_t s = 0; s < shape_members_.size(); ++s)
      if (shape_members_[s] == member) {
        Load probe;
        probe.member = member;
        probe.coordinate = eps;
        probe.direction = direction;
        return load_vector(s, probe);
      }
    detail::throw_invalid("FrictionDampedSystem::point_shape", "no damper or load on member", member);
  }

  /// Rest state: q = q' = 0, dampers at their supports, contacts at X0, audit integrals 0.
  State initial_state() const {
    State x = State::Zero(state_size());
    if (options_.moving_contact)
      for (Index i = 0; i < D_; ++i)
        x[contact_offset() + i] = dampers_[static_cast<std::size_t>(i)].contact_coordinate;
    return x;
  }

  /// The dampers' requested initial states.
  Mode requested_mode() const {
    Mode m(D_);
    for (Index i = 0; i < D_; ++i) {
      const bool stick = has_stick_[static_cast<std::size_t>(i)];
      m[i] = stick ? dampers_[static_cast<std::size_t>(i)].initial_state : ContactState::SlipPositive;
    }
    return m;
  }

  /// Checks that x has state_size() entries, mode has num_dampers() states, each a ContactState
  /// enumerator other than LiftOff, and that only dampers
  /// that may separate (flight_slot(i) >= 0) are ContactState::Separated (two comparisons and two per damper;
  /// done by evaluate() before every solve, so by rhs, guards, make_consistent and the outputs,
  /// and by simulate() before the first step).
  /// \throws std::invalid_argument naming `where`, the expected and the given sizes, or the
  ///         separated damper
  void validate_state(const Mode& mode, const State& x, const char* where = "FrictionDampedSystem") const {
    if (x.size() != state_size())
      throw std::invalid_argument(std::string(where) + ": state x has size " + std::to_string(x.size()) +
                                  ", expected state_size() = " + std::to_string(state_size()));
    if (mode.size() != D_)
      throw std::invalid_argument(std::string(where) + ": mode (DamperStates) has " +
                                  std::to_string(mode.size()) + " states, expected num_dampers() = " +
                                  std::to_string(D_));
    for (Index i = 0; i < D_; ++i) {  // only a damper with Separation::Separate has a flight state
      if (!detail::is_enumerator(mode[i], ContactState::Separated))
        detail::require_enumerator(where, "mode[" + std::to_string(i) + "]", "ContactState", mode[i],
                                   ContactState::Separated);
      if (mode[i] == ContactState::LiftOff)  // the model stops there, or separates (Separated)
        throw std::invalid_argument(std::string(where) + ": mode[" + std::to_string(i) +
                                    "] is lift_off, which the model never runs in (a damper is in contact "
                                    "- stick, slip - or Separated)");
      if (mode[i] == ContactState::Separated && flight_slot_[static_cast<std::size_t>(i)] < 0)
        throw std::invalid_argument(std::string(where) + ": mode[" + std::to_string(i) +
                                    "] is separated, but damper " + std::to_string(i) +
                                    " cannot separate (PointDamper::separation = Stop, or a "
                                    "constant normal load, or lift-off not watched)");
    }
    if (has_walls_) validate_walls(mode, where);
  }

  // ---- hybrid-system concept ------------------------------------------------------------------
  /// dx/dt in mode `mode` (the coupled solve of docs/model.md, then the state derivatives).
  void rhs(const Mode& mode, Scalar t, const State& x, State& dxdt) {
    const Evaluation& e = evaluate(mode, t, x);
    dxdt.resize(x.size());
    linear_derivative(e, x, dxdt);
    if (options_.energy_audit) {
      const auto qd = x.template segment<Modes>(n_, n_);
      Scalar p_ext = 0;
      for (Index l = 0; l < load_psi_.cols(); ++l)
        p_ext += loads_[static_cast<std::size_t>(l)].value(t) * load_psi_.col(l).dot(qd);
      const Index o = energy_offset();
      dxdt[o] = p_ext;
      dxdt[o + 1] = qd.dot(modal(modal_damping_).cwiseProduct(qd));
      dxdt[o + 2] = -e.f.dot(e.V);
      dxdt[o + 3] = options_.moving_contact ? -(e.N.array() * e.slope.array() * e.V.array()).sum() : Scalar(0);
      if (audit_size() > 4) dxdt[o + 4] = Scalar(0);  // D_imp changes at impacts only
    }
    if (!e.finite) dxdt.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
  }

  /// Number of guards in `mode`: per damper its contact guards (CoulombContact::num_guards:
  /// exact laws stuck two, mu_s N -+ f, slipping one, V; regularised laws none; then N when
  /// lift-off is watched; a separated damper one, its gap), then the member-end guards X and
  /// L - X while it can slide or fly with a moving contact and an end that does not extend
  /// (PointDamper::start_end / finish_end, MemberEnd; an extending end's guard is 1).
  Index num_guards(const Mode& mode) const {
    Index count = 0;
    for (Index i = 0; i < D_; ++i) count += guards_of(mode, i);
    return count;
  }

  /// Guard values at (mode, t, x), in the order of num_guards(); an event is a zero crossing in
  /// the direction of guard_direction().
  void guards(const Mode& mode, Scalar t, const State& x, GuardVector& g) {
    const Evaluation& e = evaluate(mode, t, x);
    g.resize(num_guards(mode));
    fill_guards(mode, e, g.data());
  }

  /// Crossing direction that triggers guard `idx` of `mode` (CoulombContact::guard_direction;
  /// member-end guards: Falling).
  CrossingDirection guard_direction(const Mode& mode, Index idx) const {
    for (Index i = 0; i < D_; ++i) {
      const Index nc = contact_guards_of(mode, i);
      if (idx < nc) {
        return detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [&](const auto& law) {
          return CoulombContact<std::decay_t<decltype(law)>>::guard_direction(mode[i], idx,
                                                                              watch_lift_off(i));
        });
      }
      idx -= nc;
      if (end_guards_of(mode, i)) {
        if (idx < 2) return CrossingDirection::Falling;
        idx -= 2;
      }
    }
    STICKSLIP_ASSERT(false && "guard index out of range");
    return CrossingDirection::Either;
  }

  /// Event handling: lift-off (Separation::Stop) and a contact leaving its member (MemberEnd::Stop)
  /// stop the run with a reason; a separable damper's lift-off, a gap closing (impact) and a wall
  /// are handled as in docs/model_separation.md ("Separation", "Member ends");
  /// stick/slip guards pick a consistent set of new contact states for all dampers (see
  /// docs/model.md) and reset a new stick's sliding velocity to exactly zero.
  TransitionAction transition(Mode& mode, const TriggeredGuards& triggered, Scalar t, State& x);

  /// A consistent initial mode for state x at t, starting from the requested states; it also
  /// reports lift-off at t0 (N <= 0), or a load whose value at t is not finite
  /// (NonFiniteLoad), through `stop_reason()`. Returns false when none exists.
  /// \throws std::invalid_argument when t or an entry of x is not finite, or x or mode is not
  ///         as validate_state() wants it (see validate_start)
  bool make_consistent(Mode& mode, Scalar t, State& x);

  // ---- outputs --------------------------------------------------------------------------------
  /// Forces and kinematics at (mode, t, x); the reference stays valid until the next call.
  /// \throws std::invalid_argument when x or mode has the wrong size or a separated damper
  ///         (see validate_state)
  const Evaluation& evaluate(const Mode& mode, Scalar t, const State& x);

  /// How the most recent solve (the most recent evaluate() that missed its cache) was done.
  const SolveInfo& last_solve() const noexcept { return solve_info_; }

  /// Contact switches logged since construction or the last clear_events(): one ContactEvent
  /// per damper whose state a resolution changed, from transition() and from make_consistent().
  /// So events().size() differs from the stepper's StepperStats::events (one per transition()
  /// call): a transition that switches k dampers logs k (two mirror dampers: 2 per stepper
  /// event), one that stops the run (lift-off, a member end) or keeps every state logs none, and
  /// make_consistent()'s switches at t0 are logged with no stepper event. Equal to the sum over
  /// the observer's EventRecords of the dampers whose state differs between `from` and `to`, plus
  /// make_consistent()'s switches (tests/model/event_log_test.cpp).
  const std::vector<ContactEvent>& events() const noexcept { return events_; }
  /// Impacts of separated dampers logged since construction or the last clear_events(), one per
  /// impact (a bounce is also logged in events() as a switch Separated -> Separated, a landing
  /// as Separated -> its contact state).
  const std::vector<ImpactEvent>& impacts() const noexcept { return impacts_; }
  /// Empties the event and impact logs (e.g. before a new run from the same system).
  void clear_events() {
    events_.clear();
    impacts_.clear();
  }
  /// Why the system last stopped a run or refused a start (None when it never did): set by
  /// transition() (LiftOff, LeftMember, NoConsistentState) and by make_consistent() (LiftOff at
  /// t0; a false return without lift-off leaves it as it was); never reset.
  StopReason stop_reason() const noexcept { return stop_reason_; }
  /// The damper stop_reason() refers to (-1 while it is None; the load for NonFiniteLoad).
  Index stop_damper() const noexcept { return stop_damper_; }
  /// The last evaluation whose load value was not finite (the evaluation is then not finite
  /// either: rhs() returns NaN, and simulate() names the load in its NonFiniteState message).
  const LoadFault& load_fault() const noexcept { return load_fault_; }

  /// The checks of a run's start, before any evaluation (simulate(), make_consistent()): t0
  /// finite, x0 and mode as validate_state() wants them, every entry of x0 finite, and no
  /// damper in ContactState::LiftOff (validate_state). `t_name`, `x_name`: the parameters'
  /// names in the messages. \throws std::invalid_argument naming `where` and the parameter
  void validate_start(const Mode& mode, Scalar t0, const State& x0, const char* where,
                      const char* t_name = "t0", const char* x_name = "x0") const {
    detail::require_finite(where, t_name, t0);
    validate_state(mode, x0, where);
    using std::isfinite;
    for (Index k = 0; k < x0.size(); ++k)
      if (!isfinite(x0[k]))
        detail::throw_invalid(where, std::string(x_name) + "[" + std::to_string(k) + "] must be finite", x0[k]);
  }

  /// Mechanical energy: modal kinetic + strain energy, the dampers' kinetic energy along u
  /// (and along w with an inertial normal load), spring energy, and the preload's potential.
  Scalar mechanical_energy(const Mode& mode, Scalar t, const State& x);

  /// Energy balance at (mode, t, x) against the mechanical energy E0 of the run's start.
  /// Requires the energy audit option (throws std::invalid_argument otherwise).
  EnergyBalance energy_balance(const Mode& mode, Scalar t, const State& x, Scalar E0) {
    if (!options_.energy_audit)
      detail::throw_invalid("FrictionDampedSystem::energy_balance", "energy_audit option is off", 0);
    EnergyBalance b;
    b.mechanical = mechanical_energy(mode, t, x);
    const Index o = energy_offset();
    b.external_work = x[o];
    b.viscous_dissipation = x[o + 1];
    b.friction_dissipation = x[o + 2];
    b.slope_work = x[o + 3];
    if (audit_size() > 4) b.impact_loss = x[o + 4];
    b.residual = (b.mechanical - E0) - (b.external_work - b.viscous_dissipation - b.friction_dissipation +
                                        b.slope_work - b.impact_loss);
    return b;
  }

  // ---- linear part per discrete mode (docs/model_solve.md, "Linear part per discrete mode")
  /// Number of linear components of linear_part(): the state without the energy-audit integrals,
  /// which are quadratures (their rates depend on t and the other components only).
  Index linear_size() const noexcept { return state_size() - audit_size(); }

  /// The linear part of mode `mode` at (t, x) (stickslip/ode/linear_part.hpp):
  ///   x_L' = A_m x_L + b_m(t) + r_m(t, x),   x_L = (q, q', x_d, x_d', X)  (linear_size()),
  /// with the contact coordinates frozen at the state's X (X0 without a moving contact): the X
  /// columns of A_m are zero. b_m = b0 + sum_k (bc_k cos w_k t + bs_k sin w_k t) holds the
  /// preloads N0 and the harmonic loads (F = a sin(w t + phi) + offset). Exact (r_m = 0) when no
  /// load has a time_function and every damper sticks, or slips at a fixed contact under a
  /// CoulombLaw. Otherwise (exact = false) A_m is the fixed-contact form at the frozen X with the
  /// slip coefficients frozen at mu(V) of x (convective terms, slope coupling, the motion of X
  /// and time_function loads left to r_m), and b0 is corrected so that r_m(t, x) = 0. Affine
  /// guards (the rows of guards(), Gx x_L + g(t)) in exact modes; in inexact modes those of the
  /// frozen linear part (frozen_guard_rows) when lp.want_inexact_guards, none otherwise. With the energy
  /// audit, an exact mode also gives the audit's four rates as quadratic forms (quadrature_forms:
  /// external work, viscous and friction dissipation, slope work). `version`
  /// changes when the mode, a frozen X or a frozen slip coefficient changes. Returns false when
  /// the evaluation at (t, x) is not finite. Allocates nothing once lp has the sizes of the mode
  /// (after the system's first call). Throws std::invalid_argument on a wrong size of x or mode.
  bool linear_part(const Mode& mode, Scalar t, const State& x, LinearPart<Scalar>& lp);

  // ---- Jacobian df/dx (the variational equations of shooting; has_jacobian_v) -------
  /// J = df/dx of rhs() in mode `mode` at (t, x), state_size() x state_size(). Where the mode is
  /// exact (linear_part: every damper stuck, or slipping or flying at a fixed contact under a
  /// CoulombLaw, no time_function load) J_LL = A_m of linear_part, the audit rows are
  /// d(z^T Q_j z)/dx_L = ((Q_j + Q_j^T) z)_L. Where a contact slides along its member under a
  /// CoulombLaw (no damper in flight or at a wall), every column but X is the tangent of the
  /// solve, (A + L^T F) du = rho - L^T dr0, dq'' = dr0 + F du (docs/model_solve.md, "Jacobian df/dx").
  /// In both cases the contact-coordinate columns X (frozen in A_m) are the same solve's
  /// derivative in X (the shapes' derivatives up to psi_w''' at X), unless a damper is in flight
  /// or at a wall: then central differences of rhs. Elsewhere every column is a central difference,
  /// (f(x + h e_j) - f(x - h e_j)) / 2h with h = 1e-6 max(1, |x_j|). J is NaN where the
  /// evaluation at x is not finite. Allocates nothing once J and the work vectors have their
  /// sizes. Throws std::invalid_argument on a wrong size of x or mode.
  void jacobian(const Mode& mode, Scalar t, const State& x, Matrix& J);


 private:
  // Number of guards of damper i in mode: contact guards (from the contact component, incl.
  // the lift-off guard when watched) followed by two member-end guards when they apply.
  Index contact_guards_of(const Mode& mode, Index i) const {
    return detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [&](const auto& law) {
      using L = std::decay_t<decltype(law)>;
      return CoulombContact<L>::num_guards(mode[i], watch_lift_off(i));
    });
  }
  /// Lift-off is watched for dampers whose normal force varies.
  bool watch_lift_off(Index i) const {
    return options_.watch_lift_off && inertial_[static_cast<std::size_t>(i)];
  }
  bool end_guards_of(const Mode& mode, Index i) const {
    const std::size_t iu = static_cast<std::size_t>(i);
    if (!moving_[iu] || (end_kind_[iu][0] == MemberEnd::Extend && end_kind_[iu][1] == MemberEnd::Extend)) return false;
    return !has_stick_[static_cast<std::size_t>(i)] || detail::is_slipping(mode[i]) ||
           mode[i] == ContactState::Separated;
  }
  Index guards_of(const Mode& mode, Index i) const {
    return contact_guards_of(mode, i) + (end_guards_of(mode, i) ? 2 : 0);
  }

  /// The guards of `mode` from an evaluation, into g[0 .. num_guards(mode)): per damper its
  /// contact guards (CoulombContact::guards), then X and L - X when end_guards_of.
  void fill_guards(const Mode& mode, const Evaluation& e, Scalar* g) const {
    Index k = 0;
    for (Index i = 0; i < D_; ++i) {
      const std::size_t iu = static_cast<std::size_t>(i);
      const Index nc = contact_guards_of(mode, i);
      if (mode[i] == ContactState::Separated)
        CoulombContact<CoulombLaw<Scalar>>::gap_guard(e.gap[i], g + k);
      else if (nc > 0)
        detail::with_law(dampers_[iu].law, [&](const auto& law) {
          CoulombContact<std::decay_t<decltype(law)>> contact(law);
          contact.guards(mode[i], e.V[i], e.N[i], e.f[i] + e.wall_force[i], watch_lift_off(i), g + k);
        });
      if (has_walls_ && mode[i] == ContactState::Stick && mode.wall(i) != WallRest::None)
        rest_guard(mode.wall(i), e.N[i], g + k);
      k += nc;
      if (end_guards_of(mode, i)) {
        const Scalar L = shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
        // (an end that extends keeps a constant guard, so that the guard count stays two)
        g[k++] = end_kind_[iu][0] != MemberEnd::Extend ? e.X[i] : Scalar(1);
        g[k++] = end_kind_[iu][1] != MemberEnd::Extend ? L - e.X[i] : Scalar(1);
        if (has_walls_ && mode[i] == ContactState::Separated) hold_guard(mode.wall(i), e.f[i] + e.wall_force[i], g + k - 2);
      }
    }
  }

  /// Derivative of the state's first linear_size() components from an evaluation:
  /// (q', q'', x_d', x_d'', X') - the X rows only when a contact moves: X' = V for a moving
  /// contact, 0 for a fixed one.
  template <class Out>
  void linear_derivative(const Evaluation& e, const State& x, Out& d) const {
    d.template segment<Modes>(0, n_) = x.template segment<Modes>(n_, n_);
    d.template segment<Modes>(n_, n_) = modal(e.qdd);
    d.segment(x_offset(), D_) = x.segment(xd_offset(), D_);
    d.segment(xd_offset(), D_) = e.xdd;
    if (options_.moving_contact)
      for (Index i = 0; i < D_; ++i)
        d[contact_offset() + i] = moving_[static_cast<std::size_t>(i)] ? e.V[i] : Scalar(0);
    flight_derivative(x, d);
  }

  /// The flight rows of the derivative: y_d' and y_d'' = N0 / m of a separated damper (its
  /// preload pushes it towards the member, docs/model_separation.md "Separation"); 0 for a damper in
  /// contact (its flight coordinates wait, unused, until a lift-off sets them). Uses flying_ of
  /// the evaluation's solve.
  template <class Out>
  void flight_derivative(const State& x, Out& d) const {
    for (Index i = 0; i < D_; ++i) {
      const std::size_t iu = static_cast<std::size_t>(i);
      const Index k = flight_slot_[iu];
      if (k < 0) continue;
      const Index y = flight_offset() + k, yd = y + num_separable_;
      d[y] = flying_[iu] ? x[yd] : Scalar(0);
      d[yd] = flying_[iu] ? dampers_[iu].preload / dampers_[iu].effective_mass() : Scalar(0);
    }
  }

  Vector load_vector(std::size_t shape, const Load& load) const {
    const Shapes& shapes = shapes_[shape];
    if (!shapes.contains(load.coordinate))
      detail::throw_invalid("PointLoad", "coordinate must lie on member " + std::to_string(load.member) +
                                             " (valid range [0, " + detail::format_value(shapes.length()) + "])",
                            load.coordinate);
    const typename Shapes::Values v = shapes.evaluate(load.coordinate);
    return load_direction_row(v, shape_direction_[shape].first, shape_direction_[shape].second, load.direction);
  }

  void allocate_workspace() {
    const Index D2 = 2 * D_;
    values_.resize(static_cast<std::size_t>(D_));
    cursors_.assign(static_cast<std::size_t>(D_), ElementCursor{});
    for (auto& v : values_) v.resize(n_);
    C_.setZero(n_, D2);
    dpsi_w_.setZero(n_, D_);
    S_.setZero(D2, D2);
    key_.setZero(4 * D2);
    shapes_X_.setConstant(D_, std::numeric_limits<Scalar>::quiet_NaN());  // nothing evaluated yet
    factor_key_.setZero(4 * D2);
    factor_unknowns_ = -1;
    lu_sized_.assign(static_cast<std::size_t>(D2 + 1), Eigen::PartialPivLU<Matrix>());
    rhs_.setZero(D2);
    r0_.setZero(n_);
    for (Vector* v : {&b_n_, &res_n_, &dz_n_}) v->setZero(n_);
    for (Vector* v : {&b_u_, &res_u_, &dz_u_}) v->setZero(D2);
    d_.setZero(D_);
    mu_.setZero(D_);
    // (rows n..padded_order(n) stay zero: the fixed-size mode-space form reads K = padded_order(n)
    // rows of every column for n <= 8; everything else reads and writes the first n)
    F_.setZero(padded_order(n_), D2);
    L_.setZero(padded_order(n_), D2);
    A_.setZero(D2);
    c_.setZero(D2);
    u_.setZero(D2);
    unknown_of_.assign(static_cast<std::size_t>(D2), 0);
    slip_b_.setZero(n_, D_);
    Mn_.setZero(n_, n_);
    lun_ = Eigen::PartialPivLU<Matrix>(n_);
    eval_.qdd.setZero(n_);
    for (Vector* v : {&eval_.N, &eval_.f, &eval_.V, &eval_.Vdot, &eval_.xdd, &eval_.X, &eval_.slope, &eval_.y, &eval_.gap,
                      &eval_.wall_force})
      v->setZero(D_);
    flying_.assign(static_cast<std::size_t>(D_), 0);
    impacts_.reserve(has_impacts_ ? 1024 : 0);
    if (has_impacts_) {  // the impulse response of transition() works in the probe workspace
      allocate_linear_part_workspace();
      response_.setZero(n_, 2);
      response_x_.setZero(D_, 2);
      impulse_dir_.setZero(n_, 2);
    }
    cache_x_.resize(0);
    events_.reserve(1024);
    involved_.reserve(static_cast<std::size_t>(D_));
  }

  /// Shapes of damper i at contact coordinate X into C_ and its slope column. Kept while X
  /// is unchanged (bitwise): a stuck damper's X is exactly constant over every stage of a stick
  /// phase, so its shapes are evaluated once per phase.
  void evaluate_shapes(Index i, Scalar X) const {
    if (shapes_X_[i] == X) return;
    shapes_X_[i] = X;
    const std::size_t iu = static_cast<std::size_t>(i);
    auto& v = values_[iu];
    shapes_[static_cast<std::size_t>(damper_shape_[iu])].evaluate(X, v, cursors_[iu]);
    const Scalar side = dampers_[iu].side;  // y_i is measured along side * w
    C_.col(i) = side * v.psi_w;
    C_.col(D_ + i) = v.psi_u;
    dpsi_w_.col(i) = side * v.dpsi_w;
  }

  /// Frozen affine guards of an inexact mode (long Lawson steps while slipping),
  /// completed from the rows of guards() that linear_part_by_probes recorded under the frozen solve
  /// (X = lp_X_, mu = lp_mu_): an end guard reads the frozen linear part's X (g = X, L - X), and
  /// g0 is corrected so that the rows Gx x_L + g(t) equal guards() at (t, x).
  void frozen_guard_rows(const Mode& mode, Scalar t, const State& x, LinearPart<Scalar>& lp);

  // ---- linear part per discrete mode: helpers -----------------------------------------------
  void allocate_linear_part_workspace() {
    lp_xs_.setZero(state_size());
    for (Vector* v : {&lp_f_, &lp_b_}) v->setZero(linear_size());
    for (Vector* v : {&lp_X_, &lp_mu_, &lp_key_X_, &lp_key_mu_}) v->setZero(D_);
    lp_g_.setZero(D_ * (CoulombContact<CoulombLaw<Scalar>>::max_guards + 2));
    lp_preload_.assign(static_cast<std::size_t>(D_), Scalar(0));
  }

  /// A_m, b_m and (exact modes without end guards; inexact ones with frozen_guards, completed by
  /// frozen_guard_rows) the affine guards of `mode` by probing the
  /// frozen solve (solve_forces<true>: X = lp_X_, mu = lp_mu_), which is affine in x_L, N0 and the
  /// load values: b0 at x_L = 0; with the preloads set to zero, column j of A_m at x_L = e_j
  /// and load l's response at unit load (no differences, so nothing cancels). Each probe reuses
  /// the factorisation of the frozen matrix, which is refactorised at the first probe when a
  /// slipping contact moves (its rows are otherwise formed in element space) and after the last.
  void linear_part_by_probes(const Mode& mode, bool exact, bool moving_slip, bool frozen_guards,
                             LinearPart<Scalar>& lp) {
    using std::cos;
    using std::sin;
    using std::abs;
    const Index P = linear_size(), probed = 2 * n_ + 2 * D_;  // X columns: zero (X frozen)
    bool end_guards = false;
    for (Index i = 0; i < D_; ++i) end_guards = end_guards || end_guards_of(mode, i);
    const Index G = (exact && !end_guards) || (!exact && frozen_guards) ? num_guards(mode) : 0;
    lp.omega.clear();
    for (const Load& l : loads_)
      if (!l.time_function && l.omega != Scalar(0) &&
          std::find(lp.omega.begin(), lp.omega.end(), abs(l.omega)) == lp.omega.end())
        lp.omega.push_back(abs(l.omega));
    const Index K = static_cast<Index>(lp.omega.size());
    // The audit's rates as quadratic forms in z = (x_L, 1, cos w_k t, sin w_k t) (exact modes):
    // the friction forces f and slip velocities V are affine in z, recorded at every probe.
    const bool forms = exact && options_.energy_audit;
    const Index nz = P + 1 + 2 * K;
    if (forms) {
      lp_fz_.setZero(D_, nz);
      lp_vz_.setZero(D_, nz);
    }
    auto record = [&](Index col, Scalar scale) {
      if (!forms) return;
      lp_fz_.col(col) += scale * eval_.f;
      lp_vz_.col(col) += scale * eval_.V;
    };
    lp.A.setZero(P, P);
    lp.bc.setZero(P, K);
    lp.bs.setZero(P, K);
    lp.Gx.setZero(G, G > 0 ? P : 0);
    lp.gc.setZero(G, K);
    lp.gs.setZero(G, K);

    const bool refine = options_.refine_stale_factorisation;
    options_.refine_stale_factorisation = false;  // a direct solve of the frozen matrix at every probe
    if (moving_slip) factor_unknowns_ = -1;
    lp_xs_.setZero();
    if (options_.moving_contact) lp_xs_.segment(contact_offset(), D_) = lp_X_;
    frozen_probe(mode, -1, G);
    record(P, Scalar(1));
    lp.b0 = lp_f_;
    lp.g0 = lp_g_.head(G);
    for (Index i = 0; i < D_; ++i) std::swap(lp_preload_[static_cast<std::size_t>(i)], dampers_[static_cast<std::size_t>(i)].preload);
    const Index flight = 2 * num_separable_;  // the flight columns y_d, y_d' follow X
    for (Index jj = 0; jj < probed + flight; ++jj) {
      const Index j = jj < probed ? jj : flight_offset() + (jj - probed);
      lp_xs_[j] = Scalar(1);
      frozen_probe(mode, -1, G);
      lp_xs_[j] = Scalar(0);
      record(j, Scalar(1));
      lp.A.col(j) = lp_f_;
      if (G > 0) lp.Gx.col(j) = lp_g_.head(G);
    }
    for (Index l = 0; l < static_cast<Index>(loads_.size()); ++l) {
      const Load& load = loads_[static_cast<std::size_t>(l)];
      if (load.time_function) continue;  // left to the remainder
      frozen_probe(mode, l, G);
      // F = a sin(w t + phi) + offset = a sin(phi) cos(w t) + a cos(phi) sin(w t) + offset
      const Scalar cosine = load.amplitude * sin(load.phase), sine = load.amplitude * cos(load.phase);
      if (load.omega == Scalar(0)) {
        record(P, load.offset + cosine);
        lp.b0 += (load.offset + cosine) * lp_f_;
        lp.g0 += (load.offset + cosine) * lp_g_.head(G);
        continue;
      }
      lp.b0 += load.offset * lp_f_;
      lp.g0 += load.offset * lp_g_.head(G);
      const Index k = static_cast<Index>(std::find(lp.omega.begin(), lp.omega.end(), abs(load.omega)) - lp.omega.begin());
      const Scalar s = load.omega < 0 ? -sine : sine;  // sin(-w t + phi) = sin(phi) cos(w t) - cos(phi) sin(w t)
      record(P, load.offset);
      record(P + 1 + 2 * k, cosine);
      record(P + 2 + 2 * k, s);
      lp.bc.col(k) += cosine * lp_f_;
      lp.bs.col(k) += s * lp_f_;
      lp.gc.col(k) += cosine * lp_g_.head(G);
      lp.gs.col(k) += s * lp_g_.head(G);
    }
    for (Index i = 0; i < D_; ++i) std::swap(lp_preload_[static_cast<std::size_t>(i)], dampers_[static_cast<std::size_t>(i)].preload);
    options_.refine_stale_factorisation = refine;
    if (moving_slip) factor_unknowns_ = -1;  // rhs() forms these rows in element space
    cache_valid_ = false;
    if (forms) audit_forms(P, K, lp);
  }

  /// The energy audit's rates (rhs) as quadratic forms z^T Q_j z of an exact mode
  /// (LinearPart::quadrature_forms): W_ext' = sum_l F_l(t) psi_l . q' with F_l in the clock
  /// components of z, D_visc' = q'^T diag(c) q', D_fric' = -f . V with f = lp_fz_ z and
  /// V = lp_vz_ z, W_slope' = 0 (a stuck damper has V = 0, an exact slipping one a fixed contact).
  void audit_forms(Index P, Index K, LinearPart<Scalar>& lp) const {
    using std::abs;
    using std::sin;
    using std::cos;
    const Index nz = P + 1 + 2 * K;
    lp.quadrature_forms.resize(static_cast<std::size_t>(audit_size()));  // D_imp (5th): rate 0
    for (Matrix& q : lp.quadrature_forms) q.setZero(nz, nz);
    for (Index l = 0; l < static_cast<Index>(loads_.size()); ++l) {
      const Load& load = loads_[static_cast<std::size_t>(l)];
      const auto psi = load_psi_.col(l).transpose();
      const Scalar cosine = load.amplitude * sin(load.phase), sine = load.amplitude * cos(load.phase);
      if (load.omega == Scalar(0)) {
        lp.quadrature_forms[0].block(P, n_, 1, n_) += (load.offset + cosine) * psi;
        continue;
      }
      const Index k = static_cast<Index>(std::find(lp.omega.begin(), lp.omega.end(), abs(load.omega)) - lp.omega.begin());
      const Scalar s = load.omega < 0 ? -sine : sine;
      lp.quadrature_forms[0].block(P, n_, 1, n_) += load.offset * psi;
      lp.quadrature_forms[0].block(P + 1 + 2 * k, n_, 1, n_) += cosine * psi;
      lp.quadrature_forms[0].block(P + 2 + 2 * k, n_, 1, n_) += s * psi;
    }
    lp.quadrature_forms[1].diagonal().segment(n_, n_) = modal_damping_.head(n_);
    lp.quadrature_forms[2].noalias() = -lp_fz_.transpose() * lp_vz_;
  }

  /// One probe: the frozen solve at the probe state lp_xs_ with load `load` at unit value (none
  /// for -1); the derivative of x_L into lp_f_ and, for G > 0, the guards into lp_g_.
  void frozen_probe(const Mode& mode, Index load, Index G) {
    structural_r0(lp_xs_);
    if (load >= 0) r0_ += load_psi_.col(load);
    solve_forces<true>(mode, lp_xs_);
    linear_derivative(eval_, lp_xs_, lp_f_);
    if (G > 0) fill_guards(mode, eval_, lp_g_.data());
  }

  /// Signed slip coefficient mu_i with f_i = -mu_i N_i for a slipping (or regularised) damper.
  Scalar slip_coefficient(Index i, ContactState s, Scalar V) const {
    using std::isnan;
    const Scalar constant = kinetic_constant_[static_cast<std::size_t>(i)];
    if (!isnan(constant)) return Scalar(detail::slip_sign(s)) * constant;
    return detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [&](const auto& law) -> Scalar {
      using L = std::decay_t<decltype(law)>;
      using std::abs;
      if constexpr (L::has_stick_state)
        return Scalar(detail::slip_sign(s)) * law.kinetic_coefficient(abs(V));
      else
        return law.coefficient(V);
    });
  }

  /// The coupled solve for (q'', N, f, x'') in mode `mode` (docs/model_solve.md, "acceleration solve").
  /// Known forces (constant N, f = -mu N of a slipping damper) are eliminated first; the U <= 2D
  /// remaining unknowns u satisfy  A u + L^T q'' = c  with  q'' = r0 + F u  (A diagonal, F and L
  /// n x U). Solved in the smaller of two equivalent forms: the capacitance (Woodbury) system
  /// (A + L^T F) u = c - L^T r0, or the mode-space system (I + F A^-1 L^T) q'' = r0 + F A^-1 c,
  /// used with A = I (rows with |A_jj| >= 1/2 are divided by A_jj as they are assembled).
  void solve(const Mode& mode, Scalar t, const State& x) const {
    structural_r0(x);
    using std::isfinite;
    for (Index l = 0; l < load_psi_.cols(); ++l) {
      const Scalar F = loads_[static_cast<std::size_t>(l)].value(t);
      if (!isfinite(F)) load_fault_ = LoadFault{l, t, F, load_fault_.count + 1};
      r0_.noalias() += F * load_psi_.col(l);
    }
    solve_forces<false>(mode, x);
  }

  /// r0_ = -omega^2 q - c q' with the basis' modal damping coefficients c (2 zeta omega, or
  /// alpha + beta omega^2 for Rayleigh damping; r0 of docs/model_solve.md without the loads).
  void structural_r0(const State& x) const {
    const auto q = x.template segment<Modes>(0, n_);
    const auto qd = x.template segment<Modes>(n_, n_);
    modal(r0_).noalias() = -modal(omega2_).cwiseProduct(q) - modal(modal_damping_).cwiseProduct(qd);
  }

  /// The solve after r0_ = r0 (docs/model_solve.md) is formed. Frozen (linear_part): every damper's
  /// rows as at a fixed contact at the state's X (a slipping damper's too: no convective terms,
  /// no slope coupling) with the slip coefficient lp_mu_ instead of the law's.
  template <bool Frozen>
  void solve_forces(const Mode& mode, const State& x) const {
    const Index n = n_, D = D_;
    const auto q = x.template segment<Modes>(0, n);
    const auto qd = x.template segment<Modes>(n, n);
    Evaluation& e = eval_;
    num_unknowns_ = 0;
    for (Index i = 0; i < D; ++i) {
      const std::size_t iu = static_cast<std::size_t>(i);
      const Damper& dmp = dampers_[iu];
      const bool moving = moving_[iu];
      if (moving) {
        const Scalar X = x[contact_offset() + i];
        e.X[i] = X;
        using std::isfinite;
        if (!isfinite(X)) {  // a blown-up trial state: report it as non-finite (no shapes at NaN)
          for (Vector* v : {&e.qdd, &e.N, &e.f, &e.V, &e.Vdot, &e.xdd, &e.slope, &e.y, &e.gap})
            v->setConstant(std::numeric_limits<Scalar>::quiet_NaN());
          e.finite = false;
          return;
        }
      } else {
        e.X[i] = dmp.contact_coordinate;
      }
      const ContactState s = mode[i];
      flying_[iu] = s == ContactState::Separated;
      e.gap[i] = Scalar(0);
      if (flying_[iu]) {
        flight_rows(i, x);
        if (has_walls_ && mode.wall(i) != WallRest::None) hold_rows(i, x);
        continue;
      }
      const bool stuck = has_stick_[iu] && s == ContactState::Stick;
      if (!Frozen && moving && !stuck) {  // the contact moves at every call: element-space products
        moving_damper(i, mode, x);
        continue;
      }
      if (moving) evaluate_shapes(i, e.X[i]);  // kept over a stick phase (X constant)
      const auto a = C_.col(i), b = C_.col(D + i);
      const Scalar m = dmp.effective_mass(), k = dmp.effective_stiffness();
      const Scalar xi = x[x_offset() + i];
      const Scalar V = stuck ? Scalar(0) : x[xd_offset() + i] - qd.dot(b);
      e.V[i] = V;
      // Only stuck dampers and slipping dampers at a fixed contact come here (moving ones went to
      // moving_damper): no convective terms (V = 0, or convective_terms off without a moving
      // contact), and the slope enters only the outputs and the audit.
      e.slope[i] = moving ? q.dot(dpsi_w_.col(i)) : Scalar(0);
      e.y[i] = q.dot(a);
      d_[i] = 0;
      const bool inertial = inertial_[iu];
      if (stuck) {  // stick rows (eq 11 with x'' = b^T q''): N_i + m a^T q'' = N0, f_i - m b^T q'' = k x
        if (inertial) {
          const Index j = add_unknown(i, Scalar(1), dmp.preload, Scalar(0), Scalar(0));
          modal(F_.col(j)) = a;
          modal(L_.col(j)) = m * a;
        } else {
          e.N[i] = dmp.preload;
          r0_.noalias() += dmp.preload * a;
        }
        const Index j = add_unknown(i, Scalar(1), k * xi, Scalar(0), Scalar(0), D + i);
        modal(F_.col(j)) = -b;
        modal(L_.col(j)) = -m * b;
      } else {  // slip rows (15-16 with 19 and 22): f_i = -mu_i N_i
        const Scalar mu = Frozen ? lp_mu_[i] : slip_coefficient(i, s, V);
        mu_[i] = mu;
        if (inertial) {
          const Index j = add_unknown(i, Scalar(1), dmp.preload, mu, Scalar(0));
          modal(F_.col(j)) = a + mu * b;
          modal(L_.col(j)) = m * a;
        } else {
          e.N[i] = dmp.preload;
          e.f[i] = -mu * dmp.preload;
          r0_.noalias() += dmp.preload * (a + mu * b);
        }
      }
    }

    const Index U = num_unknowns_;
    solve_info_ = SolveInfo{};
    if (U > 0) solve_unknowns(U);
    else e.qdd = r0_;  // every force known (all dampers slipping under constant normal load)
    for (Index j = 0; j < U; ++j) {
      const Index col = unknown_of_[static_cast<std::size_t>(j)];
      (col < D ? e.N[col] : e.f[col - D]) = u_[j];
    }
    for (Index i = 0; i < D; ++i) {
      const std::size_t iu = static_cast<std::size_t>(i);
      const Damper& dmp = dampers_[iu];
      const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
      const bool held = flying_[iu] && mode.wall(i) != WallRest::None;  // in flight, held by a wall
      Scalar bq;
      if (!Frozen && moving_[iu] && !stuck && !flying_[iu]) {  // b from moving_damper
        bq = modal(slip_b_.col(i)).dot(modal(e.qdd));
      } else {
        bq = C_.col(D + i).dot(e.qdd);
      }
      if (stuck || held) {
        e.xdd[i] = bq;
        e.Vdot[i] = 0;
      } else {
        if (inertial_[iu]) e.f[i] = -mu_[i] * e.N[i];  // N_i was an unknown
        e.xdd[i] = (e.f[i] - dmp.effective_stiffness() * x[x_offset() + i]) / dmp.effective_mass();
        e.Vdot[i] = e.xdd[i] - bq - d_[i];
      }
    }
    if (has_walls_) split_wall_reaction(mode);
    e.finite = detail::all_finite(e.qdd) && detail::all_finite(e.N) && detail::all_finite(e.f);
  }

  /// A separated damper (no unknown: N = f = 0): its shapes at X, V = x' - b^T q', the member's
  /// y = a^T q, slope and the gap y - y_d (its guard); e.y reports the damper's own y_d.
  void flight_rows(Index i, const State& x) const {
    const std::size_t iu = static_cast<std::size_t>(i);
    Evaluation& e = eval_;
    if (moving_[iu]) evaluate_shapes(i, e.X[i]);
    const auto q = x.template segment<Modes>(0, n_);
    const auto qd = x.template segment<Modes>(n_, n_);
    const Index y = flight_offset() + flight_slot_[iu];
    e.V[i] = x[xd_offset() + i] - qd.dot(modal(C_.col(D_ + i)));
    e.slope[i] = moving_[iu] ? q.dot(modal(dpsi_w_.col(i))) : Scalar(0);
    e.gap[i] = q.dot(modal(C_.col(i))) - x[y];
    e.y[i] = x[y];
    e.N[i] = Scalar(0);
    e.f[i] = Scalar(0);
    d_[i] = Scalar(0);
    mu_[i] = Scalar(0);
  }

  /// One slipping damper with a moving contact (its X changes at every call): its slip row
  /// (docs/model_solve.md, with the convective terms), from the element's n x 6 nodal block B and the shape-function weights
  /// at X (MemberShapes::locate). Every shape vector is B times a 6-vector of weights, so the
  /// projections need only P = B^T [q q'] (one n x 6 x 2 product) and the two columns of the solve
  /// are F_j = B (c_a + mu c_b), L_j = B (m c_a - m s c_b) (slip_columns): 21 n multiplies and no
  /// shape vectors, against 31 n multiply-adds for evaluating the five shape vectors and projecting
  /// them one by one.
  void moving_damper(Index i, const Mode& mode, const State& x) const {
    using Vec6 = Eigen::Matrix<Scalar, 6, 1>;
    const std::size_t iu = static_cast<std::size_t>(i);
    const Index n = n_;
    const Damper& dmp = dampers_[iu];
    Evaluation& e = eval_;
    const Shapes& shapes = shapes_[static_cast<std::size_t>(damper_shape_[iu])];
    const typename Shapes::Location loc = shapes.locate(e.X[i], cursors_[iu]);
    const auto B = element_block(iu, loc.element);
    const auto& w = loc.weights;
    const Scalar sd = dmp.side;  // y_i is measured along side * w
    Vec6 ca, cb;
    ca << Scalar(0), sd * w.w1, sd * w.t1, Scalar(0), sd * w.w2, sd * w.t2;
    cb << w.u1, Scalar(0), Scalar(0), w.u2, Scalar(0), Scalar(0);
    // P = B^T [q q'], accumulated mode by mode from the transposed block (six contiguous values
    // per mode: packet operations, no horizontal sums). Of B^T q only the w-part (w1, t1, w2, t2:
    // entries 1, 2, 4, 5) enters; of B^T q' all six.
    using Vec2 = Eigen::Matrix<Scalar, 2, 1>;
    const auto Bt = nodal_t_[static_cast<std::size_t>(damper_shape_[iu])].template block<6, Modes>(3 * loc.element, 0, 6, n);
    const auto q = x.template segment<Modes>(0, n), qd = x.template segment<Modes>(n, n);
    Vec2 Pq1 = Vec2::Zero(), Pq4 = Vec2::Zero();
    Vec6 Pqd = Vec6::Zero();
    for (Index j = 0; j < n; ++j) {
      Pq1.noalias() += q[j] * Bt.col(j).template segment<2>(1);
      Pq4.noalias() += q[j] * Bt.col(j).template segment<2>(4);
      Pqd.noalias() += qd[j] * Bt.col(j);
    }
    const Scalar wp1 = Pq1[0], wp2 = Pq1[1], wp4 = Pq4[0], wp5 = Pq4[1];  // w-part of B^T q
    const Scalar m = dmp.effective_mass(), k = dmp.effective_stiffness();
    const Scalar xi = x[x_offset() + i];
    const Scalar V = x[xd_offset() + i] - (w.u1 * Pqd[0] + w.u2 * Pqd[3]);  // x' - b^T q'
    e.V[i] = V;
    const Scalar slope = sd * (w.dw1 * wp1 + w.dt1 * wp2 + w.dw2 * wp4 + w.dt2 * wp5);
    Scalar h = 0, dd = 0;
    if (options_.convective_terms) {
      const Scalar dw_qd = sd * (w.dw1 * Pqd[1] + w.dt1 * Pqd[2] + w.dw2 * Pqd[4] + w.dt2 * Pqd[5]);
      const Scalar ddw_q = sd * (w.ddw1 * wp1 + w.ddt1 * wp2 + w.ddw2 * wp4 + w.ddt2 * wp5);
      h = Scalar(2) * dw_qd * V + ddw_q * V * V;
      dd = w.du * (Pqd[3] - Pqd[0]) * V;
    }
    e.slope[i] = slope;
    e.y[i] = ca[1] * wp1 + ca[2] * wp2 + ca[4] * wp4 + ca[5] * wp5;
    d_[i] = dd;
    const Scalar mu = slip_coefficient(i, mode[i], V);
    mu_[i] = mu;
    if (inertial_[iu]) {
      const Scalar sc = options_.convective_terms ? slope : Scalar(0);
      Scalar diag = Scalar(1) - sc * mu, rhs = dmp.preload - m * h + sc * k * xi + m * sc * dd;
      Scalar la = m, lb = -m * sc;  // L_j = B (la c_a + lb c_b)
      using std::abs;
      if (diag != Scalar(1) && abs(diag) >= Scalar(0.5)) {  // the row over its diagonal (solve_unknowns)
        const Scalar inv = Scalar(1) / diag;
        la *= inv;
        lb *= inv;
        rhs *= inv;
        diag = Scalar(1);
      }
      const Index j = add_unknown(i, diag, rhs, mu, sc);
      slip_columns(modal(F_.col(j)), modal(L_.col(j)), modal(slip_b_.col(i)), B, ca, cb, mu, la, lb);
    } else {
      e.N[i] = dmp.preload;
      e.f[i] = -mu * dmp.preload;
      block_times<true>(modal(r0_), B, dmp.preload * (ca + mu * cb));
      modal(slip_b_.col(i)).noalias() = w.u1 * B.col(0) + w.u2 * B.col(3);  // b, for b^T q''
    }
  }

  /// The two columns of a moving slipping damper's unknown from one pass over its n x 6 block B:
  /// with the shape vectors a = B c_a (four nonzero weights) and b = B c_b (two),
  /// F_j = a + mu b and L_j = la a + lb b - 15 operations per mode instead of the 22 of two
  /// six-term products, and B read once; b itself is kept (dstB) for b^T q'' after the solve.
  template <class DstF, class DstL, class DstB, class Block6>
  static void slip_columns(DstF&& dstF, DstL&& dstL, DstB&& dstB, const Block6& B,
                           const Eigen::Matrix<Scalar, 6, 1>& ca, const Eigen::Matrix<Scalar, 6, 1>& cb,
                           Scalar mu, Scalar la, Scalar lb) {
    const Index n = B.rows(), s = B.outerStride();
    const Scalar* bu1 = B.data();
    Scalar* f = dstF.data();
    Scalar* l = dstL.data();
    Scalar* bb = dstB.data();
    const Scalar a1 = ca[1], a2 = ca[2], a4 = ca[4], a5 = ca[5], b0 = cb[0], b3 = cb[3];
    for (Index r = 0; r < n; ++r) {
      const Scalar a = a1 * bu1[r + s] + a2 * bu1[r + 2 * s] + a4 * bu1[r + 4 * s] + a5 * bu1[r + 5 * s];
      const Scalar b = b0 * bu1[r] + b3 * bu1[r + 3 * s];
      f[r] = a + mu * b;
      l[r] = la * a + lb * b;
      bb[r] = b;
    }
  }

  /// dst = B c (Add: dst += B c) for an n x 6 block B with contiguous columns: one pass over
  /// the rows, each a six-term sum (a plain loop the compiler vectorises over rows; Eigen's
  /// six-column expression on a dynamic-length block measured 2x slower with AVX-512, where
  /// n = 6 fills no 8-wide packet, and no faster with SSE2).
  template <bool Add, class Dst, class Block6>
  static void block_times(Dst&& dst, const Block6& B, const Eigen::Matrix<Scalar, 6, 1>& c) {
    const Index n = B.rows(), s = B.outerStride();
    const Scalar* b = B.data();
    Scalar* d = dst.data();
    const Scalar c0 = c[0], c1 = c[1], c2 = c[2], c3 = c[3], c4 = c[4], c5 = c[5];
    for (Index r = 0; r < n; ++r) {
      const Scalar v = c0 * b[r] + c1 * b[r + s] + c2 * b[r + 2 * s] + c3 * b[r + 3 * s] +
                       c4 * b[r + 4 * s] + c5 * b[r + 5 * s];
      if constexpr (Add)
        d[r] += v;
      else
        d[r] = v;
    }
  }

  /// Appends an unknown (column of z = [N; f], A entry, right side) of damper i; its key
  /// (column, X_i, mu_i, slope_i) fixes its column, A entry and row for the factorisation reuse.
  Index add_unknown(Index i, Scalar diag, Scalar rhs, Scalar mu, Scalar sc, Index column = -1) const {
    const Index U = num_unknowns_;
    if (column < 0) column = i;
    unknown_of_[static_cast<std::size_t>(U)] = column;
    A_[U] = diag;
    c_[U] = rhs;
    Scalar* key = key_.data() + 4 * U;
    key[0] = Scalar(column);
    key[1] = eval_.X[i];
    key[2] = mu;
    key[3] = sc;
    return num_unknowns_++;
  }

  /// Solves for the U unknowns and q'' (see solve()), in the cheaper of the two forms. A system
  /// of order up to 8 (U unknowns, or n modes in the mode-space form) uses a fixed-size 2, 4, 6
  /// or 8 LU padded with identity rows (padded_order); a larger capacitance system an exact-size
  /// LU allocated by the first solve with that many unknowns (in a run: the transition into the
  /// mode, which evaluates it; never inside a step). Every row is assembled with A_jj = 1 except
  /// a slip row whose diagonal 1 - s_i mu_i is below 1/2 in magnitude (a row with |A_jj| >= 1/2 is
  /// divided by it in moving_damper: one division and seven products instead of a pass over F). The
  /// mode-space form needs A = I - no such row - else the capacitance form. The factorisation is
  /// kept while its key (per unknown: column, X, mu, slope) is unchanged - while the unknowns
  /// belong to stuck dampers (X constant) or to a fixed contact with a constant slip coefficient -
  /// so that such calls cost O(n U + U^2). When only X, mu or the slope changed and the system is
  /// larger than 8 x 8, refine() tries iterative refinement from the old factorisation first.
  void solve_unknowns(Index U) const {
    const Index n = n_;
    Evaluation& e = eval_;
    const auto F = F_.topLeftCorner(n, U);
    const auto L = L_.topLeftCorner(n, U);
    const auto A = A_.head(U);
    const auto c = c_.head(U);
    auto u = u_.head(U);
    // (std::equal stops at the first difference: a slipping damper's key changes at every call)
    const bool reuse = factor_unknowns_ == U &&
                       std::equal(key_.data(), key_.data() + 4 * U, factor_key_.data());
    if (!reuse && options_.refine_stale_factorisation && factor_unknowns_ == U &&
        padded_order(factor_mode_space_ ? n : U) > 8 && same_columns(U) && refine(F, L, A, c, u)) {
      solve_info_.unknowns = U;
      solve_info_.mode_space = factor_mode_space_;
      solve_info_.system_size = factor_mode_space_ ? n : U;
      return;  // (the factorisation and its key stay those of the matrix factorised)
    }
    if (!reuse) {
      const double nd = static_cast<double>(n), ud = static_cast<double>(U);
      // Products + LU, the LU at the order actually factorised (padded_order: 2, 4, 6 or 8).
      const auto lu_cost = [](Index order) { const double o = static_cast<double>(order); return o * o * o / 3.0; };
      const double capacitance_cost = nd * ud * ud + lu_cost(padded_order(U));
      const double mode_space_cost = nd * nd * ud + lu_cost(padded_order(n));
      factor_mode_space_ = mode_space_cost < capacitance_cost && (A.array() == Scalar(1)).all();
      factor_unknowns_ = -1;  // valid again once the factorisation below is complete
    }
    const Index order = padded_order(factor_mode_space_ ? n : U);
    if (factor_mode_space_ && order <= 8) {
      // (a fixed Modes is at most the padded order; the other sizes are never reached)
      if constexpr (fits_order<2>()) if (order == 2) solve_mode_space_small<2>(U, reuse, lu2_);
      if constexpr (fits_order<4>()) if (order == 4) solve_mode_space_small<4>(U, reuse, lu4_);
      if constexpr (fits_order<6>()) if (order == 6) solve_mode_space_small<6>(U, reuse, lu6_);
      if constexpr (fits_order<8>()) if (order == 8) solve_mode_space_small<8>(U, reuse, lu8_);
    } else if (factor_mode_space_) {
      // (I + F L^T) q'' = r0 + F c, then u = c - L^T q'' (A = I).
      if (!reuse) {
        // (assigned, then 1 added to the diagonal: a setIdentity() first and an accumulating
        // product cost a third more, measured at n = 24, U = 32)
        Mn_.noalias() = F * L.transpose();
        Mn_.diagonal().array() += Scalar(1);
        lun_.compute(Mn_);
      }
      r0_.noalias() += F * c;
      e.qdd.noalias() = lun_.solve(r0_);
      u = c;
      u.noalias() -= L.transpose() * e.qdd;
    } else if (order == 2) {
      solve_small<2>(U, reuse, lu2_);
    } else if (order == 4) {
      solve_small<4>(U, reuse, lu4_);
    } else if (order == 6) {
      solve_small<6>(U, reuse, lu6_);
    } else if (order == 8) {
      solve_small<8>(U, reuse, lu8_);
    } else {
      Eigen::PartialPivLU<Matrix>& lu = sized_lu(U);
      if (!reuse) {
        S_.topLeftCorner(U, U).noalias() = L.transpose() * F;
        S_.diagonal().head(U) += A;
        lu.compute(S_.topLeftCorner(U, U));
      }
      rhs_.head(U) = c;
      rhs_.head(U).noalias() -= L.transpose() * r0_;
      u.noalias() = lu.solve(rhs_.head(U));
      e.qdd = r0_;
      e.qdd.noalias() += F * u;
    }
    if (!reuse) {
      factor_key_.head(4 * U) = key_.head(4 * U);
      factor_unknowns_ = U;
    }
    solve_info_.unknowns = U;
    solve_info_.mode_space = factor_mode_space_;
    solve_info_.system_size = order;
    solve_info_.reused = reuse;
  }

  /// True when the unknowns are the same forces as those of the stored factorisation (same
  /// columns of z = [N; f], in the same order); X, mu and slope may differ.
  bool same_columns(Index U) const {
    for (Index j = 0; j < U; ++j)
      if (key_[4 * j] != factor_key_[4 * j]) return false;
    return true;
  }

  /// Iterative refinement with the stored factorisation of a matrix M0 of the same form and
  /// columns (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., ch. 12: fixed
  /// precision refinement): z <- z + M0^-1 (b - M z), with the residual of the current matrix M
  /// formed from F and L (2 n U multiply-adds) in place of forming and factorising M
  /// (n U min(n, U) + min(n, U)^3 / 3). Converges when the corrections contract, i.e. when M is
  /// close to M0 - a slipping contact that moved by a stage's step. Accepted when a correction is
  /// below kRefineTol relative to z (max norm); abandoned (false, the caller refactorises) when a
  /// correction fails to halve or after kMaxRefinements, so a large change costs a few products.
  /// F, L: the n x U directions, A, c: diagonal and right side, u: the unknowns (views of the
  /// workspace, as in solve_unknowns).
  template <class Directions, class Coefficients, class Unknowns>
  bool refine(const Directions& F, const Directions& L, const Coefficients& A, const Coefficients& c,
              Unknowns u) const {
    const Index U = u.size();
    Evaluation& e = eval_;
    Scalar previous = std::numeric_limits<Scalar>::infinity();
    if (factor_mode_space_) {
      if (!(A.array() == Scalar(1)).all()) return false;  // the mode-space form needs A = I
      // (I + F L^T) q'' = b = r0 + F c
      auto t = rhs_.head(U);  // L^T q''
      b_n_ = r0_;
      b_n_.noalias() += F * c;
      e.qdd.noalias() = lun_.solve(b_n_);
      for (int k = 1; k <= kMaxRefinements; ++k) {
        t.noalias() = L.transpose() * e.qdd;
        res_n_ = b_n_ - e.qdd;
        res_n_.noalias() -= F * t;
        dz_n_.noalias() = lun_.solve(res_n_);
        e.qdd += dz_n_;
        const Scalar size = dz_n_.cwiseAbs().maxCoeff();
        if (size <= kRefineTol * e.qdd.cwiseAbs().maxCoeff()) {
          u = c;
          u.noalias() -= L.transpose() * e.qdd;
          solve_info_.refinements = k;
          return true;
        }
        if (!(size <= Scalar(0.5) * previous)) return false;
        previous = size;
      }
      return false;
    }
    // (A + L^T F) u = b = c - L^T r0
    Eigen::PartialPivLU<Matrix>& lu = sized_lu(U);
    auto b = b_u_.head(U);
    auto res = res_u_.head(U);
    auto dz = dz_u_.head(U);
    b = c;
    b.noalias() -= L.transpose() * r0_;
    u.noalias() = lu.solve(b);
    for (int k = 1; k <= kMaxRefinements; ++k) {
      res_n_.noalias() = F * u;
      res = b - A.cwiseProduct(u);
      res.noalias() -= L.transpose() * res_n_;
      dz.noalias() = lu.solve(res);
      u += dz;
      const Scalar size = dz.cwiseAbs().maxCoeff();
      if (size <= kRefineTol * u.cwiseAbs().maxCoeff()) {
        e.qdd = r0_;
        e.qdd.noalias() += F * u;
        solve_info_.refinements = k;
        return true;
      }
      if (!(size <= Scalar(0.5) * previous)) return false;
      previous = size;
    }
    return false;
  }
  static constexpr int kMaxRefinements = 6;
  /// Relative size (max norm) of the last correction at which refinement stops: 16 units of
  /// round-off, about the accuracy of the direct LU solve of these well-conditioned matrices.
  static constexpr Scalar kRefineTol = Scalar(16) * std::numeric_limits<Scalar>::epsilon();

  /// The capacitance form for U <= K unknowns in a fixed K x K system padded with identity rows:
  /// (A + L^T F) u = c - L^T r0, then q'' = r0 + F u. Coefficient-based products: for a K x K
  /// result GEMM/GEMV packing costs more than it saves.
  template <int K, class Factor>
  void solve_small(Index U, bool reuse, Factor& lu) const {
    // No padding: products with K columns known at compile time. Only for K <= 4 (the blade's
    // 2 slipping and 4 stuck unknowns), to keep the instantiations per system type few.
    if constexpr (K <= 4) {
      if (U == K) return solve_small_products<K>(K, reuse, lu);
    }
    solve_small_products<Eigen::Dynamic, K>(U, reuse, lu);
  }
  /// solve_small with Cols (or, for Eigen::Dynamic, U) columns of F and L in a K x K system.
  template <int Cols, int K = Cols, class Factor>
  void solve_small_products(Index U, bool reuse, Factor& lu) const {
    const auto F = F_.template block<Modes, Cols>(0, 0, n_, U);
    const auto L = L_.template block<Modes, Cols>(0, 0, n_, U);
    const auto r0 = modal(r0_);
    if (!reuse) {
      Eigen::Matrix<Scalar, K, K> S = Eigen::Matrix<Scalar, K, K>::Identity();
      S.template topLeftCorner<Cols, Cols>(U, U).noalias() = L.transpose().lazyProduct(F);
      S.diagonal().template head<Cols>(U) += A_.template head<Cols>(U);
      lu.compute(S);
    }
    Eigen::Matrix<Scalar, K, 1> r = Eigen::Matrix<Scalar, K, 1>::Zero();
    auto rU = r.template head<Cols>(U);
    rU = c_.template head<Cols>(U);
    rU.noalias() -= L.transpose().lazyProduct(r0);
    const Eigen::Matrix<Scalar, K, 1> z = lu.solve(r);
    solve_info_.pivoted = lu.pivoting();
    auto u = u_.template head<Cols>(U);
    u = z.template head<Cols>(U);
    auto qdd = modal(eval_.qdd);
    qdd = r0;
    qdd.noalias() += F.lazyProduct(u);
  }

  /// The mode-space form for n <= K modes in a fixed K x K system padded with identity rows
  /// (A = I, see solve_unknowns): (I + F L^T) q'' = r0 + F c, then u = c - L^T q''. F_ and L_
  /// have K rows here, zero below row n, so the products run on K x U blocks with K fixed (a
  /// zero row of F leaves an identity row of the matrix; a zero row of L an identity column).
  template <int K, class Factor>
  void solve_mode_space_small(Index U, bool reuse, Factor& lu) const {
    using Fixed = Eigen::Matrix<Scalar, K, Eigen::Dynamic>;
    const Eigen::Map<const Fixed> F(F_.data(), K, U), L(L_.data(), K, U);
    const auto c = c_.head(U);
    if (!reuse) {
      Eigen::Matrix<Scalar, K, K> M = Eigen::Matrix<Scalar, K, K>::Identity();
      M.noalias() += F.lazyProduct(L.transpose());
      lu.compute(M);
    }
    Eigen::Matrix<Scalar, K, 1> rhs = Eigen::Matrix<Scalar, K, 1>::Zero();
    rhs.template segment<Modes>(0, n_) = modal(r0_);
    rhs.noalias() += F.lazyProduct(c);
    const Eigen::Matrix<Scalar, K, 1> z = lu.solve(rhs);
    solve_info_.pivoted = lu.pivoting();
    modal(eval_.qdd) = z.template segment<Modes>(0, n_);
    auto u = u_.head(U);
    u = c;
    u.noalias() -= L.transpose().lazyProduct(z);
  }

  /// Order of the matrix factorised for m unknowns (capacitance form) or m modes (mode space):
  /// up to 8, the next of 2, 4, 6, 8 (a fixed-size LU, padded with identity rows: fixed sizes
  /// let Eigen unroll what a dynamic LU of the same order spends in loop and call overhead);
  /// beyond, m itself (an exact-size dynamic LU).
  static Index padded_order(Index m) noexcept { return m <= 8 ? m + (m & 1) : m; }
  /// True when n modes fit a K x K mode-space system (always for dynamic Modes).
  template <int K>
  static constexpr bool fits_order() noexcept { return Modes == Eigen::Dynamic || Modes <= K; }

  // A view with the compile-time number of modes as its number of rows.
  template <class V>
  auto modal(V&& v) const { return v.template segment<Modes>(0, n_); }
  /// Element e's n x 6 nodal block of damper iu's member (MemberShapes::element_block).
  auto element_block(std::size_t iu, Index e) const {
    const auto B = shapes_[static_cast<std::size_t>(damper_shape_[iu])].element_block(e);
    return Eigen::Map<const Eigen::Matrix<Scalar, Modes, 6>, 0, Eigen::OuterStride<>>(
        B.data(), n_, 6, Eigen::OuterStride<>(B.outerStride()));
  }

  /// The exact-size LU for U > 8 unknowns (allocated on first use only).
  Eigen::PartialPivLU<Matrix>& sized_lu(Index U) const {
    Eigen::PartialPivLU<Matrix>& lu = lu_sized_[static_cast<std::size_t>(U)];
    if (lu.rows() != U) lu = Eigen::PartialPivLU<Matrix>(U);
    return lu;
  }

  /// Picks consistent states for the dampers in `involved` (and any stuck damper whose capacity
  /// the new states exceed): each is tried stuck first; those whose required stick force exceeds
  /// mu_s N slip in the direction of the excess force. Bounded fixed-point iteration.
  bool resolve(Mode& mode, std::vector<Index>& involved, Scalar t, State& x) {
    const Mode before = mode;
    for (Index i : involved)
      if (has_stick_[static_cast<std::size_t>(i)]) mode[i] = ContactState::Stick;
    bool consistent = false;
    for (int iter = 0; iter < 4 * static_cast<int>(D_) + 4 && !consistent; ++iter) {
      set_stuck_velocities(mode, x);
      cache_valid_ = false;
      const Evaluation& e = evaluate(mode, t, x);
      if (!e.finite) {  // a blown-up state: no states to choose; the stepper's finiteness check
        mode = before;  // after the transition reports it (Status::NonFiniteState)
        consistent = true;
        break;
      }
      consistent = true;
      for (Index i = 0; i < D_; ++i) {
        if (!has_stick_[static_cast<std::size_t>(i)] || mode[i] != ContactState::Stick) continue;
        const ContactState next = detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [&](const auto& law) {
          CoulombContact<std::decay_t<decltype(law)>> contact(law);
          return contact.decide(ContactState::Stick, Scalar(0), e.N[i], e.f[i]);
        });
        if (next == ContactState::LiftOff) continue;  // reported by the lift-off guard / check
        if (next != ContactState::Stick && has_walls_ && rest_at_wall(mode, i, next, x)) {
          consistent = false;
          break;  // re-solve with the wall holding it
        }
        if (next != ContactState::Stick) {
          mode[i] = next;
          consistent = false;
          if (std::find(involved.begin(), involved.end(), i) == involved.end()) involved.push_back(i);
          break;  // re-solve: one switch can relieve the others
        }
      }
    }
    cache_valid_ = false;
    for (Index i = 0; i < D_; ++i)
      if (before[i] != mode[i]) events_.push_back(ContactEvent{t, i, before[i], mode[i]});
    return consistent;
  }

  /// Enforce V_i = 0 exactly for stuck dampers: x_i' = q'^T psi_u(X_i). Only the stuck dampers'
  /// shapes are evaluated (and then kept for the solve that follows: X is unchanged); slipping
  /// ones are formed in element space by the solve.
  void set_stuck_velocities(const Mode& mode, State& x) {
    const auto qd = x.segment(n_, n_);
    for (Index i = 0; i < D_; ++i) {
      if (!has_stick_[static_cast<std::size_t>(i)] || mode[i] != ContactState::Stick) continue;
      if (moving_[static_cast<std::size_t>(i)]) evaluate_shapes(i, x[contact_offset() + i]);
      x[xd_offset() + i] = qd.dot(C_.col(D_ + i));
    }
  }

  TransitionAction stop(StopReason why, Index i, Scalar t, const State& x, const Mode& mode) {
    stop_reason_ = why;
    stop_damper_ = i;
    const std::string at = " at t = " + detail::format_value(t);
    const std::string who = "damper " + std::to_string(i);
    switch (why) {
      case StopReason::LiftOff: {
        const Evaluation& e = evaluate(mode, t, x);
        return TransitionAction::halt("lift-off: the normal force of " + who + " reached zero" + at +
                                      " (N = " + detail::format_value(e.N[i]) +
                                      "); the model assumes permanent contact");
      }
      case StopReason::LeftMember: {
        const std::size_t iu = static_cast<std::size_t>(i);
        const Scalar X = moving_[iu] ? x[contact_offset() + i] : dampers_[iu].contact_coordinate;
        return TransitionAction::halt(
            "left member: the contact point of " + who + " reached the end of member " +
            std::to_string(dampers_[iu].member) + at + " (X = " + detail::format_value(X) +
            ", valid range [0, " + detail::format_value(shapes_[static_cast<std::size_t>(damper_shape_[iu])].length()) + "])");
      }
      case StopReason::NoConsistentState:
        return TransitionAction::halt("no consistent stick/slip state found for " + who + at);
      case StopReason::NonFiniteLoad:
        return TransitionAction::halt("PointLoad[" + std::to_string(i) + "] is not finite" + at + " (F = " +
                                      detail::format_value(load_fault_.value) + ")");
      case StopReason::None: break;
    }
    return TransitionAction::halt("stopped" + at);
  }

  // ---- separation (docs/model_separation.md "Separation"; defined below the class) ----------------------
  /// The member's normal displacement y = a^T q and velocity y' = a^T q' + slope V (slope with a
  /// moving contact) under damper i, its slope and sliding velocity V; leaves i's shapes in C_.
  struct MemberContact {
    Scalar y, yd, slope, V;
  };
  MemberContact member_contact(Index i, const State& x) const;
  /// The impacts of impacting_, then the lift-offs of lifting_ (into flight); false when an
  /// impact has no solution (frictional_impact not resolved).
  bool separation_transition(Mode& mode, Scalar t, State& x);
  /// Damper i leaves the member: flight coordinates y_d, y_d' := the member's y, y' under it.
  void separate(Mode& mode, Index i, Scalar t, State& x);
  /// W = G M_eff^-1 G^T of a damper of mass m at slope s: the member's part impulse_dir_^T
  /// response_ (after impulse_response) plus the damper's [[(1 + s^2)/m, s/m], [s/m, 1/m]],
  /// symmetric (the member's part is, up to round-off).
  Eigen::Matrix<Scalar, 2, 2> inverse_effective_mass(Scalar s, Scalar m) const {
    Eigen::Matrix<Scalar, 2, 2> W = impulse_dir_.transpose() * response_;
    W(0, 0) += (Scalar(1) + s * s) / m;
    W(1, 1) += Scalar(1) / m;
    W(0, 1) = W(1, 0) = (W(0, 1) + W(1, 0)) / Scalar(2) + s / m;
    return W;
  }
  /// The impact of separated damper i (gap = 0): frictional_impact with W from the member's
  /// impulse response; velocities updated, the loss booked; bounce or landing.
  bool impact(Mode& mode, Index i, Scalar t, State& x);
  /// Gap acceleration g'' of separated damper i in flight at (mode, t, x):
  ///   g'' = a^T q'' + 2 s_d V + c V^2 + slope V' - N0/m,  V' = x'' - b^T q'' - (psi_u'^T q') V,
  /// with s_d = side psi_w'^T q', c = side psi_w''^T q at X (the terms in V with a moving contact
  /// only: d^2/dt^2 of y = side psi_w(X(t))^T q(t) with X' = V, minus y_d'' = N0/m).
  Scalar flight_gap_acceleration(const Mode& mode, Index i, Scalar t, const State& x);
  /// Whether the rebound of separated damper i at gap rate v_after > 0 (state x just after the
  /// bounce) stays inside the landing band: g'' < 0 and v_after^2 <= 2 |g''| kLandingBand L, i.e.
  /// the flight's apex below kLandingBand L (docs/model_separation.md "Separation", "The landing band").
  bool rebound_within_band(const Mode& mode, Index i, Scalar t, const State& x, Scalar v_after);
  /// Height of the landing band relative to the member length (1e-8 L: 4e-10 m on a 4 cm
  /// platform): a bounce whose flight would not rise above it lands. Well above the stepper's
  /// default guard_zero_tolerance (1e-12), by which a gap guard restarted at zero sinks at each
  /// located impact (docs/model_separation.md "Separation").
  static constexpr double kLandingBand = 1e-8;
  /// response_ = the member's modal velocity jumps, response_x_ the dampers' x' jumps, for unit
  /// modal impulses impulse_dir_ (two columns), through the other dampers' contact rows.
  void impulse_response(const Mode& mode, const State& x);
  /// Damper i's contact point reached the wall at end `end` (0: X = 0, 1: X = L): the sliding
  /// velocity V -> -e V by a tangential impulse through W_t = 1/m + b^T R b (with the normal
  /// impulse that keeps an inertial contact closed on a sloped member); the loss booked.
  void wall_impact(Mode& mode, Index i, int end, Scalar t, State& x);
  /// Candidates (dampers that may separate, in contact) whose normal force is not positive leave
  /// the member; the other dampers' states are then resolved again. False when resolve fails.
  bool land_or_separate(Mode& mode, const std::vector<Index>& candidates, Scalar t, State& x);
  /// land_or_separate over every damper in contact that may separate: no such damper is left
  /// pressed by N <= 0, where its N guard would start on its triggering side and not fire.
  bool separate_unpressed(Mode& mode, Scalar t, State& x) {
    lifting_.clear();
    for (Index i = 0; i < D_; ++i)
      if (flight_slot_[static_cast<std::size_t>(i)] >= 0 && mode[i] != ContactState::Separated) lifting_.push_back(i);
    return land_or_separate(mode, lifting_, t, x);
  }
  /// The first damper in contact whose lift-off is watched and that may not separate, with
  /// N <= 0 at (mode, t, x); -1 when there is none.
  Index unpressed_contact(const Mode& mode, Scalar t, const State& x) {
    const Evaluation& e = evaluate(mode, t, x);
    for (Index i = 0; i < D_; ++i)
      if (watch_lift_off(i) && flight_slot_[static_cast<std::size_t>(i)] < 0 && mode[i] != ContactState::Separated &&
          e.finite && !(e.N[i] > Scalar(0)))
        return i;
    return -1;
  }

  // ---- resting at a wall (docs/model_separation.md "Resting at a wall"; defined below the class) --------
  /// A stuck damper resting at a wall: the tangential force f solved for splits into friction
  /// (up to mu_s N towards the wall) and the wall's reaction (the excess, into eval_.wall_force).
  void split_wall_reaction(const Mode& mode) const;
  /// The stick guard of a resting damper that would let it slip into its wall (start: mu_s N - f,
  /// finish: mu_s N + f) is replaced by N, positive in contact (affine in the state like the
  /// others; it falls to 0 with the lift-off guard).
  static void rest_guard(WallRest wall, Scalar N, Scalar* g) noexcept { g[wall == WallRest::Start ? 0 : 1] = N; }
  /// A separated damper held at a wall (docs/model_separation.md "Held at a wall in flight"): the guard of
  /// its wall end (end_g[0]: X, end_g[1]: L - X) becomes the wall's reaction, which can only push:
  /// F at the start wall, -F at the finish wall (F = f + wall_force, the force along u holding it).
  static void hold_guard(WallRest wall, Scalar F, Scalar* end_g) noexcept {
    if (wall == WallRest::Start) end_g[0] = F;
    if (wall == WallRest::Finish) end_g[1] = -F;
  }
  /// The tangential row of separated damper i held at a wall: V = 0, i.e. x'' = b^T q'', with the
  /// force F along u as an unknown, F - m b^T q'' = k x (the stick row without a normal row).
  void hold_rows(Index i, const State& x) const {
    const Damper& dmp = dampers_[static_cast<std::size_t>(i)];
    const auto b = C_.col(D_ + i);
    const Index j = add_unknown(i, Scalar(1), dmp.effective_stiffness() * x[x_offset() + i], Scalar(0), Scalar(0), D_ + i);
    modal(F_.col(j)) = -b;
    modal(L_.col(j)) = -dmp.effective_mass() * b;
    eval_.V[i] = Scalar(0);
  }
  /// Separated dampers held at a wall whose holding force pulls away from it (F < 0 at the
  /// start, F > 0 at the finish) leave the wall (the mark cleared), until none does.
  void release_pulled_holds(Mode& mode, Scalar t, const State& x);
  /// Tangential acceleration V' of separated damper i in flight: x'' - b^T q'' - (psi_u'^T q') V.
  Scalar flight_sliding_acceleration(const Mode& mode, Index i, Scalar t, const State& x);
  /// A damper at rest that would slip into a wall it lies at (X within kWallBand L of the end, or
  /// beyond it) rests against that wall instead: marked, X set to the end. True when it did.
  /// (Its turning point after a rebound slower than the stepper's guard_zero_tolerance can
  /// resolve lies there: the end guard would start "at zero" and miss the crossing.)
  bool rest_at_wall(Mode& mode, Index i, ContactState next, State& x);
  /// Width of the band at a wall end, relative to the member length, in which a damper at rest
  /// counts as lying at the wall (1e-8 L: 4e-10 m on a 4 cm platform, above the default
  /// guard_zero_tolerance of 1e-12 and far below any slip that matters).
  static constexpr double kWallBand = 1e-8;
  /// Throws std::invalid_argument when a damper is marked as resting at an end that is not a wall.
  void validate_walls(const Mode& mode, const char* where) const;
  /// Clears the wall marks of dampers that are no longer stuck (so that a later stick away from
  /// the wall is an ordinary one).
  static void forget_left_walls(Mode& mode) {
    for (Index i = 0; i < mode.size(); ++i)
      if (mode[i] != ContactState::Stick && mode[i] != ContactState::Separated) mode.set_wall(i, WallRest::None);
  }

  // Scene.
  std::vector<Damper> dampers_;
  std::vector<Load> loads_;
  ModelOptions<Scalar> options_;
  Index n_ = 0, D_ = 0;
  Vector omega2_, modal_damping_;
  std::vector<Shapes> shapes_;
  std::vector<Matrix> nodal_t_;  // per shape: the member's nodal values transposed, 3 (nodes) x n
  std::vector<Index> shape_members_;
  std::vector<std::pair<Scalar, Scalar>> shape_direction_;  // member (cos, sin)
  std::vector<Index> damper_shape_;
  // Per damper (char, not the bit-packed vector<bool>, read in every evaluation): the law has a
  // stick state; the normal force varies (vertical inertia).
  std::vector<char> has_stick_, inertial_;
  std::vector<Scalar> kinetic_constant_;  // a CoulombLaw's mu_k, else NaN (slip_coefficient)
  Matrix load_psi_;

  // Workspace of the solve (allocated once; the solve allocates nothing).
  mutable std::vector<typename Shapes::Values> values_;
  mutable std::vector<ElementCursor> cursors_;
  // Shapes at the contacts of stuck dampers and fixed contacts (C = [a_1..a_D b_1..b_D], slopes).
  mutable Matrix C_, dpsi_w_;
  mutable Vector r0_, d_, mu_;
  // Reduced unknowns of the solve: force directions F, row directions L, diagonal A, right side c.
  mutable Matrix F_, L_, S_, Mn_;
  mutable Vector A_, c_, u_, rhs_;
  mutable Vector b_n_, res_n_, dz_n_, b_u_, res_u_, dz_u_;  // refinement (refine())
  mutable std::vector<Index> unknown_of_;  // column of z = [N; f] held by each unknown
  mutable Index num_unknowns_ = 0;
  // Moving slipping dampers (moving_damper): b = psi_u at the contact, for b^T q'' after the solve.
  mutable Matrix slip_b_;
  mutable Eigen::PartialPivLU<Matrix> lun_;
  mutable std::vector<Eigen::PartialPivLU<Matrix>> lu_sized_;  // [U]: exact-size LU, U > 4
  // Factorisation reuse: the key of the last factorised matrix and its number of unknowns.
  mutable Vector key_, factor_key_;
  mutable Vector shapes_X_;  // contact coordinate at which each damper's shapes were evaluated
  mutable Index factor_unknowns_ = -1;
  mutable bool factor_mode_space_ = false;
  mutable detail::Inverse2<Scalar> lu2_;  // order 2: closed-form inverse
  // orders 4, 6, 8: checked block elimination, a pivoted LU where the check fails
  mutable detail::CheckedBlockSolve<Scalar, 4> lu4_;
  mutable detail::CheckedBlockSolve<Scalar, 6> lu6_;
  mutable detail::CheckedBlockSolve<Scalar, 8> lu8_;
  mutable Evaluation eval_;
  mutable SolveInfo solve_info_;
  bool cache_valid_ = false;
  Scalar cache_t_{};
  Mode cache_mode_;
  State cache_x_;

  // Linear part (linear_part): probe work vectors (sized by the first call), the key of the last
  // call (mode, frozen X and slip coefficients) with its version, the last exact mode's result.
  State lp_xs_;
  Vector lp_f_, lp_b_, lp_X_, lp_mu_, lp_key_X_, lp_key_mu_;
  Matrix lp_fz_, lp_vz_;  // f and V of an exact mode as maps of z (audit_forms)
  GuardVector lp_g_;
  std::vector<Scalar> lp_preload_;
  Mode lp_mode_;
  bool lp_key_valid_ = false, lp_cached_ = false;
  std::uint64_t lp_version_ = 0;
  LinearPart<Scalar> lp_cache_;

  // Jacobian (jacobian): the linear part of the mode, z of the audit forms, difference vectors.
  LinearPart<Scalar> jac_lp_;
  Vector jac_z_;
  State jac_x_, jac_fp_, jac_fm_;
  /// Column j of J by central differences of rhs (h = 1e-6 max(1, |x_j|)).
  void jacobian_column(const Mode& mode, Scalar t, const State& x, Index j, Matrix& J);
  /// J of an inexact mode by the tangent of the solve (every column but the moving contacts'
  /// X, which the caller takes by differences); false, J untouched, where it does not apply (a
  /// damper in flight or resting at a wall, or slipping under a law whose coefficient varies
  /// with V).
  bool tangent_jacobian(const Mode& mode, Scalar t, const State& x, Matrix& J);
  /// The tangent's (and contact_columns') condition: no damper in flight or resting at a wall,
  /// and every slipping damper's coefficient a constant (a CoulombLaw's mu_k).
  bool tangent_applies(const Mode& mode) const {
    using std::isnan;
    for (Index i = 0; i < D_; ++i) {
      const std::size_t iu = static_cast<std::size_t>(i);
      if (mode[i] == ContactState::Separated || mode.wall(i) != WallRest::None) return false;
      const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
      if (!stuck && isnan(kinetic_constant_[iu])) return false;
    }
    return true;
  }
  // Workspace of tangent_jacobian: per unknown its row of the tangent right side and of du, the
  // gradients of one damper's scalars, its shapes at X, the capacitance matrix and its LU per
  // number of unknowns.
  Matrix jac_rho_, jac_du_, jac_S_;
  Eigen::Matrix<Scalar, 1, Eigen::Dynamic> jac_gV_, jac_gs_, jac_gh_, jac_gd_, jac_gc_;
  typename Shapes::Values jac_shape_;
  std::vector<Eigen::PartialPivLU<Matrix>> jac_lu_;
  /// The columns of the moving contacts' X in closed form (docs/model_solve.md, "Jacobian df/dx"),
  /// where the tangent applies (no damper in flight or at a wall, Coulomb slip); false, J
  /// untouched, elsewhere. `lu_ready`: tangent_jacobian has just factorised A + L^T F at x.
  bool contact_columns(const Mode& mode, Scalar t, const State& x, Matrix& J, bool lu_ready);
  // Workspace of contact_columns: psi_w''' at X, the right side g = dr0/dX + (dF/dX) u of the
  // tangent, dq''/dX and du/dX.
  Vector jac_d3w_, jac_g_, jac_dqdd_, jac_dux_, jac_sol_;
  /// The LU of the tangent's capacitance matrix A + L^T F (U unknowns) of the last evaluation.
  Eigen::PartialPivLU<Matrix>& tangent_lu(Index U) {
    if (jac_lu_.size() <= static_cast<std::size_t>(U))  // U <= 2D: one slot per count, made once
      jac_lu_.resize(static_cast<std::size_t>(std::max(U, 2 * D_) + 1));
    Eigen::PartialPivLU<Matrix>& lu = jac_lu_[static_cast<std::size_t>(U)];
    if (lu.rows() != U) lu = Eigen::PartialPivLU<Matrix>(U);
    jac_S_.noalias() = L_.topLeftCorner(n_, U).transpose() * F_.topLeftCorner(n_, U);
    jac_S_.diagonal() += A_.head(U);
    lu.compute(jac_S_);
    return lu;
  }
  /// The row of `column` (N_i: i; a stuck damper's f_i: D + i) among the last solve's unknowns,
  /// or -1 (a constant normal load).
  Index unknown_row(Index column) const {
    for (Index j = 0; j < num_unknowns_; ++j)
      if (unknown_of_[static_cast<std::size_t>(j)] == column) return j;
    return -1;
  }
  /// Damper i's shapes at its contact X into jac_shape_ (MemberShapes::evaluate).
  const typename Shapes::Values& jacobian_shapes(Index i, Scalar X) {
    const std::size_t iu = static_cast<std::size_t>(i);
    shapes_[static_cast<std::size_t>(damper_shape_[iu])].evaluate(X, jac_shape_, cursors_[iu]);
    return jac_shape_;
  }
  /// True when linear_part's A_m is exact in `mode` (r_m = 0 with X frozen), as linear_part decides.
  bool exact_mode(const Mode& mode) const;

  // Per damper: its contact point moves (ModelOptions::moving_contact and PointDamper::contact_point).
  std::vector<bool> moving_;

  std::vector<ContactEvent> events_;
  std::vector<ImpactEvent> impacts_;
  std::vector<Index> involved_, lifting_, impacting_;
  // Separation (docs/model_separation.md "Separation"): per damper its flight slot (-1: cannot separate),
  // the number S of such dampers, which dampers the last solve had in flight, and the impulse
  // response workspace of impact() (member velocity and damper velocity jumps per unit impulse).
  std::vector<Index> flight_slot_;
  Index num_separable_ = 0;
  // Member ends per damper (start X = 0, finish X = L), resolved: Stop, Extend or Wall; whether
  // the audit books impacts (separation or walls); the walls hit at the current transition.
  std::vector<std::array<MemberEnd, 2>> end_kind_;
  bool has_impacts_ = false;
  bool has_walls_ = false;  // some damper has a MemberEnd::Wall (resting contact possible)
  std::vector<std::pair<Index, int>> wall_hits_;
  mutable std::vector<char> flying_;
  Matrix response_, response_x_, impulse_dir_;
  StopReason stop_reason_ = StopReason::None;
  mutable LoadFault load_fault_;
  Index stop_damper_ = -1;
};

// ---- members defined out of the class: not implicitly inline, so that the compiled mode can
// declare FrictionDampedSystem<double> extern and instantiate them once (docs/compiled.md) ----

template <class Scalar_, class Law_, int Modes>
FrictionDampedSystem<Scalar_, Law_, Modes>::FrictionDampedSystem(const FrameModel<Scalar>& model,
                                                                 const ModalBasis<Scalar>& basis,
                                                                 std::vector<Damper> dampers,
                                                                 std::vector<Load> loads,
                                                                 ModelOptions<Scalar> options)
    : dampers_(std::move(dampers)), loads_(std::move(loads)), options_(options) {
  n_ = basis.size();
  D_ = static_cast<Index>(dampers_.size());
  if (n_ < 1) detail::throw_invalid("FrictionDampedSystem", "basis must hold >= 1 mode", n_);
  if (Modes != Eigen::Dynamic && n_ != Modes)
    detail::throw_invalid("FrictionDampedSystem",
                          "basis must hold exactly Modes = " + std::to_string(Modes) +
                              " modes (use ModalBasis::truncated), basis size",
                          n_);
  if (D_ > DamperStates::max_dampers)
    detail::throw_invalid("FrictionDampedSystem", "at most 64 dampers", D_);
  detail::require_enumerator("FrictionDampedSystem", "options.normal_load", "NormalLoad", options_.normal_load,
                             NormalLoad::Inertial);
  detail::require_enumerator("FrictionDampedSystem", "options.end_policy", "EndPolicy", options_.end_policy,
                             EndPolicy::Extrapolate);
  for (Index i = 0; i < D_; ++i) dampers_[static_cast<std::size_t>(i)].validate(i);  // before their fields are read
  for (const Damper& d : dampers_) {
    const bool moving = options_.moving_contact && d.contact_point == ContactPoint::Moving;
    moving_.push_back(moving);
  }
  // The state carries contact coordinates when at least one contact moves.
  options_.moving_contact = std::find(moving_.begin(), moving_.end(), true) != moving_.end();
  if (!options_.moving_contact) options_.convective_terms = false;

  omega2_ = basis.omega().array().square().matrix();
  // c_j of the basis (2 zeta_j omega_j, or alpha + beta omega_j^2 with Rayleigh damping, which
  // keeps alpha on a rigid-body mode): not recomputed from zeta, which is 0 for a rigid mode.
  modal_damping_ = basis.damping_coefficients();

  // One MemberShapes per member touched by a damper or a load.
  auto shapes_for = [&](Index member) -> Index {
    for (std::size_t s = 0; s < shape_members_.size(); ++s)
      if (shape_members_[s] == member) return static_cast<Index>(s);
    if (member < 0 || member >= model.num_members())
      detail::throw_invalid("FrictionDampedSystem", "member index does not exist", member);
    // The model watches the member ends itself (guards on X, policy Throw), so the shapes
    // extrapolate for the trial stages an integrator may take just past an end.
    shapes_.emplace_back(model, member, basis,
                         options_.end_policy == EndPolicy::Clamp ? EndPolicy::Clamp : EndPolicy::Extrapolate);
    shape_members_.push_back(member);
    {  // the member's nodal values transposed (3 per node x n): an element's 6 x n block has
       // each mode's six values contiguous, for the projections of moving_damper()
      const Shapes& sh = shapes_.back();
      Matrix t(3 * (sh.num_elements() + 1), n_);
      for (Index el = 0; el < sh.num_elements(); ++el)
        t.template middleRows<6>(3 * el) = sh.element_block(el).transpose();
      nodal_t_.push_back(std::move(t));
    }
    shape_direction_.emplace_back(model.member(member).cos, model.member(member).sin);
    return static_cast<Index>(shapes_.size() - 1);
  };

  for (Index i = 0; i < D_; ++i) {
    const Damper& d = dampers_[static_cast<std::size_t>(i)];
    const Index s = shapes_for(d.member);
    const Shapes& sh = shapes_[static_cast<std::size_t>(s)];
    if (!(d.contact_coordinate >= Scalar(0) && d.contact_coordinate <= sh.length()))
      detail::throw_invalid("PointDamper[" + std::to_string(i) + "]",
                            "contact_coordinate must lie on member " + std::to_string(d.member) +
                                " (valid range [0, " + detail::format_value(sh.length()) + "])",
                            d.contact_coordinate);
    damper_shape_.push_back(s);
    has_stick_.push_back(detail::law_has_stick_state(d.law));
    // A CoulombLaw's kinetic coefficient does not depend on the speed: read once here, so
    // that the slip rows need no dispatch on the law.
    kinetic_constant_.push_back(detail::with_law(d.law, [](const auto& l) -> Scalar {
      if constexpr (std::is_same_v<std::decay_t<decltype(l)>, CoulombLaw<Scalar>>)
        return l.kinetic_coefficient(Scalar(0));
      else
        return std::numeric_limits<Scalar>::quiet_NaN();
    }));
    inertial_.push_back(options_.normal_load == NormalLoad::Inertial && d.normal_load == NormalLoad::Inertial);
    if (d.separation == Separation::Separate) {  // N must be able to reach zero, and be watched
      const std::string where = "PointDamper[" + std::to_string(i) + "]";
      if (!inertial_.back())
        detail::throw_invalid(where, "separation = Separate needs an inertial normal load (a constant N never "
                                     "reaches zero): PointDamper::normal_load and ModelOptions::normal_load "
                                     "must be Inertial", std::string("normal_load Constant"));
      if (!options_.watch_lift_off)
        detail::throw_invalid(where, "separation = Separate needs ModelOptions::watch_lift_off = true (an "
                                     "unwatched normal force never separates the damper)",
                              std::string("watch_lift_off = false"));
    }
    const bool separable = d.separation == Separation::Separate && watch_lift_off(i);
    flight_slot_.push_back(separable ? num_separable_++ : Index(-1));
    const MemberEnd fallback = options_.end_policy == EndPolicy::Throw ? MemberEnd::Stop : MemberEnd::Extend;
    const auto resolved = [&](MemberEnd e) { return e == MemberEnd::Default ? fallback : e; };
    end_kind_.push_back({resolved(d.start_end), resolved(d.finish_end)});
    has_impacts_ = has_impacts_ || separable || end_kind_.back()[0] == MemberEnd::Wall ||
                   end_kind_.back()[1] == MemberEnd::Wall;
    has_walls_ = has_walls_ || (moving_[static_cast<std::size_t>(i)] &&
                                (end_kind_.back()[0] == MemberEnd::Wall || end_kind_.back()[1] == MemberEnd::Wall));
  }

  load_psi_.resize(n_, static_cast<Index>(loads_.size()));
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    const Load& load = loads_[l];
    load.validate(static_cast<Index>(l));
    const std::size_t s = static_cast<std::size_t>(shapes_for(load.member));
    load_psi_.col(static_cast<Index>(l)) = load_vector(s, load);
  }

  allocate_workspace();
  // Fixed contact points: the shapes never change; evaluate them once.
  for (Index i = 0; i < D_; ++i)
    if (!moving_[static_cast<std::size_t>(i)])
      evaluate_shapes(i, dampers_[static_cast<std::size_t>(i)].contact_coordinate);
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::step_rates() const -> std::vector<StepRate<Scalar>> {
  using std::sqrt;
  using C = std::complex<Scalar>;
  std::vector<StepRate<Scalar>> rates;
  // Roots of lambda^2 + 2 sigma lambda + w^2 = 0 (w > 0 or sigma > 0): the upper one of a
  // complex pair, both when real (critically damped or more; the slow one as w^2 / the stiff
  // one, without the cancellation of -sigma + sqrt(sigma^2 - w^2)).
  auto add_roots = [&rates](Scalar sigma, Scalar w, const std::string& source) {
    if (sigma < w) {
      rates.push_back({C(-sigma, sqrt(w * w - sigma * sigma)), source});
    } else {
      const Scalar stiff = -sigma - sqrt((sigma - w) * (sigma + w));
      rates.push_back({C(stiff, Scalar(0)), source});
      rates.push_back({C(w * w / stiff, Scalar(0)), source});
    }
  };
  for (Index j = 0; j < n_; ++j) {
    const std::string name = "mode " + std::to_string(j + 1);
    const Scalar w = sqrt(omega2_[j]), c = modal_damping_[j];
    if (!(w > 0)) {  // rigid-body mode q'' + c q' = 0: rates 0 and -c
      if (c > 0) rates.push_back({C(-c, Scalar(0)), name + " (rigid-body, damping c = " + detail::format_value(c) + " 1/s)"});
      continue;
    }
    std::string source = name + " (" + detail::format_frequency(w);
    if (c > 0) source += ", zeta " + detail::format_value(c / (Scalar(2) * w));
    add_roots(c / Scalar(2), w, source + ")");
  }
  // Regularised dampers: c_i = mu_i'(0) N0_i (the friction force's slope at V = 0) and beta_i,
  // the largest |psi_u|^2 the contact can see: at X0 for a fixed contact, else the largest at the
  // member's nodes (psi_u is linear on each element, so |psi_u|^2 is convex there).
  std::vector<Scalar> slope(dampers_.size(), Scalar(0));
  Scalar member_sum = 0;  // sum_j c_j beta_j
  for (std::size_t i = 0; i < dampers_.size(); ++i) {
    const Damper& d = dampers_[i];
    slope[i] = detail::with_law(d.law, [](const auto& l) -> Scalar {
      if constexpr (std::decay_t<decltype(l)>::has_stick_state)
        return Scalar(0);
      else
        return l.coefficient_derivative(Scalar(0));
    }) * d.preload;
    if (!(slope[i] > 0)) continue;
    const std::size_t s = static_cast<std::size_t>(damper_shape_[i]);
    Scalar beta = 0;
    if (options_.moving_contact) {
      const Matrix& t = nodal_t_[s];
      for (Index k = 0; k < t.rows(); k += 3) beta = std::max(beta, t.row(k).squaredNorm());
    } else {
      beta = shapes_[s].evaluate(d.contact_coordinate).psi_u.squaredNorm();
    }
    member_sum += slope[i] * beta;
  }
  for (std::size_t i = 0; i < dampers_.size(); ++i) {
    const Damper& d = dampers_[i];
    const std::string name = "damper " + std::to_string(i);
    const Scalar w = sqrt(d.effective_stiffness() / d.effective_mass());
    if (w > 0) rates.push_back({C(Scalar(0), w), name + " slip oscillator sqrt(k/m) (" + detail::format_frequency(w) + ")"});
    if (flight_slot_[i] >= 0)  // separated: y_d'' = N0/m, a double integrator
      rates.push_back({C(Scalar(0), Scalar(0)), name + " flight y_d'' = N0/m (rate 0)"});
    if (!(slope[i] > 0)) continue;
    const Scalar two_sigma = slope[i] / d.effective_mass() + member_sum;
    add_roots(two_sigma / Scalar(2), w,
              name + " regularised friction slope mu'(0) N0 / m + sum mu'(0) N0 |psi_u|^2 = " +
                  detail::format_value(two_sigma) + " 1/s");
  }
  return rates;
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::transition(Mode& mode, const TriggeredGuards& triggered,
                                                            Scalar t, State& x) -> TransitionAction {
  std::vector<Index>& involved = involved_;
  involved.clear();
  lifting_.clear();
  impacting_.clear();
  wall_hits_.clear();
  for (Index idx : triggered) {
    Index i = 0, local = idx;
    for (; i < D_; ++i) {
      const Index nc = guards_of(mode, i);
      if (local < nc) break;
      local -= nc;
    }
    STICKSLIP_ASSERT(i < D_);
    const Index nc = contact_guards_of(mode, i);
    if (local >= nc) {  // a member end: a wall reflects, else the run stops
      const int end = static_cast<int>(local - nc);
      if (mode[i] == ContactState::Separated && mode.wall(i) == (end == 0 ? WallRest::Start : WallRest::Finish)) {
        mode.set_wall(i, WallRest::None);  // held in flight: the wall's reaction reached zero, it leaves
        cache_valid_ = false;
        continue;
      }
      if (end_kind_[static_cast<std::size_t>(i)][static_cast<std::size_t>(end)] != MemberEnd::Wall)
        return stop(StopReason::LeftMember, i, t, x, mode);
      wall_hits_.emplace_back(i, end);
      continue;
    }
    if (mode[i] == ContactState::Separated) {  // the gap closed: an impact
      impacting_.push_back(i);
      continue;
    }
    const bool lift = watch_lift_off(i) && local == nc - 1;
    if (lift && flight_slot_[static_cast<std::size_t>(i)] < 0) return stop(StopReason::LiftOff, i, t, x, mode);
    if (lift) {
      lifting_.push_back(i);
      continue;
    }
    if (std::find(involved.begin(), involved.end(), i) == involved.end()) involved.push_back(i);
  }
  if (!separation_transition(mode, t, x))
    return stop(StopReason::NoConsistentState, impacting_.front(), t, x, mode);
  // The new states leave no damper in contact with N <= 0 (one switch changes the accelerations
  // and so the normal forces of the others): a damper that may separate leaves the member, one
  // that may not stops the run at its lift-off.
  const bool consistent = resolve(mode, involved, t, x) && separate_unpressed(mode, t, x);
  if (has_walls_) release_pulled_holds(mode, t, x);
  forget_left_walls(mode);
  if (!consistent)
    return stop(StopReason::NoConsistentState, involved.empty() ? 0 : involved.front(), t, x, mode);
  const Index lifted = unpressed_contact(mode, t, x);
  return lifted < 0 ? TransitionAction::proceed() : stop(StopReason::LiftOff, lifted, t, x, mode);
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::make_consistent(Mode& mode, Scalar t, State& x) -> bool {
  validate_start(mode, t, x, "FrictionDampedSystem::make_consistent", "t", "x");
  std::vector<Index>& involved = involved_;
  involved.clear();
  for (Index i = 0; i < D_; ++i)
    if (mode[i] == ContactState::Stick) involved.push_back(i);
  const long load_faults = load_fault_.count;
  const bool resolved = resolve(mode, involved, t, x);
  if (load_fault_.count != load_faults && load_fault_.t == t) {  // F_l(t0) is not finite: no start
    stop(StopReason::NonFiniteLoad, load_fault_.load, t, x, mode);
    return false;
  }
  if (!resolved) return false;
  {
    const Evaluation& e = evaluate(mode, t, x);
    for (Index i = 0; i < D_; ++i) {
      // A constant normal load N0 = 0 never presses an exact-law damper: no contact, ever.
      const std::size_t iu = static_cast<std::size_t>(i);
      const bool unpressed = !inertial_[iu] && has_stick_[iu];
      if (mode[i] == ContactState::Separated || flight_slot_[iu] >= 0) continue;  // below
      if ((watch_lift_off(i) || unpressed) && !(e.N[i] > Scalar(0))) {
        stop(StopReason::LiftOff, i, t, x, mode);
        return false;
      }
    }
  }
  // Dampers that may separate: those without a positive normal force leave the member at t0.
  const bool consistent = separate_unpressed(mode, t, x);
  if (has_walls_) release_pulled_holds(mode, t, x);
  forget_left_walls(mode);
  return consistent;
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::evaluate(const Mode& mode, Scalar t, const State& x)
    -> const Evaluation& {
  if (!(cache_valid_ && t == cache_t_ && mode == cache_mode_ && x.size() == cache_x_.size() &&
        x == cache_x_)) {
    validate_state(mode, x, "FrictionDampedSystem::evaluate");
    solve(mode, t, x);
    cache_valid_ = true;
    cache_t_ = t;
    cache_mode_ = mode;
    cache_x_ = x;
  }
  return eval_;
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::mechanical_energy(const Mode& mode, Scalar t,
                                                                   const State& x) -> Scalar {
  const Evaluation& e = evaluate(mode, t, x);
  const auto q = x.head(n_);
  const auto qd = x.segment(n_, n_);
  Scalar E = Scalar(0.5) * qd.squaredNorm() + Scalar(0.5) * q.dot(omega2_.cwiseProduct(q));
  for (Index i = 0; i < D_; ++i) {
    const Damper& d = dampers_[static_cast<std::size_t>(i)];
    const Scalar m = d.effective_mass(), k = d.effective_stiffness();
    const Scalar xi = x[x_offset() + i], xdi = x[xd_offset() + i];
    if (moving_[static_cast<std::size_t>(i)]) evaluate_shapes(i, e.X[i]);  // a slipping damper's are not kept
    if (mode[i] == ContactState::Separated) {  // in flight: its own y_d, y_d' (docs/model_separation.md "Separation")
      const Index y = flight_offset() + flight_slot_[static_cast<std::size_t>(i)];
      const Scalar yd = x[y + num_separable_];
      E += Scalar(0.5) * m * (xdi * xdi + yd * yd) + Scalar(0.5) * k * xi * xi - d.preload * x[y];
      continue;
    }
    const Scalar y = q.dot(C_.col(i));
    E += Scalar(0.5) * m * xdi * xdi + Scalar(0.5) * k * xi * xi - d.preload * y;
    if (inertial_[static_cast<std::size_t>(i)]) {
      Scalar yd = qd.dot(C_.col(i));
      if (moving_[static_cast<std::size_t>(i)]) yd += e.slope[i] * e.V[i];
      E += Scalar(0.5) * m * yd * yd;
    }
  }
  return E;
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::linear_part(const Mode& mode, Scalar t, const State& x,
                                                             LinearPart<Scalar>& lp) -> bool {
  if (x.size() != state_size())
    detail::throw_invalid("FrictionDampedSystem::linear_part", "x must have state_size() entries, size", x.size());
  if (mode.size() != D_)
    detail::throw_invalid("FrictionDampedSystem::linear_part", "mode must hold one state per damper, size",
                          mode.size());
  const Evaluation& e = evaluate(mode, t, x);
  if (!e.finite) return false;
  if (lp_xs_.size() != state_size()) allocate_linear_part_workspace();
  using std::isnan;
  bool exact = true, moving_slip = false;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
    lp_X_[i] = e.X[i];
    if (mode[i] == ContactState::Separated) {  // free flight: linear (y'' = N0/m), f = 0
      lp_mu_[i] = Scalar(0);
      moving_slip = moving_slip || moving_[iu];
      exact = exact && !moving_[iu];
      continue;
    }
    lp_mu_[i] = stuck ? Scalar(0) : slip_coefficient(i, mode[i], e.V[i]);
    if (stuck) continue;
    moving_slip = moving_slip || moving_[iu];
    exact = exact && !moving_[iu] && !isnan(kinetic_constant_[iu]);
  }
  for (const Load& l : loads_) exact = exact && !l.time_function;

  const bool same = lp_key_valid_ && mode == lp_mode_ && lp_X_ == lp_key_X_ && lp_mu_ == lp_key_mu_;
  if (!same) {
    ++lp_version_;
    lp_mode_ = mode;
    lp_key_X_ = lp_X_;
    lp_key_mu_ = lp_mu_;
    lp_key_valid_ = true;
    lp_cached_ = false;
  }
  if (lp_cached_) {  // an exact mode depends on its key only
    lp = lp_cache_;
    return true;
  }
  const bool frozen_guards = !exact && lp.want_inexact_guards;
  linear_part_by_probes(mode, exact, moving_slip, frozen_guards, lp);
  if (frozen_guards) frozen_guard_rows(mode, t, x, lp);
  lp.exact = exact;
  lp.version = lp_version_;
  if (exact) {
    lp_cache_ = lp;
    lp_cached_ = true;
    return true;
  }
  // r_m(t, x) = f(t, x) - A x_L - b(t) into b0, so that the remainder vanishes at x.
  const Evaluation& ex = evaluate(mode, t, x);
  linear_derivative(ex, x, lp_f_);
  lp.load(t, lp_b_);
  lp_f_ -= lp_b_;
  lp_f_.noalias() -= lp.A * x.head(linear_size());
  lp.b0 += lp_f_;
  return true;
}

// ---- Jacobian df/dx ----------------------------------------------------------------

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::exact_mode(const Mode& mode) const {
  using std::isnan;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    if (has_stick_[iu] && mode[i] == ContactState::Stick) continue;
    if (moving_[iu]) return false;
    if (mode[i] != ContactState::Separated && isnan(kinetic_constant_[iu])) return false;
  }
  return std::none_of(loads_.begin(), loads_.end(), [](const Load& l) { return bool(l.time_function); });
}

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::jacobian_column(const Mode& mode, Scalar t, const State& x, Index j,
                                                                Matrix& J) {
  using std::abs;
  const Scalar h = Scalar(1e-6) * std::max(Scalar(1), abs(x[j]));
  jac_x_ = x;
  jac_x_[j] = x[j] + h;
  rhs(mode, t, jac_x_, jac_fp_);
  jac_x_[j] = x[j] - h;
  rhs(mode, t, jac_x_, jac_fm_);
  J.col(j) = (jac_fp_ - jac_fm_) / (Scalar(2) * h);
}

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::jacobian(const Mode& mode, Scalar t, const State& x, Matrix& J) {
  const Index N = state_size();
  if (x.size() != N)
    detail::throw_invalid("FrictionDampedSystem::jacobian", "x must have state_size() entries, size", x.size());
  if (mode.size() != D_)
    detail::throw_invalid("FrictionDampedSystem::jacobian", "mode must hold one state per damper, size", mode.size());
  J.resize(N, N);
  if (!exact_mode(mode)) {
    if (tangent_jacobian(mode, t, x, J)) {
      if (!contact_columns(mode, t, x, J, true))
        for (Index i = 0; i < D_; ++i)
          if (moving_[static_cast<std::size_t>(i)]) jacobian_column(mode, t, x, contact_offset() + i, J);
      return;
    }
    for (Index j = 0; j < N; ++j) jacobian_column(mode, t, x, j, J);
    return;
  }
  if (!linear_part(mode, t, x, jac_lp_)) {
    J.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
    return;
  }
  STICKSLIP_ASSERT(jac_lp_.exact && "FrictionDampedSystem::jacobian: exact_mode disagrees with linear_part");
  const Index P = linear_size();
  J.setZero();
  J.topLeftCorner(P, P) = jac_lp_.A;
  if (jac_lp_.has_quadrature_forms()) {  // d(z^T Q z)/dz = (Q + Q^T) z, its first P entries
    const Index K = static_cast<Index>(jac_lp_.omega.size());
    jac_z_.resize(P + 1 + 2 * K);
    jac_z_.head(P) = x.head(P);
    jac_z_[P] = Scalar(1);
    using std::cos;
    using std::sin;
    for (Index k = 0; k < K; ++k) {
      const Scalar w = jac_lp_.omega[static_cast<std::size_t>(k)];
      jac_z_[P + 1 + 2 * k] = cos(w * t);
      jac_z_[P + 2 + 2 * k] = sin(w * t);
    }
    for (std::size_t q = 0; q < jac_lp_.quadrature_forms.size(); ++q) {
      const Matrix& Q = jac_lp_.quadrature_forms[q];
      auto row = J.row(P + static_cast<Index>(q)).head(P).transpose();
      row.noalias() = Q.topRows(P) * jac_z_;
      row.noalias() += Q.leftCols(P).transpose() * jac_z_;
    }
  }
  if (options_.moving_contact && !contact_columns(mode, t, x, J, false))
    for (Index i = 0; i < D_; ++i) jacobian_column(mode, t, x, contact_offset() + i, J);
}

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::tangent_jacobian(const Mode& mode, Scalar t, const State& x,
                                                                 Matrix& J) {
  if (!tangent_applies(mode)) return false;
  // (every path that forms F_, L_, A_, u_ for another state - the frozen probes, the impulse
  // response, resolve - invalidates the cache, so after evaluate() they are x's)
  const Evaluation& e = evaluate(mode, t, x);
  const Index N = state_size(), n = n_, U = num_unknowns_, D2 = 2 * D_;
  if (!e.finite) {
    J.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
    return true;
  }
  if (jac_rho_.rows() != D2 || jac_rho_.cols() != N) {
    jac_rho_.setZero(D2, N);
    jac_du_.setZero(D2, N);
    for (auto* g : {&jac_gV_, &jac_gs_, &jac_gh_, &jac_gd_, &jac_gc_}) g->setZero(N);
    jac_shape_.resize(n);
  }
  J.setZero();
  const Index qd0 = n;  // first q' column
  // The solve: A u + L^T q'' = c (one row per unknown), q'' = r0 + F u, r0 = -omega^2 q - c q'
  // + (terms of X and t only). Its tangent in a direction dx, with F constant off the X columns
  // (a Coulomb slip coefficient is a constant, the shapes depend on X only):
  //   (A + L^T F) du = rho - L^T dr0,   rho_j = dc_j - dA_j u_j - dL_j^T q'',   dq'' = dr0 + F du.
  // rho is nonzero only in the rows of a stuck damper's friction (c = k x_d) and of a slipping
  // damper with a moving contact, whose row (moving_damper, over its diagonal s_j when divided)
  //   (1 - sc mu) N + m (a - sc b)^T q'' = N0 - m h + sc k x_d + m sc dd
  // carries the slope sc = q^T psi_w'(X) (with the convective terms), h = 2 (psi_w'^T q') V +
  // (psi_w''^T q) V^2 and dd = (psi_u'^T q') V, V = x_d' - b^T q'.
  auto rho = jac_rho_.topRows(U);
  rho.setZero();
  const bool convective = options_.convective_terms;
  for (Index j = 0; j < U; ++j) {
    const Index col = unknown_of_[static_cast<std::size_t>(j)];
    const Index i = col < D_ ? col : col - D_;
    const std::size_t iu = static_cast<std::size_t>(i);
    const Damper& dmp = dampers_[iu];
    const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
    if (col >= D_) {  // a stuck damper's friction row: f - m b^T q'' = k x_d
      rho(j, x_offset() + i) = dmp.effective_stiffness();
      continue;
    }
    if (stuck || !moving_[iu] || !convective) continue;  // N0 on the right: constant
    const auto& v = jacobian_shapes(i, e.X[i]);  // b = psi_u, psi_u', psi_w', psi_w'' at X
    const Scalar sd = dmp.side, m = dmp.effective_mass(), k = dmp.effective_stiffness();
    const auto q = x.segment(0, n), qd = x.segment(n, n);
    const Scalar V = e.V[i], sc = e.slope[i], mu = mu_[i], xi = x[x_offset() + i];
    const Scalar dw_qd = sd * v.dpsi_w.dot(qd), ddw_q = sd * v.ddpsi_w.dot(q), du_qd = v.dpsi_u.dot(qd);
    const Scalar dd = du_qd * V;
    // gradients (rows over the state) of V, sc, h and dd
    jac_gV_.setZero();
    jac_gV_[xd_offset() + i] = Scalar(1);
    jac_gV_.segment(qd0, n) = -v.psi_u.transpose();
    jac_gs_.setZero();
    jac_gs_.head(n) = sd * v.dpsi_w.transpose();
    jac_gh_ = (Scalar(2) * dw_qd + Scalar(2) * ddw_q * V) * jac_gV_;
    jac_gh_.head(n) += (V * V * sd) * v.ddpsi_w.transpose();
    jac_gh_.segment(qd0, n) += (Scalar(2) * V * sd) * v.dpsi_w.transpose();
    jac_gd_ = du_qd * jac_gV_;
    jac_gd_.segment(qd0, n) += V * v.dpsi_u.transpose();
    // rho_j = (dc - dA N - dL^T q'') / s_j with dc = -m dh + (k x_d + m dd) dsc + sc k dx_d +
    // m sc ddd, dA = -mu dsc, dL = -m b dsc
    jac_gc_ = -m * jac_gh_ + (k * xi + m * dd + mu * e.N[i] + m * v.psi_u.dot(e.qdd)) * jac_gs_ +
              (m * sc) * jac_gd_;
    jac_gc_[x_offset() + i] += sc * k;
    using std::abs;
    const Scalar diag = Scalar(1) - sc * mu;
    const Scalar s_j = diag != Scalar(1) && abs(diag) >= Scalar(0.5) ? diag : Scalar(1);
    rho.row(j) = jac_gc_ / s_j;
  }
  // dq'' = dr0 + F du (n x N), J's q'' rows; dr0 = -omega^2 dq - c dq'.
  auto qdd_rows = J.middleRows(n, n);
  if (U > 0) {
    const auto F = F_.topLeftCorner(n, U);
    const auto L = L_.topLeftCorner(n, U);
    rho.leftCols(n).noalias() += L.transpose() * omega2_.asDiagonal();
    rho.middleCols(qd0, n).noalias() += L.transpose() * modal_damping_.asDiagonal();
    Eigen::PartialPivLU<Matrix>& lu = tangent_lu(U);
    auto du = jac_du_.topRows(U);
    du.noalias() = lu.solve(rho);
    qdd_rows.noalias() = F * du;
  }
  qdd_rows.leftCols(n).diagonal() -= omega2_;
  qdd_rows.middleCols(qd0, n).diagonal() -= modal_damping_;
  J.topRows(n).middleCols(qd0, n).diagonal().setOnes();  // (q)' = q'
  // Per damper: x_d' rows, x_d'' rows, X' = V rows (moving slip), and the audit's friction and
  // slope rows; dN_i is du of N_i's unknown (0 for a constant normal load).
  const bool audit = options_.energy_audit;
  const Index o = audit ? energy_offset() : -1;
  if (audit) {
    for (Index l = 0; l < load_psi_.cols(); ++l)  // W_ext' = sum_l F_l(t) psi_l^T q'
      J.row(o).segment(qd0, n) += loads_[static_cast<std::size_t>(l)].value(t) * load_psi_.col(l).transpose();
    J.row(o + 1).segment(qd0, n) = Scalar(2) * modal_damping_.cwiseProduct(x.segment(n, n)).transpose();
  }
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const Damper& dmp = dampers_[iu];
    const Scalar m = dmp.effective_mass(), k = dmp.effective_stiffness();
    J(x_offset() + i, xd_offset() + i) = Scalar(1);
    const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
    if (stuck) {  // x_d'' = b^T q'' (V = 0: no X', friction or slope power)
      J.row(xd_offset() + i).noalias() = C_.col(D_ + i).head(n).transpose() * qdd_rows;
      continue;
    }
    const Index unknown = unknown_row(i);
    // x_d'' = (f - k x_d) / m, f = -mu N
    const Scalar mu = mu_[i];
    if (unknown >= 0) J.row(xd_offset() + i) = (-mu / m) * jac_du_.row(unknown);
    J(xd_offset() + i, x_offset() + i) -= k / m;
    // V = x_d' - b^T q' (b at X)
    jac_gV_.setZero();
    jac_gV_[xd_offset() + i] = Scalar(1);
    if (moving_[iu]) {
      jac_gV_.segment(qd0, n) = -modal(slip_b_.col(i)).transpose();
      J.row(contact_offset() + i) = jac_gV_;
    } else {
      jac_gV_.segment(qd0, n) = -C_.col(D_ + i).head(n).transpose();
    }
    if (!audit) continue;
    const Scalar V = e.V[i], Ni = e.N[i], fi = e.f[i];
    // D_fric' = -sum f V: -(V df + f dV), df = -mu dN
    if (unknown >= 0) J.row(o + 2) += (V * mu) * jac_du_.row(unknown);
    J.row(o + 2) -= fi * jac_gV_;
    if (options_.moving_contact && moving_[iu]) {  // W_slope' = -sum N slope V
      const Scalar sl = e.slope[i];
      if (unknown >= 0) J.row(o + 3) -= (sl * V) * jac_du_.row(unknown);
      J.row(o + 3) -= (Ni * sl) * jac_gV_;
      J.row(o + 3).head(n) -= (Ni * V * dmp.side) * jacobian_shapes(i, e.X[i]).dpsi_w.transpose();
    }
  }
  return true;
}

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::contact_columns(const Mode& mode, Scalar t, const State& x,
                                                                Matrix& J, bool lu_ready) {
  using std::abs;
  if (!tangent_applies(mode)) return false;
  // The solve A u + L^T q'' = c, q'' = r0 + F u at x (cached when rhs or the tangent just ran).
  const Evaluation& e = evaluate(mode, t, x);
  const Index n = n_, U = num_unknowns_;
  if (!e.finite) {
    for (Index i = 0; i < D_; ++i)
      if (moving_[static_cast<std::size_t>(i)]) J.col(contact_offset() + i).setConstant(std::numeric_limits<Scalar>::quiet_NaN());
    return true;
  }
  Eigen::PartialPivLU<Matrix>* lu = nullptr;
  if (U > 0) lu = lu_ready ? &jac_lu_[static_cast<std::size_t>(U)] : &tangent_lu(U);
  jac_d3w_.resize(n);
  jac_g_.resize(n);
  jac_dqdd_.resize(n);
  jac_dux_.resize(std::max<Index>(U, 1));
  jac_sol_.resize(std::max<Index>(U, 1));
  const auto q = x.segment(0, n), qd = x.segment(n, n), qdd = e.qdd.head(n);
  const bool audit = options_.energy_audit, convective = options_.convective_terms;
  const Index o = audit ? energy_offset() : -1;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    // X_i of a fixed contact stays X0 (f does not depend on it; its column, if the state has
    // one, is zero from the caller); without a moving contact the state has no X at all.
    if (!moving_[iu]) continue;
    const Index cX = contact_offset() + i;
    J.col(cX).setZero();
    // Shapes at X and their X-derivatives: b = psi_u, b' = psi_u' (psi_u'' = 0: linear in the
    // element), a = s psi_w, a' = s psi_w', and psi_w''' = B (0, w1''', t1''', 0, w2''', t2''')
    // (constant in the element: 12/Le^3, 6/Le^2, -12/Le^3, 6/Le^2).
    const Damper& dmp = dampers_[iu];
    const Shapes& shapes = shapes_[static_cast<std::size_t>(damper_shape_[iu])];
    const typename Shapes::Location loc = shapes.locate(e.X[i], cursors_[iu]);
    {
      const auto B = element_block(iu, loc.element);
      const Scalar inv = loc.weights.du, w3 = Scalar(12) * inv * inv * inv, t3 = Scalar(6) * inv * inv;
      jac_d3w_.noalias() = w3 * (B.col(1) - B.col(4)) + t3 * (B.col(2) + B.col(5));
    }
    const auto& v = jacobian_shapes(i, e.X[i]);
    const Scalar sd = dmp.side, m = dmp.effective_mass(), k = dmp.effective_stiffness();
    const Scalar xi = x[x_offset() + i];
    const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
    const Index jN = unknown_row(i), jf = unknown_row(D_ + i);  // N_i's and (stuck) f_i's rows
    // d/dX of the solve: (A + L^T F) du = rho - L^T g, dq'' = g + F du, with
    // rho_j = (dc_j - dA_j u_j - dL_j^T q'') / s_j in damper i's rows and g = dr0 + dF u.
    jac_g_.setZero();
    jac_dux_.setZero();
    const Scalar slope = sd * v.dpsi_w.dot(q), dslope = sd * v.ddpsi_w.dot(q);
    Scalar dV = 0;  // dV/dX of a slipping damper (V = x_d' - b^T q')
    if (stuck) {
      if (jN >= 0) {  // N + m a^T q'' = N0: F_j = a, L_j = m a
        jac_g_.noalias() += (sd * u_[jN]) * v.dpsi_w;
        jac_dux_[jN] = -m * sd * v.dpsi_w.dot(qdd);
      } else {  // N0 a in r0
        jac_g_.noalias() += (sd * dmp.preload) * v.dpsi_w;
      }
      if (jf >= 0) {  // f - m b^T q'' = k x_d: F_j = -b, L_j = -m b
        jac_g_.noalias() -= u_[jf] * v.dpsi_u;
        jac_dux_[jf] = m * v.dpsi_u.dot(qdd);
      }
    } else {
      const Scalar mu = mu_[i], V = e.V[i];
      dV = -v.dpsi_u.dot(qd);
      if (jN >= 0) {  // F_j = a + mu b, L_j = m (a - sc b), A_j = 1 - sc mu, c_j = N0 - m h + sc k x_d + m sc dd
        const Scalar Ni = u_[jN];
        jac_g_.noalias() += Ni * (sd * v.dpsi_w + mu * v.dpsi_u);
        Scalar rho = -m * sd * v.dpsi_w.dot(qdd), diag = Scalar(1);
        if (convective) {
          const Scalar sc = slope, dsc = dslope;
          const Scalar dw_qd = sd * v.dpsi_w.dot(qd), ddw_q = sd * v.ddpsi_w.dot(q);
          const Scalar d_dw_qd = sd * v.ddpsi_w.dot(qd), d_ddw_q = sd * jac_d3w_.dot(q);
          const Scalar du_qd = v.dpsi_u.dot(qd), dd = du_qd * V, d_dd = du_qd * dV;
          const Scalar dh = Scalar(2) * (d_dw_qd * V + dw_qd * dV) + d_ddw_q * V * V + Scalar(2) * ddw_q * V * dV;
          const Scalar dc = -m * dh + dsc * k * xi + m * dsc * dd + m * sc * d_dd;
          const Scalar dA = -dsc * mu;
          // dL = m (a' - sc' b - sc b')
          rho += dc - dA * Ni + m * (dsc * v.psi_u.dot(qdd) + sc * v.dpsi_u.dot(qdd));
          diag = Scalar(1) - sc * mu;
        }
        const Scalar s_j = diag != Scalar(1) && abs(diag) >= Scalar(0.5) ? diag : Scalar(1);
        jac_dux_[jN] = rho / s_j;
      } else {  // N0 (a + mu b) in r0
        jac_g_.noalias() += dmp.preload * (sd * v.dpsi_w + mu * v.dpsi_u);
      }
    }
    auto du = jac_sol_.head(U);
    if (U > 0) {
      jac_dux_.head(U).noalias() -= L_.topLeftCorner(n, U).transpose() * jac_g_;
      du.noalias() = lu->solve(jac_dux_.head(U));
      jac_dqdd_.noalias() = jac_g_ + F_.topLeftCorner(n, U) * du;
    } else {
      jac_dqdd_ = jac_g_;
    }
    auto col = J.col(cX);
    col.segment(n, n) = jac_dqdd_;
    // Per damper l: x_d'' (stick: b_l^T q''; slip: (-mu N_l - k x_d) / m), X' = V (moving slip)
    // and the audit's friction and slope power; dN_l, df_l from du.
    for (Index l = 0; l < D_; ++l) {
      const std::size_t lw = static_cast<std::size_t>(l);
      const Damper& dl = dampers_[lw];
      const bool l_stuck = has_stick_[lw] && mode[l] == ContactState::Stick;
      const Index l_unknown = unknown_row(l);
      const Scalar dN = l_unknown >= 0 ? du[l_unknown] : Scalar(0);
      if (l_stuck) {
        const auto bl = C_.col(D_ + l).head(n);
        col[xd_offset() + l] = bl.dot(jac_dqdd_) + (l == i ? v.dpsi_u.dot(qdd) : Scalar(0));
        continue;
      }
      const Scalar mu = mu_[l];
      col[xd_offset() + l] = -mu * dN / dl.effective_mass();
      const Scalar dVl = l == i ? dV : Scalar(0);
      if (l == i) col[cX] = dV;  // X' = V
      if (!audit) continue;
      const Scalar Vl = e.V[l], Nl = e.N[l], fl = e.f[l];
      col[o + 2] += Vl * mu * dN - fl * dVl;  // D_fric' = -f V, df = -mu dN
      if (moving_[lw]) {  // W_slope' = -N slope V
        const Scalar sl = e.slope[l], dsl = l == i ? dslope : Scalar(0);
        col[o + 3] -= dN * sl * Vl + Nl * dsl * Vl + Nl * sl * dVl;
      }
    }
  }
  return true;
}

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::frozen_guard_rows(const Mode& mode, Scalar t, const State& x,
                                                                   LinearPart<Scalar>& lp) {
  using std::cos;
  using std::sin;
  const Index P = linear_size(), G = lp.Gx.rows(), K = static_cast<Index>(lp.omega.size());
  // End guards (X, L - X; a constant 1 at an end that extends): rows of the contact coordinate
  // (+1, -1; g0 below adds 0, L), which the probes hold at X* (their X columns are not probed).
  Index k = 0;
  for (Index i = 0; i < D_; ++i) {
    k += contact_guards_of(mode, i);
    if (!end_guards_of(mode, i)) continue;
    const std::size_t iu = static_cast<std::size_t>(i);
    for (Index e = 0; e < 2; ++e, ++k) {
      lp.Gx.row(k).setZero();
      lp.gc.row(k).setZero();
      lp.gs.row(k).setZero();
      if (end_kind_[iu][static_cast<std::size_t>(e)] != MemberEnd::Extend)
        lp.Gx(k, contact_offset() + i) = e == 0 ? Scalar(1) : Scalar(-1);
    }
  }
  // g0 = g(t, x) - Gx x_L - sum_k (gc_k cos w_k t + gs_k sin w_k t): the rows equal guards() at
  // the refresh point.
  fill_guards(mode, evaluate(mode, t, x), lp_g_.data());
  lp_g_.head(G).noalias() -= lp.Gx * x.head(P);
  lp.g0 = lp_g_.head(G);
  for (Index kk = 0; kk < K; ++kk) {
    const Scalar w = lp.omega[static_cast<std::size_t>(kk)];
    lp.g0 -= cos(w * t) * lp.gc.col(kk) + sin(w * t) * lp.gs.col(kk);
  }
}

// ---- separation: lift-off into flight, impacts, landings (docs/model_separation.md "Separation") --------

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::member_contact(Index i, const State& x) const -> MemberContact {
  const std::size_t iu = static_cast<std::size_t>(i);
  const Scalar X = moving_[iu] ? x[contact_offset() + i] : dampers_[iu].contact_coordinate;
  if (moving_[iu]) evaluate_shapes(i, X);
  const auto q = x.template segment<Modes>(0, n_);
  const auto qd = x.template segment<Modes>(n_, n_);
  MemberContact c;
  c.y = q.dot(modal(C_.col(i)));
  c.V = x[xd_offset() + i] - qd.dot(modal(C_.col(D_ + i)));
  c.slope = moving_[iu] ? q.dot(modal(dpsi_w_.col(i))) : Scalar(0);
  c.yd = qd.dot(modal(C_.col(i))) + c.slope * c.V;
  return c;
}

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::separate(Mode& mode, Index i, Scalar t, State& x) {
  const MemberContact c = member_contact(i, x);
  const Index y = flight_offset() + flight_slot_[static_cast<std::size_t>(i)];
  x[y] = c.y;
  x[y + num_separable_] = c.yd;
  events_.push_back(ContactEvent{t, i, mode[i], ContactState::Separated});
  mode[i] = ContactState::Separated;
  cache_valid_ = false;
}

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::impulse_response(const Mode& mode, const State& x) {
  // The frozen solve (solve_forces<true>) is the impulse problem when r0 is the impulse and the
  // state, preloads and slip coefficients are zero: q'' -> the jump of q', N and f -> the other
  // dampers' impulses, x'' -> the jumps of their x'. The other contacts act through their rows:
  // a stuck damper's tangential and (inertial) normal constraint, a slipping one's normal
  // constraint without its friction impulse (mu = 0: a symmetric W, no work of the constraints).
  lp_xs_.setZero();
  if (options_.moving_contact) lp_xs_.segment(contact_offset(), D_) = x.segment(contact_offset(), D_);
  lp_mu_.setZero();
  for (Index j = 0; j < D_; ++j) std::swap(lp_preload_[static_cast<std::size_t>(j)], dampers_[static_cast<std::size_t>(j)].preload);
  const bool refine = options_.refine_stale_factorisation;
  options_.refine_stale_factorisation = false;
  factor_unknowns_ = -1;
  for (Index c = 0; c < 2; ++c) {
    modal(r0_) = modal(impulse_dir_.col(c));
    solve_forces<true>(mode, lp_xs_);
    response_.col(c) = eval_.qdd;
    response_x_.col(c) = eval_.xdd;
  }
  for (Index j = 0; j < D_; ++j) std::swap(lp_preload_[static_cast<std::size_t>(j)], dampers_[static_cast<std::size_t>(j)].preload);
  options_.refine_stale_factorisation = refine;
  factor_unknowns_ = -1;
  cache_valid_ = false;
}

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::impact(Mode& mode, Index i, Scalar t, State& x) {
  using Mat2 = Eigen::Matrix<Scalar, 2, 2>;
  using Vec2 = Eigen::Matrix<Scalar, 2, 1>;
  const std::size_t iu = static_cast<std::size_t>(i);
  const Damper& d = dampers_[iu];
  const Scalar m = d.effective_mass();
  // A damper held at a wall in flight lands (or bounces) with its own rows out of the member's
  // response, as any flying damper; the wall holds it again afterwards if nothing moves it away.
  const WallRest held = mode.wall(i);
  mode.set_wall(i, WallRest::None);
  const MemberContact c = member_contact(i, x);  // i's shapes now in C_
  const Scalar s = c.slope;
  // Rows of the gap rate g' = (a - s b)^T q' + s x' - y_d' and of V = x' - b^T q' in the
  // velocities (q', x', y_d'); the impulse L = (L_n, L_t) acts on them through these rows.
  impulse_dir_.col(0) = C_.col(i) - s * C_.col(D_ + i);
  impulse_dir_.col(1) = -C_.col(D_ + i);
  const Index y = flight_offset() + flight_slot_[iu], yd = y + num_separable_;
  const Vec2 v(c.yd - x[yd], c.V);
  impulse_response(mode, x);
  const Mat2 W = inverse_effective_mass(s, m);
  auto solve_impact = [&](const NewtonImpact<Scalar>& newton) {
    return detail::with_law(d.law, [&](const auto& law) {
      using L = std::decay_t<decltype(law)>;
      if constexpr (L::has_stick_state) {
        return frictional_impact(newton, law, W, v);
      } else {  // a bounded friction force has no impulse: Newton's law alone, through W_nn
        FrictionalImpact<Scalar> r;
        const NormalImpact<Scalar> normal = newton.impact(v[0], W(0, 0));
        r.impulse = Vec2(normal.impulse, Scalar(0));
        r.velocity_after = v + W.col(0) * normal.impulse;
        r.velocity_after[0] = normal.velocity_after;
        r.energy_loss = normal.energy_loss;
        r.lands = normal.lands;
        r.state = slip_state(r.velocity_after[1]);
        return r;
      }
    });
  };
  // The velocity jumps of an impulse L on the damper (and -L through the rows on the member).
  auto apply = [&](const Vec2& L) {
    x.segment(n_, n_) += response_ * L;
    for (Index j = 0; j < D_; ++j)
      if (j != i) x[xd_offset() + j] += response_x_(j, 0) * L[0] + response_x_(j, 1) * L[1];
    x[xd_offset() + i] += (s * L[0] + L[1]) / m;
    x[yd] -= L[0] / m;
  };
  FrictionalImpact<Scalar> hit = solve_impact(NewtonImpact<Scalar>(d.restitution, d.landing_speed));
  if (!hit.resolved) return false;
  apply(hit.impulse);
  if (!hit.lands && rebound_within_band(mode, i, t, x, hit.velocity_after[0])) {
    // A rebound too low to leave the landing band is a landing (docs/model_separation.md "Separation"):
    // the plastic impact (e = 0) in its place, i.e. the difference of the two impulses added.
    const FrictionalImpact<Scalar> landing = solve_impact(NewtonImpact<Scalar>(Scalar(0), d.landing_speed));
    if (!landing.resolved) return false;
    apply(landing.impulse - hit.impulse);
    hit = landing;
  }
  const Vec2& L = hit.impulse;
  if (audit_size() > 4) x[energy_offset() + 4] += hit.energy_loss;
  const ContactState to = hit.lands ? hit.state : ContactState::Separated;
  if (held != WallRest::None) {  // back at the wall: held (V = 0 in flight), or an impact on it
    const Scalar V_after = hit.velocity_after[1];
    const bool into = held == WallRest::Start ? V_after < Scalar(0) : V_after > Scalar(0);
    if (into) wall_hits_.emplace_back(i, held == WallRest::Start ? 0 : 1);
    else if (to == ContactState::Separated && V_after == Scalar(0)) mode.set_wall(i, held);
  }
  impacts_.push_back(ImpactEvent{t, i, L[0], L[1], v[0], hit.velocity_after[0], v[1], hit.velocity_after[1],
                                 hit.energy_loss, to});
  events_.push_back(ContactEvent{t, i, ContactState::Separated, to});
  mode[i] = to;
  if (to == ContactState::Stick) involved_.push_back(i);  // resolve() decides stick or slip
  cache_valid_ = false;
  return true;
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::flight_gap_acceleration(const Mode& mode, Index i, Scalar t,
                                                                         const State& x) -> Scalar {
  STICKSLIP_ASSERT(mode[i] == ContactState::Separated);
  const std::size_t iu = static_cast<std::size_t>(i);
  const Damper& d = dampers_[iu];
  const Evaluation& e = evaluate(mode, t, x);  // q'' with i in flight (no force of i on the member)
  const Scalar pull = d.preload / d.effective_mass();
  const auto qdd = modal(e.qdd);
  if (!moving_[iu]) return qdd.dot(modal(C_.col(i))) - pull;  // a fixed point: y'' = a^T q''
  const Scalar Vdot = flight_sliding_acceleration(mode, i, t, x);  // (evaluates the same, cached)
  const auto& v = values_[iu];
  const auto q = x.template segment<Modes>(0, n_);
  const auto qd = x.template segment<Modes>(n_, n_);
  const Scalar side = d.side, V = e.V[i];
  return side * (v.psi_w.dot(qdd) + Scalar(2) * v.dpsi_w.dot(qd) * V + v.ddpsi_w.dot(q) * V * V) + e.slope[i] * Vdot -
         pull;
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::flight_sliding_acceleration(const Mode& mode, Index i, Scalar t,
                                                                             const State& x) -> Scalar {
  const std::size_t iu = static_cast<std::size_t>(i);
  const Evaluation& e = evaluate(mode, t, x);
  if (!moving_[iu]) return Scalar(0);
  evaluate_shapes(i, e.X[i]);
  const auto& v = values_[iu];
  const auto qd = x.template segment<Modes>(n_, n_);
  return e.xdd[i] - v.psi_u.dot(modal(e.qdd)) - v.dpsi_u.dot(qd) * e.V[i];
}

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::release_pulled_holds(Mode& mode, Scalar t, const State& x) {
  for (Index pass = 0; pass <= D_; ++pass) {
    const Evaluation& e = evaluate(mode, t, x);
    if (!e.finite) return;
    bool changed = false;
    for (Index i = 0; i < D_; ++i) {
      const WallRest w = mode.wall(i);
      if (mode[i] != ContactState::Separated || w == WallRest::None) continue;
      const Scalar F = e.f[i] + e.wall_force[i];
      if (w == WallRest::Start ? F < Scalar(0) : F > Scalar(0)) {
        mode.set_wall(i, WallRest::None);
        changed = true;
      }
    }
    if (!changed) return;
  }
}

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::rebound_within_band(const Mode& mode, Index i, Scalar t,
                                                                     const State& x, Scalar v_after) {
  const Scalar a = flight_gap_acceleration(mode, i, t, x);
  const Scalar band = Scalar(kLandingBand) * shapes_[static_cast<std::size_t>(damper_shape_[static_cast<std::size_t>(i)])].length();
  return a < Scalar(0) && v_after * v_after <= Scalar(-2) * a * band;
}

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::wall_impact(Mode& mode, Index i, int end, Scalar t, State& x) {
  const std::size_t iu = static_cast<std::size_t>(i);
  const Damper& d = dampers_[iu];
  const Scalar m = d.effective_mass();
  const MemberContact c = member_contact(i, x);  // i's shapes now in C_
  const Scalar V = c.V;
  if (!(end == 0 ? V < Scalar(0) : V > Scalar(0))) return;  // not moving into the wall
  // V = x' - b^T q': the impulse L_t on the damper along u acts on the member as -b L_t. A
  // damper in contact with an inertial normal load keeps its contact through the impact: with
  // a slope s, V's jump moves it along the normal by s dV, which takes a normal impulse L_n
  // with gap' = (a - s b)^T q' + s x' - y_d' held at 0 (the rows of impact(); its own contact
  // rows are taken out of the member's response for this, and its friction impulse left out).
  const bool normal = inertial_[iu] && mode[i] != ContactState::Separated;
  const Scalar s = normal ? c.slope : Scalar(0);
  impulse_dir_.col(0) = C_.col(i) - s * C_.col(D_ + i);
  impulse_dir_.col(1) = -C_.col(D_ + i);
  const char inertial = inertial_[iu];
  inertial_[iu] = 0;  // (no preload in the probe: no rows of its own)
  impulse_response(mode, x);
  inertial_[iu] = inertial;
  // Resting contact (docs/model_separation.md "Resting at a wall"): a damper in contact with a stick state
  // that arrives at or below its landing speed, or at a plastic wall, stops against it.
  using std::abs;
  const bool rests = has_stick_[iu] && mode[i] != ContactState::Separated &&
                     (d.wall_restitution == Scalar(0) || abs(V) <= d.landing_speed);
  // Held in flight (docs/model_separation.md "Held at a wall in flight"): a separated damper that arrives at
  // or below its landing speed, at a plastic wall, or whose rebound would turn within the wall
  // band (V^2 e^2 <= 2 |V'| kWallBand L with V' pushing it into the wall: no velocity guard in
  // flight would see that turning point) stays at the wall.
  const bool holds = mode[i] == ContactState::Separated && [&] {
    if (d.wall_restitution == Scalar(0) || abs(V) <= d.landing_speed) return true;
    const Scalar push = (end == 0 ? Scalar(-1) : Scalar(1)) * flight_sliding_acceleration(mode, i, t, x);
    const Scalar Lm = shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
    const Scalar rebound = d.wall_restitution * V;
    return push > Scalar(0) && rebound * rebound <= Scalar(2) * push * Scalar(kWallBand) * Lm;
  }();
  const Scalar V_after = rests || holds ? Scalar(0) : -d.wall_restitution * V;
  Eigen::Matrix<Scalar, 2, 1> L(Scalar(0), Scalar(0));
  if (normal) {
    L = inverse_effective_mass(s, m).inverse() * Eigen::Matrix<Scalar, 2, 1>(Scalar(0), V_after - V);
  } else {
    L[1] = (V_after - V) / (Scalar(1) / m + impulse_dir_.col(1).dot(response_.col(1)));
  }
  x.segment(n_, n_) += response_ * L;
  for (Index j = 0; j < D_; ++j)
    if (j != i) x[xd_offset() + j] += response_x_(j, 0) * L[0] + response_x_(j, 1) * L[1];
  x[xd_offset() + i] += (s * L[0] + L[1]) / m;
  const Scalar loss = -L[1] * (V + V_after) / Scalar(2);
  if (audit_size() > 4) x[energy_offset() + 4] += loss;
  ContactState to = mode[i];
  if (mode[i] != ContactState::Separated) {
    if (rests) {  // at the end (it was within |V| times the event time tolerance of it)
      to = ContactState::Stick;
      mode.set_wall(i, end == 0 ? WallRest::Start : WallRest::Finish);
      x[contact_offset() + i] = end == 0 ? Scalar(0) : shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
      involved_.push_back(i);  // resolve() keeps it (the wall takes the push) or lets it slip away
    } else {
      to = slip_state(V_after);
    }
  } else if (holds) {
    mode.set_wall(i, end == 0 ? WallRest::Start : WallRest::Finish);
    x[contact_offset() + i] = end == 0 ? Scalar(0) : shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
  }
  impacts_.push_back(ImpactEvent{t, i, L[0], L[1], Scalar(0), Scalar(0), V, V_after, loss, to, true});
  events_.push_back(ContactEvent{t, i, mode[i], to});
  mode[i] = to;
  cache_valid_ = false;
}

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::separation_transition(Mode& mode, Scalar t, State& x) {
  for (Index i : impacting_)
    if (!impact(mode, i, t, x)) return false;
  for (const auto& hit : wall_hits_) wall_impact(mode, hit.first, hit.second, t, x);
  for (Index i : lifting_) separate(mode, i, t, x);
  involved_.erase(std::remove_if(involved_.begin(), involved_.end(),
                                 [&](Index i) { return mode[i] == ContactState::Separated; }),
                  involved_.end());
  return true;
}

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::land_or_separate(Mode& mode, const std::vector<Index>& candidates,
                                                                  Scalar t, State& x) {
  for (Index pass = 0; pass <= D_; ++pass) {
    bool changed = false;
    for (Index i : candidates) {
      if (flight_slot_[static_cast<std::size_t>(i)] < 0 || mode[i] == ContactState::Separated) continue;
      const Evaluation& e = evaluate(mode, t, x);
      if (!e.finite) return true;  // reported by the stepper's finiteness check
      if (e.N[i] > Scalar(0)) continue;
      separate(mode, i, t, x);
      changed = true;
    }
    if (!changed) return true;
    involved_.clear();
    if (!resolve(mode, involved_, t, x)) return false;
  }
  return true;
}

// ---- resting at a wall (docs/model_separation.md "Resting at a wall") -----------------------------------

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::split_wall_reaction(const Mode& mode) const {
  Evaluation& e = eval_;
  for (Index i = 0; i < D_; ++i) {
    e.wall_force[i] = Scalar(0);
    const WallRest wall = mode.wall(i);
    if (wall == WallRest::None) continue;
    const Scalar mu_s = detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [](const auto& law) -> Scalar {
      if constexpr (std::decay_t<decltype(law)>::has_stick_state)
        return law.static_coefficient();
      else
        return Scalar(0);  // (never resting: validate_walls)
    });
    // Start wall (X = 0): it pushes the damper along +u, R >= 0, and takes f - mu_s N when the
    // force f needed to hold the damper exceeds the friction bound mu_s N; finish wall: R <= 0.
    const Scalar capacity = mu_s * e.N[i];
    const Scalar excess = wall == WallRest::Start ? e.f[i] - capacity : e.f[i] + capacity;
    if (wall == WallRest::Start ? excess > Scalar(0) : excess < Scalar(0)) {
      e.wall_force[i] = excess;
      e.f[i] = wall == WallRest::Start ? capacity : -capacity;  // exactly the bound (not f - excess)
    }
  }
}

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::rest_at_wall(Mode& mode, Index i, ContactState next, State& x) {
  const std::size_t iu = static_cast<std::size_t>(i);
  if (!moving_[iu] || mode.wall(i) != WallRest::None) return false;
  const int end = next == ContactState::SlipNegative ? 0 : 1;  // the end it would slip towards
  if (end_kind_[iu][static_cast<std::size_t>(end)] != MemberEnd::Wall) return false;
  const Scalar L = shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
  const Scalar X = x[contact_offset() + i], band = Scalar(kWallBand) * L;
  if (end == 0 ? X > band : X < L - band) return false;
  mode.set_wall(i, end == 0 ? WallRest::Start : WallRest::Finish);
  x[contact_offset() + i] = end == 0 ? Scalar(0) : L;
  return true;
}

template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::validate_walls(const Mode& mode, const char* where) const {
  for (Index i = 0; i < D_; ++i) {
    const WallRest wall = mode.wall(i);
    if (wall == WallRest::None) continue;
    const std::size_t iu = static_cast<std::size_t>(i);
    const bool needs_stick = mode[i] != ContactState::Separated;  // (held in flight: no friction)
    if (!moving_[iu] || (needs_stick && !has_stick_[iu]) || end_kind_[iu][wall == WallRest::Start ? 0 : 1] != MemberEnd::Wall)
      throw std::invalid_argument(std::string(where) + ": mode[" + std::to_string(i) + "] rests at the " +
                                  (wall == WallRest::Start ? "start" : "finish") + " wall, but damper " +
                                  std::to_string(i) + " has no wall there (a moving contact, a law with a "
                                  "stick state and MemberEnd::Wall at that end are needed)");
  }
}

}  // namespace stickslip

#ifdef STICKSLIP_COMPILED
// The compiled mode: FrictionDampedSystem<double> (dynamic modes, the default law variant) is
// instantiated once, in stickslip::compiled (src/friction_damped_system.cpp).
namespace stickslip {
extern template class FrictionDampedSystem<double>;
}  // namespace stickslip
#endif
