#pragma once
/// \file contact_system.hpp
/// \brief A modal structure with planar rigid bodies, friction contacts of any kind (the contact
/// concept) and point loads, as a hybrid system: the coupled solve, guards and transitions
/// written once over the contacts, never per kind (docs/contacts.md).
///
/// Generalised coordinates z = (q, bodies' (x, y, theta)): mass-normalised modal coordinates q
/// (component 2, damping c_j, loads F_l(t) along rows phi_l) and the bodies' coordinates, with the
/// diagonal mass matrix M = diag(1, ..., 1, m_b, m_b, J_b, ...). Each contact i has a sliding
/// velocity v_i = g_i . z' and, with a body side, a normal velocity v_n,i = h_i . z' (rows that
/// depend on the bodies' rotations):
///   M z'' = r + sum_i (g_i f_i + h_i N_i),
///   r = (-c o q' - omega^2 o q + sum_l phi_l F_l(t), the bodies' spring and load forces).
/// A slipping contact's force is f_i = -mu_k(|v_i|) N_i sgn(v_i) (paper eq. 1; a regularised law's
/// -mu(v_i) N_i in every state): known under a held normal, proportional to the unknown N_i
/// under a unilateral one. The unknowns lambda (the stuck contacts' f_i and the closed unilateral
/// contacts' N_i) keep their velocities' rates at zero: C lambda = -(G M^-1 r + G' z'), with
/// C = G M^-1 B^T (the capacitance form; G holds the constrained rows, B the rows the unknowns
/// act along: h_i + mu_i g_i for a slipping contact's N_i). f_required = lambda drives component
/// 4's stick guards, N_i = 0 a closed contact's lift-off guard, the gap a separated one's landing.
/// A contact whose side b moves along its member (contact_system_moving.hpp) has its rows at the
/// current contact coordinate X (a state, X' = (t . u) v), holds its gap on the row h_i - (t . u)
/// s_i g_i (s_i the member's slope under it) and adds the convective terms of paper eqs 17-19.

#include <stickslip/beam/frame_model.hpp>
#include <stickslip/contact/contact_state.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/modal/modal_basis.hpp>
#include <stickslip/model/contact_concept.hpp>
#include <stickslip/model/damper_states.hpp>
#include <stickslip/model/detail/body_contact_choices.hpp>
#include <stickslip/model/detail/capacitance_factor.hpp>
#include <stickslip/model/detail/contact_linear_workspace.hpp>
#include <stickslip/model/detail/contact_machine.hpp>
#include <stickslip/model/detail/moving_contact.hpp>
#include <stickslip/model/any_contact.hpp>
#include <stickslip/model/body_contact.hpp>
#include <stickslip/model/point_contact.hpp>
#include <stickslip/model/point_load.hpp>
#include <stickslip/model/rigid_body.hpp>
#include <stickslip/model/wedge_damper.hpp>
#include <stickslip/moving_load/member_shapes.hpp>
#include <stickslip/ode/hybrid_system.hpp>
#include <stickslip/ode/linear_part.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace stickslip {

/// Options of a ContactSystem.
template <class Scalar>
struct ContactSystemOptions {
  /// Carry the energy audit's integrals (external work, viscous and friction dissipation) as
  /// three extra states; energy_balance() then closes to the integration error.
  bool energy_audit = true;
  /// |v| at or below this counts as v = 0 where a contact's state is decided (CoulombContact).
  Scalar velocity_tolerance = CoulombContact<CoulombLaw<Scalar>>::default_velocity_tolerance();
  /// A landing whose rebound would rise less than this lands plastically (e = 0; docs/contacts.md,
  /// "Impacts"): with the pressing acceleration a = -g'' of the open contact at the impact, an
  /// impact at normal velocity v_n < 0 bounces only when (e v_n)^2 / (2 a) > landing_height [m].
  /// Negative (the default): 1e-8 of the frame's size (the diagonal of its nodes' bounding box;
  /// 1e-9 m for a frame of one point). 0: every impact with e |v_n| above the velocity tolerance
  /// bounces.
  Scalar landing_height = Scalar(-1);
};

