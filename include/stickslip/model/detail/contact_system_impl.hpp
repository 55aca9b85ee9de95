#pragma once
/// \file contact_system_impl.hpp
/// \brief Member definitions of ContactSystem (contact_system.hpp): assembly, the coupled solve,
/// guards, transitions and the energy audit.

#include <stickslip/model/contact_system.hpp>

namespace stickslip {

template <class Scalar_, class Contact_>
ContactSystem<Scalar_, Contact_>::ContactSystem(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                                                std::vector<Contact> contacts, std::vector<Load> loads,
                                                Options options)
    : contacts_(std::move(contacts)), loads_(std::move(loads)), options_(options) {
  static const std::string where = "ContactSystem";
  if (basis.model_id() != frame.id())
    detail::throw_invalid(where, "basis must be computed from this frame (model id)", basis.model_id());
  detail::require_non_negative(where, "options.velocity_tolerance", options_.velocity_tolerance);
  n_ = basis.size();
  D_ = static_cast<Index>(contacts_.size());
  if (D_ > DamperStates::max_dampers)
    detail::throw_invalid(where, "at most " + std::to_string(DamperStates::max_dampers) + " contacts, got", D_);
  omega2_ = basis.omega().array().square();
  damping_ = basis.damping_coefficients();
  W_.resize(D_, n_);
  machines_.reserve(contacts_.size());
  for (Index i = 0; i < D_; ++i) {
    const Contact& c = contacts_[static_cast<std::size_t>(i)];
    const std::string name = "contact " + std::to_string(i);
    c.validate(name);
    W_.row(i) = c.tangential_row(frame, basis, name).transpose();
    if (!(W_.row(i).squaredNorm() > 0))
      detail::throw_invalid(name, "its sides do not move apart in the retained modes (zero row); it could never slip",
                            W_.row(i).norm());
    machines_.push_back(detail::make_contact_machine(c.law(), options_.velocity_tolerance));
  }
  Phi_.resize(n_, static_cast<Index>(loads_.size()));
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    loads_[l].validate(static_cast<Index>(l));
    Phi_.col(static_cast<Index>(l)) = load_row(frame, basis, loads_[l], static_cast<Index>(l));
  }
  e_.qdd.setZero(n_);
  e_.f.setZero(D_);
  e_.v.setZero(D_);
  e_.N.setZero(D_);
  r_.setZero(n_);
  C_.setIdentity(D_, D_);
  b_.setZero(D_);
  lambda_.setZero(D_);
  lu_ = Eigen::FullPivLU<Matrix>(D_, D_);
  stuck_.reserve(contacts_.size());
  events_.reserve(64);
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::load_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                                                const Load& load, Index l) -> Vector {
  const std::string where = "PointLoad[" + std::to_string(l) + "]";
  const MemberShapes<Scalar> shapes = shapes_at_point(frame, basis, StructurePoint<Scalar>{load.member, load.coordinate}, where);
  return load_direction_row(shapes.evaluate(load.coordinate), shapes.cos(), shapes.sin(), load.direction);
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::requested_mode() const -> Mode {
  Mode mode(D_);
  for (Index i = 0; i < D_; ++i) mode[i] = contacts_[static_cast<std::size_t>(i)].start_state();
  return mode;
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::validate_state(const Mode& mode, const State& x, const char* where) const {
  if (x.size() != state_size())
    detail::throw_invalid(where, "x must have state_size() = " + std::to_string(state_size()) + " entries, got",
                          x.size());
  if (mode.size() != D_)
    detail::throw_invalid(where, "mode must have one state per contact (" + std::to_string(D_) + "), got",
                          mode.size());
  for (Index i = 0; i < D_; ++i) {
    const ContactState s = mode[i];
    if (s != ContactState::Stick && s != ContactState::SlipPositive && s != ContactState::SlipNegative)
      detail::throw_invalid(where, "mode[" + std::to_string(i) + "] must be Stick, SlipPositive or SlipNegative, got",
                            static_cast<int>(s));
  }
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::solve(const Mode& mode, Scalar t, const State& x) const {
  using std::isfinite;
  const auto q = x.head(n_), qd = x.segment(n_, n_);
  Evaluation& e = e_;
  e.finite = true;
  r_ = -damping_.cwiseProduct(qd) - omega2_.cwiseProduct(q);
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    const Scalar F = loads_[l].value(t);
    r_ += F * Phi_.col(static_cast<Index>(l));
  }
  stuck_.clear();
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    e.N[i] = contacts_[iu].normal_force(t);
    e.v[i] = W_.row(i).dot(qd);
    if (mode[i] == ContactState::Stick && has_stick_state(i)) {
      stuck_.push_back(i);
      continue;
    }
    e.f[i] = detail::with_law(machines_[iu], [&](const auto& m) {
      return m.friction_force(mode[i], e.v[i], e.N[i], Scalar(0));
    });
    r_ += e.f[i] * W_.row(i).transpose();
  }
  e.qdd = r_;
  const Index U = static_cast<Index>(stuck_.size());
  if (U > 0) {
    // (W_S W_S^T) lambda = -W_S r in the top-left U x U block of C (identity elsewhere).
    C_.setIdentity();
    b_.setZero();
    for (Index a = 0; a < U; ++a) {
      const Index ia = stuck_[static_cast<std::size_t>(a)];
      b_[a] = -W_.row(ia).dot(r_);
      for (Index c = 0; c <= a; ++c)
        C_(a, c) = C_(c, a) = W_.row(ia).dot(W_.row(stuck_[static_cast<std::size_t>(c)]));
    }
    lu_.compute(C_);
    if (lu_.rank() < D_) {  // dependent stuck rows: the solve cannot split their forces
      e.finite = false;
      e.qdd.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
      return;
    }
    lambda_ = lu_.solve(b_);
    for (Index a = 0; a < U; ++a) {
      const Index ia = stuck_[static_cast<std::size_t>(a)];
      e.f[ia] = lambda_[a];
      e.qdd += lambda_[a] * W_.row(ia).transpose();
    }
  }
  if (!(isfinite(e.qdd.sum()) && isfinite(e.f.sum()) && isfinite(e.N.sum()))) e.finite = false;
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::evaluate(const Mode& mode, Scalar t, const State& x) -> const Evaluation& {
  solve(mode, t, x);
  return e_;
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::rhs(const Mode& mode, Scalar t, const State& x, State& dxdt) {
  solve(mode, t, x);
  dxdt.resize(state_size());
  const auto qd = x.segment(n_, n_);
  dxdt.head(n_) = qd;
  dxdt.segment(n_, n_) = e_.qdd;
  if (options_.energy_audit) {
    Scalar external = 0;
    for (std::size_t l = 0; l < loads_.size(); ++l)
      external += loads_[l].value(t) * Phi_.col(static_cast<Index>(l)).dot(qd);
    dxdt[audit_offset()] = external;
    dxdt[audit_offset() + 1] = damping_.dot(qd.cwiseAbs2());
    dxdt[audit_offset() + 2] = -e_.f.dot(e_.v);
  }
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::num_guards(const Mode& mode) const -> Index {
  Index k = 0;
  for (Index i = 0; i < D_; ++i) k += guards_of(mode, i);
  return k;
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::guards(const Mode& mode, Scalar t, const State& x, GuardVector& g) {
  solve(mode, t, x);
  g.resize(num_guards(mode));
  Index k = 0;
  for (Index i = 0; i < D_; ++i) {
    detail::with_law(machines_[static_cast<std::size_t>(i)], [&](const auto& m) {
      m.guards(mode[i], e_.v[i], e_.N[i], e_.f[i], false, g.data() + k);
    });
    k += guards_of(mode, i);
  }
}

template <class Scalar_, class Contact_>
CrossingDirection ContactSystem<Scalar_, Contact_>::guard_direction(const Mode& mode, Index idx) const {
  for (Index i = 0; i < D_; ++i) {
    const Index gi = guards_of(mode, i);
    if (idx < gi)
      return detail::with_law(machines_[static_cast<std::size_t>(i)],
                                  [&](const auto& m) { return m.guard_direction(mode[i], idx, false); });
    idx -= gi;
  }
  STICKSLIP_ASSERT(false && "ContactSystem::guard_direction: index beyond num_guards");
  return CrossingDirection::Either;
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::resolve(Mode& mode, Scalar t, State& x) {
  // Release the stuck contact whose required force exceeds its capacity most, one at a time,
  // until every stuck force lies within mu_s N (the stuck set of a consistent acceleration).
  for (Index iter = 0; iter <= 4 * D_ + 4; ++iter) {
    solve(mode, t, x);
    if (!e_.finite) return false;
    Index worst = -1;
    Scalar worst_excess = 0;
    for (Index i = 0; i < D_; ++i) {
      if (mode[i] != ContactState::Stick || !has_stick_state(i)) continue;
      const Scalar excess = detail::with_law(machines_[static_cast<std::size_t>(i)], [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (M::has_stick_state)
          return std::abs(e_.f[i]) - m.stick_capacity(e_.N[i]);
        else
          return Scalar(0);
      });
      if (excess > worst_excess) {
        worst_excess = excess;
        worst = i;
      }
    }
    if (worst < 0) return true;
    mode[worst] = detail::with_law(machines_[static_cast<std::size_t>(worst)],
                                       [&](const auto& m) { return m.decide_at_rest(e_.N[worst], e_.f[worst]); });
  }
  return false;
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::project_stuck_velocities(const Mode& mode, Scalar t, State& x) {
  // q' <- q' - W_S^T (W_S W_S^T)^{-1} W_S q': the nearest velocity (in kinetic energy) with
  // v_S = 0; the kinetic energy it removes is booked as friction dissipation.
  solve(mode, t, x);  // fills stuck_ and the factorisation of W_S W_S^T
  const Index U = static_cast<Index>(stuck_.size());
  if (U == 0 || !e_.finite) return;
  auto qd = x.segment(n_, n_);
  const Scalar before = Scalar(0.5) * qd.squaredNorm();
  b_.setZero();
  for (Index a = 0; a < U; ++a) b_[a] = W_.row(stuck_[static_cast<std::size_t>(a)]).dot(qd);
  lambda_ = lu_.solve(b_);
  for (Index a = 0; a < U; ++a) qd -= lambda_[a] * W_.row(stuck_[static_cast<std::size_t>(a)]).transpose();
  if (options_.energy_audit) x[audit_offset() + 2] += before - Scalar(0.5) * qd.squaredNorm();
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::make_consistent(Mode& mode, Scalar t, State& x) {
  validate_start(mode, t, x, "ContactSystem::make_consistent");
  const Mode before = mode;
  solve(mode, t, x);
  for (Index i = 0; i < D_; ++i) {  // component 4's rule 2: sliding where |v| > tolerance
    if (!has_stick_state(i)) continue;
    const Scalar v = e_.v[i];
    if (std::abs(v) <= options_.velocity_tolerance) mode[i] = ContactState::Stick;  // decided at rest below
    else mode[i] = v > 0 ? ContactState::SlipPositive : ContactState::SlipNegative;
  }
  const bool consistent = resolve(mode, t, x);
  if (consistent) project_stuck_velocities(mode, t, x);
  for (Index i = 0; i < D_; ++i)
    if (mode[i] != before[i]) events_.push_back({t, i, before[i], mode[i]});
  return consistent;
}

template <class Scalar_, class Contact_>
TransitionAction ContactSystem<Scalar_, Contact_>::transition(Mode& mode, const TriggeredGuards& which, Scalar t,
                                                              State& x) {
  const Mode before = mode;
  solve(mode, t, x);
  for (Index idx : which) {
    Index i = 0, k = idx;
    for (; i < D_ && k >= guards_of(before, i); ++i) k -= guards_of(before, i);
    if (i >= D_) continue;
    // A stick guard: component 4's rule 4 (slip against the required force); a slip state's
    // velocity guard: at rest, tried stuck and decided by resolve() with the whole set.
    if (before[i] == ContactState::Stick)
      mode[i] = detail::with_law(machines_[static_cast<std::size_t>(i)],
                                     [&](const auto& m) { return m.decide_at_rest(e_.N[i], e_.f[i]); });
    else if (is_slipping(before[i]))
      mode[i] = ContactState::Stick;
  }
  const bool consistent = resolve(mode, t, x);
  if (!consistent) {
    mode = before;
    return TransitionAction::halt("no consistent set of contact states at t = " + detail::format_value(t) +
                                  " (dependent stuck contacts, or no stuck set within mu_s N)");
  }
  project_stuck_velocities(mode, t, x);
  for (Index i = 0; i < D_; ++i)
    if (mode[i] != before[i]) events_.push_back({t, i, before[i], mode[i]});
  return TransitionAction::proceed();
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::mechanical_energy(const State& x) const -> Scalar {
  const auto q = x.head(n_), qd = x.segment(n_, n_);
  return Scalar(0.5) * (qd.squaredNorm() + omega2_.dot(q.cwiseAbs2()));
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::energy_balance(const State& x, Scalar E0) const -> EnergyBalance {
  if (!options_.energy_audit)
    detail::throw_invalid("ContactSystem::energy_balance", "needs options.energy_audit = true", 0);
  EnergyBalance b{};
  b.mechanical = mechanical_energy(x);
  b.external_work = x[audit_offset()];
  b.viscous_dissipation = x[audit_offset() + 1];
  b.friction_dissipation = x[audit_offset() + 2];
  b.residual = (b.mechanical - E0) - (b.external_work - b.viscous_dissipation - b.friction_dissipation);
  using std::abs;
  b.scale = std::max({abs(b.mechanical - E0), abs(b.external_work), abs(b.viscous_dissipation),
                      abs(b.friction_dissipation)});
  return b;
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::linear_rates() const -> std::vector<std::complex<Scalar>> {
  std::vector<std::complex<Scalar>> rates;
  rates.reserve(static_cast<std::size_t>(2 * n_));
  for (Index j = 0; j < n_; ++j) {
    const std::complex<Scalar> half(-damping_[j] / 2, 0);
    const std::complex<Scalar> root = std::sqrt(std::complex<Scalar>(damping_[j] * damping_[j] / 4 - omega2_[j], 0));
    rates.push_back(half + root);
    rates.push_back(half - root);
  }
  return rates;
}

}  // namespace stickslip
