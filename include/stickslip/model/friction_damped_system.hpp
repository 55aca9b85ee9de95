#pragma once
/// \file friction_damped_system.hpp
/// \brief A frame's retained modes + any number of sliding point-contact friction dampers +
/// external point loads, as a hybrid system for HybridStepper (the paper's eqs 11-29,
/// generalised to N dampers on any members). The algebra is written out in docs/model.md.
/// This header holds the class and its documented interface; its members are defined in one
/// header per job under detail/friction_damped_system/ (scene, layout, kinematics, solve,
/// factorisation, guards, transitions, separation, walls, energy, linear_part, jacobian),
/// included at its end (docs/architecture.md, "The composition layer").

#include "stickslip/beam.hpp"
#include "stickslip/contact.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/modal.hpp"
#include "stickslip/model/damper_states.hpp"
#include "stickslip/model/friction_damped_records.hpp"
#include "stickslip/model/detail/enum_checks.hpp"
#include "stickslip/model/detail/format_frequency.hpp"
#include "stickslip/model/detail/slip_direction.hpp"
#include "stickslip/model/detail/law_visit.hpp"
#include "stickslip/model/detail/small_solve.hpp"
#include "stickslip/model/detail/friction_damped_system/workspaces.hpp"
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

  /// One contact switch, logged by `transition` (DamperContactEvent).
  using ContactEvent = DamperContactEvent<Scalar>;
  /// One impact of a separated damper or of a moving contact on a wall (DamperImpactEvent).
  using ImpactEvent = DamperImpactEvent<Scalar>;
  /// Why the system stopped a run (DamperStopReason).
  using StopReason = DamperStopReason;
  /// The most recent non-finite point-load value (LoadFault).
  using LoadFault = stickslip::LoadFault<Scalar>;
  /// Forces and kinematics of the dampers at one (mode, t, x) (DamperEvaluation).
  using Evaluation = DamperEvaluation<Scalar>;
  /// How the last acceleration solve was done (DamperSolveInfo).
  using SolveInfo = DamperSolveInfo;
  /// Terms of the energy balance (DamperEnergyBalance).
  using EnergyBalance = DamperEnergyBalance<Scalar>;

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
  std::vector<std::complex<Scalar>> linear_rates() const;
  /// Modal row vector of the displacement of point `eps` of `member` along `direction`
  /// (GlobalX/GlobalY/Axial/Transverse; Moment gives the rotation): displacement = psi . q.
  /// The member must carry a damper or a load; throws std::invalid_argument otherwise.
  Vector point_shape(MemberId member, Scalar eps, LoadDirection direction) const;

  /// Rest state: q = q' = 0, dampers at their supports, contacts at X0, audit integrals 0.
  State initial_state() const;

  /// The dampers' requested initial states.
  Mode requested_mode() const;

  /// Checks that x has state_size() entries, mode has num_dampers() states, each a ContactState
  /// enumerator other than LiftOff, and that only dampers
  /// that may separate (flight_slot(i) >= 0) are ContactState::Separated (two comparisons and two per damper;
  /// done by evaluate() before every solve, so by rhs, guards, make_consistent and the outputs,
  /// and by simulate() before the first step).
  /// \throws std::invalid_argument naming `where`, the expected and the given sizes, or the
  ///         separated damper
  void validate_state(const Mode& mode, const State& x, const char* where = "FrictionDampedSystem") const;

  // ---- hybrid-system concept ------------------------------------------------------------------
  /// dx/dt in mode `mode` (the coupled solve of docs/model_solve.md, then the state derivatives).
  void rhs(const Mode& mode, Scalar t, const State& x, State& dxdt);

  /// Number of guards in `mode`: per damper its contact guards (CoulombContact::num_guards:
  /// exact laws stuck two, mu_s N -+ f, slipping one, V; regularised laws none; then N when
  /// lift-off is watched; a separated damper one, its gap), then the member-end guards X and
  /// L - X while it can slide or fly with a moving contact and an end that does not extend
  /// (PointDamper::start_end / finish_end, MemberEnd; an extending end's guard is 1).
  Index num_guards(const Mode& mode) const;

  /// Guard values at (mode, t, x), in the order of num_guards(); an event is a zero crossing in
  /// the direction of guard_direction().
  void guards(const Mode& mode, Scalar t, const State& x, GuardVector& g);

  /// Crossing direction that triggers guard `idx` of `mode` (CoulombContact::guard_direction;
  /// member-end guards: Falling).
  CrossingDirection guard_direction(const Mode& mode, Index idx) const;

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
  void validate_start(const Mode& mode, Scalar t0, const State& x0, const char* where, const char* t_name = "t0",
                      const char* x_name = "x0") const;

  /// Mechanical energy: modal kinetic + strain energy, the dampers' kinetic energy along u
  /// (and along w with an inertial normal load), spring energy, and the preload's potential.
  Scalar mechanical_energy(const Mode& mode, Scalar t, const State& x);

  /// Energy balance at (mode, t, x) against the mechanical energy E0 of the run's start.
  /// Requires the energy audit option (throws std::invalid_argument otherwise).
  EnergyBalance energy_balance(const Mode& mode, Scalar t, const State& x, Scalar E0);

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
  /// True when linear_part is exact in every mode (no time_function load, every contact fixed
  /// and every law a CoulombLaw): Integrator::Auto's test for the exponential method.
  bool every_mode_exact() const;

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

  static constexpr int kMaxRefinements = 6;
  /// Relative size (max norm) of the last correction at which refinement stops: 16 units of
  /// round-off, about the accuracy of the direct LU solve of these well-conditioned matrices.
  static constexpr Scalar kRefineTol = Scalar(16) * std::numeric_limits<Scalar>::epsilon();

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

  /// The member's normal displacement y = a^T q and velocity y' = a^T q' + slope V (slope with a
  /// moving contact) under damper i, its slope and sliding velocity V; leaves i's shapes in C_.
  struct MemberContact {
    Scalar y, yd, slope, V;
  };
  /// Height of the landing band relative to the member length (1e-8 L: 4e-10 m on a 4 cm
  /// platform): a bounce whose flight would not rise above it lands. Well above the stepper's
  /// default guard_zero_tolerance (1e-12), by which a gap guard restarted at zero sinks at each
  /// located impact (docs/model_separation.md "Separation").
  static constexpr double kLandingBand = 1e-8;

  /// Width of the band at a wall end, relative to the member length, in which a damper at rest
  /// counts as lying at the wall (1e-8 L: 4e-10 m on a 4 cm platform, above the default
  /// guard_zero_tolerance of 1e-12 and far below any slip that matters).
  static constexpr double kWallBand = 1e-8;

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

  // Workspaces of linear_part() and jacobian() (detail/friction_damped_system/workspaces.hpp).
  detail::LinearPartWork<Scalar> lp_;
  detail::JacobianWork<Scalar> jac_;

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

  // Members defined in the rooms, include/stickslip/model/detail/friction_damped_system/<room>.hpp
  // (docs/architecture.md, "The composition layer"), each documented at its definition.
  // scene.hpp
  Vector load_vector(std::size_t shape, const Load& load) const;
  void allocate_workspace();
  // layout.hpp
  template <class Out>
  void linear_derivative(const Evaluation& e, const State& x, Out& d) const;
  template <class Out>
  void flight_derivative(const State& x, Out& d) const;
  // kinematics.hpp
  void evaluate_shapes(Index i, Scalar X) const;
  void flight_rows(Index i, const State& x) const;
  void moving_damper(Index i, const Mode& mode, const State& x) const;
  template <class DstF, class DstL, class DstB, class Block6>
  static void slip_columns(DstF&& dstF, DstL&& dstL, DstB&& dstB, const Block6& B,
                           const Eigen::Matrix<Scalar, 6, 1>& ca, const Eigen::Matrix<Scalar, 6, 1>& cb, Scalar mu,
                           Scalar la, Scalar lb);
  template <bool Add, class Dst, class Block6>
  static void block_times(Dst&& dst, const Block6& B, const Eigen::Matrix<Scalar, 6, 1>& c);
  MemberContact member_contact(Index i, const State& x) const;
  Scalar flight_gap_acceleration(const Mode& mode, Index i, Scalar t, const State& x);
  Scalar flight_sliding_acceleration(const Mode& mode, Index i, Scalar t, const State& x);
  // solve.hpp
  Scalar slip_coefficient(Index i, ContactState s, Scalar V) const;
  void solve(const Mode& mode, Scalar t, const State& x) const;
  void structural_r0(const State& x) const;
  template <bool Frozen>
  void solve_forces(const Mode& mode, const State& x) const;
  Index add_unknown(Index i, Scalar diag, Scalar rhs, Scalar mu, Scalar sc, Index column = -1) const;
  // factorisation.hpp
  void solve_unknowns(Index U) const;
  bool same_columns(Index U) const;
  template <class Directions, class Coefficients, class Unknowns>
  bool refine(const Directions& F, const Directions& L, const Coefficients& A, const Coefficients& c, Unknowns u) const;
  template <int K, class Factor>
  void solve_small(Index U, bool reuse, Factor& lu) const;
  template <int Cols, int K = Cols, class Factor>
  void solve_small_products(Index U, bool reuse, Factor& lu) const;
  template <int K, class Factor>
  void solve_mode_space_small(Index U, bool reuse, Factor& lu) const;
  Eigen::PartialPivLU<Matrix>& sized_lu(Index U) const;
  // guards.hpp
  Index contact_guards_of(const Mode& mode, Index i) const;
  bool watch_lift_off(Index i) const;
  bool end_guards_of(const Mode& mode, Index i) const;
  Index guards_of(const Mode& mode, Index i) const;
  void fill_guards(const Mode& mode, const Evaluation& e, Scalar* g) const;
  // transitions.hpp
  bool resolve(Mode& mode, std::vector<Index>& involved, Scalar t, State& x);
  void set_stuck_velocities(const Mode& mode, State& x);
  TransitionAction stop(StopReason why, Index i, Scalar t, const State& x, const Mode& mode);
  Index unpressed_contact(const Mode& mode, Scalar t, const State& x);
  // separation.hpp
  bool separation_transition(Mode& mode, Scalar t, State& x);
  void separate(Mode& mode, Index i, Scalar t, State& x);
  Eigen::Matrix<Scalar, 2, 2> inverse_effective_mass(Scalar s, Scalar m) const;
  bool impact(Mode& mode, Index i, Scalar t, State& x);
  bool rebound_within_band(const Mode& mode, Index i, Scalar t, const State& x, Scalar v_after);
  void impulse_response(const Mode& mode, const State& x);
  bool land_or_separate(Mode& mode, const std::vector<Index>& candidates, Scalar t, State& x);
  bool separate_unpressed(Mode& mode, Scalar t, State& x);
  // walls.hpp
  void wall_impact(Mode& mode, Index i, int end, Scalar t, State& x);
  void split_wall_reaction(const Mode& mode) const;
  static void rest_guard(WallRest wall, Scalar N, Scalar* g) noexcept;
  static void hold_guard(WallRest wall, Scalar F, Scalar* end_g) noexcept;
  void hold_rows(Index i, const State& x) const;
  void release_pulled_holds(Mode& mode, Scalar t, const State& x);
  bool rest_at_wall(Mode& mode, Index i, ContactState next, State& x);
  void validate_walls(const Mode& mode, const char* where) const;
  static void forget_left_walls(Mode& mode);
  // energy.hpp
  void audit_rates(const Evaluation& e, Scalar t, const State& x, State& dxdt) const;
  void audit_forms(Index P, Index K, LinearPart<Scalar>& lp) const;
  // linear_part.hpp
  void frozen_guard_rows(const Mode& mode, Scalar t, const State& x, LinearPart<Scalar>& lp);
  void allocate_linear_part_workspace();
  void linear_part_by_probes(const Mode& mode, bool exact, bool moving_slip, bool frozen_guards,
                             LinearPart<Scalar>& lp);
  void frozen_probe(const Mode& mode, Index load, Index G);
  bool exact_mode(const Mode& mode) const;
  // jacobian.hpp
  void jacobian_column(const Mode& mode, Scalar t, const State& x, Index j, Matrix& J);
  bool tangent_jacobian(const Mode& mode, Scalar t, const State& x, Matrix& J);
  bool tangent_applies(const Mode& mode) const;
  bool contact_columns(const Mode& mode, Scalar t, const State& x, Matrix& J, bool lu_ready);
  Eigen::PartialPivLU<Matrix>& tangent_lu(Index U);
  Index unknown_row(Index column) const;
  const typename Shapes::Values& jacobian_shapes(Index i, Scalar X);

};

}  // namespace stickslip