/// Structure (a frame's retained modes) + planar rigid bodies + contacts + point loads, as a
/// HybridSystem (docs/ode.md) for simulate(), the steady states and the sweeps. `Contact` is any
/// type of the contact concept (contact_concept.hpp): PointContact by default, BodyContact for
/// contacts of rigid-body points with unilateral normals, AnyContact for a scene with both.
///
/// Thread safety: a ContactSystem holds the workspace of its solve; one object serves one run
/// at a time. Copy it for concurrent runs (copies share nothing).
template <class Scalar_, class Contact_ = PointContact<Scalar_>>
class ContactSystem {
  static_assert(is_contact_v<Contact_>,
                "ContactSystem<Scalar, Contact>: Contact needs `using Scalar`, `using Law`, "
                "tangential_row(frame, basis, where), law(), normal_force(t), start_state() and "
                "validate(where); see stickslip/model/contact_concept.hpp");

 public:
  using Scalar = Scalar_;                                     ///< floating-point type
  using Contact = Contact_;                                   ///< the contacts' type
  using Law = typename Contact::Law;                          ///< their friction law type
  using Index = Eigen::Index;                                 ///< index type
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;    ///< dynamic vector
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;  ///< dynamic matrix
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;                ///< in-plane vector
  using State = Vector;                                       ///< [z, z', audit integrals], z = (q, bodies)
  using Mode = DamperStates;                                  ///< one ContactState per contact
  using GuardVector = Vector;                                 ///< guard values
  using Load = PointLoad<Scalar>;                             ///< external point load
  using Body = RigidBody<Scalar>;                             ///< planar rigid body
  using Options = ContactSystemOptions<Scalar>;               ///< options
  /// True when the contacts may have a rigid-body side and a unilateral normal (has_body_side_v;
  /// per contact, detail::body_side_of).
  static constexpr bool body_contacts = has_body_side_v<Contact>;

  /// One contact switch, logged by transition() and make_consistent().
  struct ContactEvent {
    Scalar t;            ///< time of the switch
    Index contact;       ///< which contact switched
    ContactState from;   ///< its state before
    ContactState to;     ///< its state after
  };

  /// Forces and kinematics of the contacts at one (mode, t, x).
  struct Evaluation {
    Vector qdd;   ///< z'' (q'' then each body's x'', y'', theta'')
    Vector f;     ///< friction force on side a of each contact along its direction [N]
    Vector v;     ///< sliding velocity of side a over side b [m/s]
    Vector N;     ///< normal force [N] (0 for an open unilateral contact)
    /// Normal velocity of side a over side b's material point (0 under a held normal) [m/s];
    /// under a moving side b the gap's rate is vn - s X' (s the member's slope there).
    Vector vn;
    Vector gap;   ///< gap of a unilateral contact (0 under a held normal) [m]
    Vector X;     ///< contact coordinate of a side b that moves along its member (0 otherwise) [m]
    bool finite = true;  ///< false when the solve failed (dependent constraint rows) or x is not finite
  };

  /// The energy audit at one state: (E - E0) - (W_ext - D_visc - D_fric) = residual.
  struct EnergyBalance {
    Scalar mechanical;            ///< E: kinetic and elastic energy of modes, bodies, body springs [J]
    Scalar external_work;         ///< W_ext = int (sum_l F_l phi_l . q' + body loads' power) dt [J]
    Scalar viscous_dissipation;   ///< D_visc = int (sum_j c_j q_j'^2 + dashpots' c delta'^2) dt [J]
    /// D_fric = -int sum_i (f_i v_i + N_i v_n,i) dt, plus the kinetic energy removed by stuck
    /// projections and impacts [J].
    Scalar friction_dissipation;
    Scalar residual;              ///< (E - E0) - (W_ext - D_visc - D_fric) [J]
    Scalar scale;                 ///< largest magnitude of the terms, for a relative residual [J]
    /// |residual| / scale (0 when every term is 0).
    Scalar relative_residual() const { return scale > 0 ? std::abs(residual) / scale : Scalar(0); }
  };

  /// Assembles the system: each contact's row from `frame` and `basis` (once), each load's row.
  /// \throws std::invalid_argument naming the contact or load and the parameter: a basis of
  ///         another frame, more than DamperStates::max_dampers contacts, a contact whose row is
  ///         zero (its sides do not move apart in the retained modes, so it can never slip), a
  ///         contact's own checks (validate), a load's (PointLoad::validate) or one off its member.
  ContactSystem(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis, std::vector<Contact> contacts,
                std::vector<Load> loads = {}, Options options = {})
      : ContactSystem(frame, basis, std::vector<Body>{}, std::move(contacts), std::move(loads), options) {}

  /// As above, with planar rigid bodies (their coordinates follow the modal coordinates in z).
  /// \throws std::invalid_argument as above, and naming the body and the parameter for a body's
  ///         own checks (RigidBody::validate) or a contact whose a.body names no body.
  ContactSystem(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis, std::vector<Body> bodies,
                std::vector<Contact> contacts, std::vector<Load> loads = {}, Options options = {});

  Index num_modes() const noexcept { return n_; }                                  ///< n
  Index num_bodies() const noexcept { return B_; }                                 ///< rigid bodies
  Index num_coordinates() const noexcept { return m_; }                            ///< n + 3 bodies
  Index num_contacts() const noexcept { return D_; }                               ///< D
  /// 2(n + 3B) (+ 3 audit integrals) + one contact coordinate per moving side b.
  Index state_size() const noexcept { return contact_offset() + num_moving(); }
  Index audit_offset() const noexcept { return 2 * m_; }  ///< first audit integral (W_ext, D_visc, D_fric)
  /// Contacts whose side b moves along its member (BodyContact::contact_point = Moving).
  Index num_moving() const noexcept { return static_cast<Index>(moving_.size()); }
  /// Index in the state of the first moving contact's coordinate X (after the audit integrals;
  /// the others follow in the contacts' order).
  Index contact_offset() const noexcept { return 2 * m_ + (options_.energy_audit ? 3 : 0); }
  /// Index of body b's x in z (y, theta follow; its velocities at num_coordinates() later).
  Index body_offset(Index b) const noexcept { return n_ + 3 * b; }
  const std::vector<Contact>& contacts() const noexcept { return contacts_; }     ///< the contacts
  const std::vector<Body>& bodies() const noexcept { return bodies_; }             ///< the bodies
  const std::vector<Load>& loads() const noexcept { return loads_; }               ///< the loads
  const Options& options() const noexcept { return options_; }                     ///< the options
  /// Structure part w_i of contact i's sliding-velocity row (the whole row without bodies:
  /// s_i = w_i . q).
  auto contact_row(Index i) const { return W_.row(i).transpose(); }

  /// Rest: z = z' = 0, audit integrals 0, each moving contact at its X0.
  State initial_state() const;
  /// Each contact's start_state().
  Mode requested_mode() const;

  /// \throws std::invalid_argument naming `where` for a state of the wrong size, a mode of the
  ///         wrong size or with a state that is not an enumerator / not allowed by the contact's
  ///         normal (Separated only under a unilateral normal).
  void validate_state(const Mode& mode, const State& x, const char* where = "ContactSystem") const;

  /// validate_state, and t0 and every x0[k] finite (simulate() calls it before the first
  /// evaluation). \throws std::invalid_argument naming `where` and the entry.
  void validate_start(const Mode& mode, Scalar t0, const State& x0, const char* where = "ContactSystem") const {
    validate_state(mode, x0, where);
    detail::require_finite(where, "t0", t0);
    for (Index k = 0; k < x0.size(); ++k)
      if (!std::isfinite(x0[k])) detail::throw_invalid(where, "x0[" + std::to_string(k) + "] must be finite, got", x0[k]);
  }