// The members, one header per job. Those defined inline are the small ones and those of every
// evaluation, which each translation unit may inline; the others are not implicitly inline, so
// that the compiled mode can declare FrictionDampedSystem<double> extern and instantiate them
// once (docs/compiled.md).
#include "stickslip/model/detail/friction_damped_system/scene.hpp"
#include "stickslip/model/detail/friction_damped_system/layout.hpp"
#include "stickslip/model/detail/friction_damped_system/kinematics.hpp"
#include "stickslip/model/detail/friction_damped_system/solve.hpp"
#include "stickslip/model/detail/friction_damped_system/factorisation.hpp"
#include "stickslip/model/detail/friction_damped_system/guards.hpp"
#include "stickslip/model/detail/friction_damped_system/transitions.hpp"
#include "stickslip/model/detail/friction_damped_system/separation.hpp"
#include "stickslip/model/detail/friction_damped_system/walls.hpp"
#include "stickslip/model/detail/friction_damped_system/energy.hpp"
#include "stickslip/model/detail/friction_damped_system/linear_part.hpp"
#include "stickslip/model/detail/friction_damped_system/jacobian.hpp"

#ifdef STICKSLIP_COMPILED
// The compiled mode: FrictionDampedSystem<double> (dynamic modes, the default law variant) is
// instantiated once, in stickslip::compiled (src/friction_damped_system.cpp).
namespace stickslip {
extern template class FrictionDampedSystem<double>;
}  // namespace stickslip
#endif