  /// Makes (mode, x) consistent at t: a contact with |v| above the velocity tolerance slides in
  /// sgn(v), one at rest is tried stuck; a closed unilateral contact whose normal force is
  /// negative opens (the most tensile first), a stuck contact whose force exceeds mu_s N slips
  /// (the worst first), until the set is consistent; then the constrained velocities (stuck
  /// sliding velocities, closed normal velocities) are projected to zero (the kinetic energy
  /// removed is booked as friction dissipation). Logs the switches. Returns false when no
  /// consistent set of states was found.
  bool make_consistent(Mode& mode, Scalar t, State& x);

  /// dx/dt = (z', z'', audit powers).
  void rhs(const Mode& mode, Scalar t, const State& x, State& dxdt);
  /// Guards of every contact in order (component 4: stick 2, slip 1, regularised 0; a closed
  /// unilateral contact adds its normal force; an open one has its gap), then X and L - X of
  /// each moving side b (a member end stops the run).
  Index num_guards(const Mode& mode) const;
  /// Guard values (CoulombContact::guards / gap_guard of each contact).
  void guards(const Mode& mode, Scalar t, const State& x, GuardVector& g);
  /// Crossing direction of guard idx (CoulombContact::guard_direction).
  CrossingDirection guard_direction(const Mode& mode, Index idx) const;
  /// The contacts whose guards fired switch by component 4's rules (a closed contact whose
  /// normal force reached zero opens; an open one whose gap reached zero lands with an impact of
  /// restitution e); the whole set is then made consistent (make_consistent). Stops the run
  /// when no consistent state exists.
  TransitionAction transition(Mode& mode, const TriggeredGuards& which, Scalar t, State& x);

  /// Forces and kinematics at (mode, t, x); the reference stays valid until the next call of
  /// any non-const member. Reading it does not change later results.
  const Evaluation& evaluate(const Mode& mode, Scalar t, const State& x);

  /// E = q'.q'/2 + sum omega_j^2 q_j^2 / 2 + sum_b (m |V|^2 + J omega^2) / 2 + sum_springs k delta^2 / 2.
  Scalar mechanical_energy(const State& x) const;
  /// The energy audit; \throws std::invalid_argument when the audit is off.
  EnergyBalance energy_balance(const State& x, Scalar E0) const;

  /// Roots of s^2 + c_j s + omega_j^2 of every mode, and of m s^2 + c s + k of each body's
  /// springs along x and y (simulate()'s RK4 stability check).
  std::vector<std::complex<Scalar>> linear_rates() const;

  /// The linear part of `mode` for the exponential method (stickslip/ode/linear_part.hpp):
  /// x_L = (z, z') (the audit integrals are quadratures), A_m = [0 I; Q K, Q D] with K, D the
  /// stiffness and damping of the known forces and Q = M^-1 (I + B^T L) the map of the coupled
  /// solve (L = -C^-1 G M^-1: the unknowns' response), b_m the loads and the slipping
  /// contacts' friction forces through Q. Exact (exact_mode) with affine guards where every
  /// contact is stuck or slipping under Coulomb friction at a PointContact with a constant
  /// normal force, without bodies and time-function loads; elsewhere the rows, rotations and
  /// friction forces are frozen at (t, x) and b0 is corrected so that the remainder vanishes at
  /// x. Returns false when the solve at (t, x) fails. Allocates nothing once `lp` has its sizes
  /// for the mode. \throws std::invalid_argument for a state or mode of the wrong size.
  bool linear_part(const Mode& mode, Scalar t, const State& x, LinearPart<Scalar>& lp);
  /// True when linear_part is exact in `mode` (see linear_part).
  bool exact_mode(const Mode& mode) const;

  /// The switches logged since construction or clear_events().
  const std::vector<ContactEvent>& events() const noexcept { return events_; }
  /// Forgets the logged switches.
  void clear_events() { events_.clear(); }
  /// The landing height in use (options().landing_height, or its default for this frame) [m].
  Scalar landing_height() const noexcept { return landing_height_; }
  /// Impacts since construction at which no stick / slip case satisfied Newton's and Coulomb's
  /// laws together and the landing contacts took frictionless impulses (docs/contacts.md, "Impacts").
  Index frictionless_impacts() const noexcept { return frictionless_impacts_; }

 private:
  using Machine = detail::contact_machine_t<Law>;

  void solve(const Mode& mode, Scalar t, const State& x) const;
  bool constrained_solve() const;
  void gather_constrained() const;
  template <class Block>
  void capacitance(Block&& C) const;
  /// Side a's body of contact k % D (-1 on the structure): the entries where the rows of an
  /// unknown of contact k can be nonzero.
  Index body_of_unknown(Index k) const { return body_of_[static_cast<std::size_t>(k % D_)]; }
  /// C of the last solve() in the top-left corner of C_, padded to 2D x 2D with a scaled
  /// identity; rows_, cols_ and rate_ gathered (linear_part).
  const Matrix& padded_capacitance() const;
  void body_forces(Scalar t, const State& x) const;
  void contact_kinematics(const State& x) const;
  bool has_stick_state(Index i) const {
    return detail::with_law(machines_[static_cast<std::size_t>(i)],
                                [](const auto& m) { return std::decay_t<decltype(m)>::has_stick_state; });
  }
  bool unilateral(Index i) const { return unilateral_[static_cast<std::size_t>(i)] != 0; }
  Index guards_of(const Mode& mode, Index i) const {
    return detail::with_law(machines_[static_cast<std::size_t>(i)],
                                [&](const auto& m) { return m.num_guards(mode[i], unilateral(i)); });
  }
  void assemble_body_side(Index i, const Contact& c, const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                          const std::string& name);
  void assemble_moving_side(Index i, const Contact& c, const FrameModel<Scalar>& frame,
                            const ModalBasis<Scalar>& basis, const std::string& name);
  void moving_rows(const State& x) const;
  void moving_rates(const State& x) const;
  Index contact_guards(const Mode& mode) const;
  /// The row of contact i's gap rate: the normal row, less the slope's share of the sliding row
  /// under a moving side b.
  auto gap_rate_row(Index i) const { return moving_of_[static_cast<std::size_t>(i)] >= 0 ? Hc_.row(i) : H_.row(i); }
  bool resolve(Mode& mode, Scalar t, State& x);
  bool resolve_greedy(Mode& mode, Scalar t, State& x, bool may_open);
  bool separating(const Mode& entry, const Mode& mode) const;
  bool impulse(const Mode& mode, Scalar t, State& x);
  bool impact(const Mode& mode, Scalar t, State& x);
  Scalar impulse_friction(Index i) const;
  void init_impulse(const FrameModel<Scalar>& frame);
  void landing_restitution(Index i, const State& x);
  void spring_extension(const State& x, Index b, const BodySpring<Scalar>& spring, Scalar& delta, Scalar& rate,
                        Eigen::Matrix<Scalar, 3, 1>& row) const;
  /// As above, with turn = (cos theta, sin theta) of body b (detail::turn_of).
  void spring_extension(const State& x, Index b, const Vector2& turn, const BodySpring<Scalar>& spring, Scalar& delta,
                        Scalar& rate, Eigen::Matrix<Scalar, 3, 1>& row) const;
  /// target += s row^T over the entries where a contact's row can be nonzero: the modes and side
  /// a's body `body` (none when -1). The other entries of the row must be zero.
  template <class Row, class Target>
  void add_row(const Row& row, Index body, Scalar s, Target&& target) const;
  /// row . z over the same entries (z: z', z'' or any m-vector).
  template <class Row, class Z>
  Scalar row_dot(const Row& row, Index body, const Z& z) const;
  static Vector load_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis, const Load& load,
                         Index l);

  std::vector<Body> bodies_;
  std::vector<Contact> contacts_;
  std::vector<Load> loads_;
  Options options_;
  Index n_ = 0, B_ = 0, m_ = 0, D_ = 0;
  Vector omega2_, damping_;
  Vector minv_;   // m: the inverse of the diagonal mass matrix
  Matrix W_;      // D x n: structure part of the sliding-velocity rows
  Matrix Wn_;     // D x n: structure part of the normal-velocity rows (zero under a held normal)
  Matrix Phi_;    // n x L: load rows
  std::vector<char> unilateral_;           // contact i has a unilateral normal
  std::vector<char> stop_at_lift_off_;     // contact i stops the run where its N reaches zero
  std::vector<char> extends_;              // 2 per moving side b: continues past X = 0, X = L
  Index lifted_ = -1;                      // the contact whose lift-off stopped resolve()
  std::vector<Index> body_of_;             // body of side a, -1 when side a is on the structure
  std::vector<Vector2> point_, tdir_, ndir_;
  Vector restitution_, gap0_;
  std::vector<Machine> machines_;
  mutable std::vector<detail::MovingSide<Scalar>> moving_;  // contacts whose side b moves
  std::vector<Index> moving_of_;           // slot in moving_ of contact i, -1 when side b is fixed
  std::vector<ContactEvent> events_;
  std::vector<char> landing_;              // contacts landing at this transition

  // The impact (contact_impulse.hpp): per contact, sized at construction.
  static constexpr signed char impact_frictionless = 0, impact_stick = 1, impact_slip = 2;
  static constexpr Index max_friction_landings = 6;  // 3^6 cases at most; more land frictionless
  static constexpr Index max_touching = 8;           // contacts of the complementarity enumeration
  std::vector<signed char> impact_choice_;  // a landing contact's case: frictionless, stick or slip
  std::vector<Index> impact_row_;           // row of its normal impulse (its tangential one follows)
  std::vector<Index> impact_list_;          // landing contacts with friction / touching contacts
  Vector impact_e_, impact_mu_, impact_s_;  // restitution in use, mu = -s mu_k of a slip, s
  Vector vt_, zsave_;                       // sliding velocities before, z' before
  Scalar landing_height_ = 0;
  Index frictionless_impacts_ = 0;

  // Workspace of solve(): sized at construction, no allocation in a time step.
  mutable Evaluation e_;
  mutable Vector r_;                      // m: known generalised forces
  using RowMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  // Rows are nonzero only on the modes and on side a's body (add_row, row_dot).
  mutable RowMatrix G_, H_;               // D x m: full sliding / normal velocity rows
  mutable RowMatrix Hc_;                  // D x m: gap-rate rows of moving contacts (gap_rate_row)
  mutable std::vector<Vector2> turn_;     // B: (cos theta, sin theta) of each body at the solve's state
  mutable Vector spring_rate_;            // every body spring's delta' at the solve's state, in order
  mutable Vector gdot_, hdot_;            // D: G' z', H' z' (the rows' rates times z')
  mutable Vector mu_;                     // D: f = mu N of a non-stuck closed unilateral contact
  mutable RowMatrix rows_, cols_;         // 2D x m: constrained rows, directions of the unknowns
  mutable Vector rate_;                   // 2D: rows' rates times z' of the constrained rows
  mutable Matrix C_;                      // 2D x 2D, the constrained block in its top-left corner
  mutable Vector b_, lambda_;
  mutable Eigen::FullPivLU<Matrix> lu_;   // the impulses' padded C_
  std::vector<char> fixed_row_;           // contact i's sliding row is constant (side a on the structure, b fixed)
  /// Factorisations of C for sets of stuck contacts with constant rows, keyed by the set.
  static constexpr Index capacitance_slots = 8;
  mutable detail::CapacitanceCache<Scalar> capacitance_cache_;
  mutable detail::CapacitanceFactor<Scalar> fresh_factor_;  // C of a set with state-dependent rows
  mutable std::vector<Index> unknown_;    // contact of each unknown; + D_ for a normal force
  detail::ContactLinearWorkspace<Scalar> lin_;  // linear_part's matrices (contact_system_linear.hpp)
};

}  // namespace stickslip

#include <stickslip/model/detail/contact_system_impl.hpp>
#include <stickslip/model/detail/contact_system_linear.hpp>

#ifdef STICKSLIP_COMPILED
// The compiled mode (docs/compiled.md): ContactSystem<double, C> of the three contact kinds and
// simulate()'s runs on them are instantiated once, in stickslip::compiled.
#include <stickslip/model/detail/compiled_contact_system.hpp>
#endif
