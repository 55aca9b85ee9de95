#pragma once
/// \file contact_system_impl.hpp
/// \brief Member definitions of ContactSystem (contact_system.hpp): assembly, the state's checks,
/// the right-hand side and the energy audit. The coupled solve is in contact_system_solve.hpp,
/// guards and transitions in contact_system_events.hpp.

#include <stickslip/model/contact_system.hpp>

namespace stickslip {

template <class Scalar_, class Contact_>
ContactSystem<Scalar_, Contact_>::ContactSystem(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                                                std::vector<Body> bodies, std::vector<Contact> contacts,
                                                std::vector<Load> loads, Options options)
    : bodies_(std::move(bodies)), contacts_(std::move(contacts)), loads_(std::move(loads)), options_(options) {
  static const std::string where = "ContactSystem";
  if (basis.model_id() != frame.id())
    detail::throw_invalid(where, "basis must be computed from this frame (model id)", basis.model_id());
  detail::require_non_negative(where, "options.velocity_tolerance", options_.velocity_tolerance);
  n_ = basis.size();
  B_ = static_cast<Index>(bodies_.size());
  m_ = n_ + 3 * B_;
  D_ = static_cast<Index>(contacts_.size());
  if (D_ > DamperStates::max_dampers)
    detail::throw_invalid(where, "at most " + std::to_string(DamperStates::max_dampers) + " contacts", D_);
  omega2_ = basis.omega().array().square();
  damping_ = basis.damping_coefficients();
  minv_.setOnes(m_);
  for (Index b = 0; b < B_; ++b) {
    const Body& body = bodies_[static_cast<std::size_t>(b)];
    body.validate("body " + std::to_string(b));
    minv_[body_offset(b)] = minv_[body_offset(b) + 1] = Scalar(1) / body.mass;
    minv_[body_offset(b) + 2] = Scalar(1) / body.inertia;
  }
  W_.resize(D_, n_);
  Wn_.setZero(D_, n_);
  unilateral_.assign(contacts_.size(), 0);
  stop_at_lift_off_.assign(contacts_.size(), 0);
  body_of_.assign(contacts_.size(), -1);
  point_.assign(contacts_.size(), Vector2::Zero());
  tdir_.assign(contacts_.size(), Vector2::Zero());
  ndir_.assign(contacts_.size(), Vector2::Zero());
  restitution_.setZero(D_);
  gap0_.setZero(D_);
  moving_of_.assign(contacts_.size(), -1);
  machines_.reserve(contacts_.size());
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const Contact& c = contacts_[iu];
    const std::string name = "contact " + std::to_string(i);
    c.validate(name);
    W_.row(i) = c.tangential_row(frame, basis, name).transpose();
    bool moves = W_.row(i).squaredNorm() > 0;
    if constexpr (body_contacts) {
      if (detail::body_side_of(c)) {
        assemble_body_side(i, c, frame, basis, name);
        const detail::BodyContactChoices choices = detail::contact_choices_of(c);
        unilateral_[iu] = !choices.held_normal;
        stop_at_lift_off_[iu] = choices.stop_at_lift_off;
        if (detail::moving_side_of(c)) {
          assemble_moving_side(i, c, frame, basis, name);
          extends_.push_back(choices.extend_start);
          extends_.push_back(choices.extend_finish);
        }
        moves = true;  // the body point's own row [t, t . (k x R r)] is never zero
      }
    }
    if (!moves)
      detail::throw_invalid(name, "its sides do not move apart in the retained modes (zero row); it could never slip",
                            W_.row(i).norm());
    machines_.push_back(detail::make_contact_machine(c.law(), options_.velocity_tolerance));
  }
  Phi_.resize(n_, static_cast<Index>(loads_.size()));
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    loads_[l].validate(static_cast<Index>(l));
    Phi_.col(static_cast<Index>(l)) = load_row(frame, basis, loads_[l], static_cast<Index>(l));
  }
  e_.qdd.setZero(m_);
  e_.f.setZero(D_);
  e_.v.setZero(D_);
  e_.N.setZero(D_);
  e_.vn.setZero(D_);
  e_.gap.setZero(D_);
  e_.X.setZero(D_);
  r_.setZero(m_);
  G_.setZero(D_, m_);
  H_.setZero(D_, m_);
  G_.leftCols(n_) = W_;
  H_.leftCols(n_) = Wn_;
  Hc_ = H_;
  turn_.assign(bodies_.size(), Vector2(Scalar(1), Scalar(0)));
  std::size_t springs = 0;
  for (const Body& body : bodies_) springs += body.springs.size();
  spring_rate_.setZero(static_cast<Index>(springs));
  gdot_.setZero(D_);
  hdot_.setZero(D_);
  mu_.setZero(D_);
  rows_.setZero(2 * D_, m_);
  cols_.setZero(2 * D_, m_);
  rate_.setZero(2 * D_);
  C_.setIdentity(2 * D_, 2 * D_);
  b_.setZero(2 * D_);
  lambda_.setZero(2 * D_);
  lu_ = Eigen::FullPivLU<Matrix>(2 * D_, 2 * D_);
  fixed_row_.assign(contacts_.size(), 0);
  for (std::size_t i = 0; i < contacts_.size(); ++i)
    fixed_row_[i] = static_cast<char>(body_of_[i] < 0 && moving_of_[i] < 0);
  capacitance_cache_ = detail::CapacitanceCache<Scalar>(capacitance_slots, D_);
  fresh_factor_ = detail::CapacitanceFactor<Scalar>(2 * D_);
  unknown_.reserve(2 * contacts_.size());
  landing_.assign(contacts_.size(), 0);
  init_impulse(frame);
  events_.reserve(64);
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::assemble_body_side(Index i, const Contact& c, const FrameModel<Scalar>& frame,
                                                          const ModalBasis<Scalar>& basis, const std::string& name) {
  const std::size_t iu = static_cast<std::size_t>(i);
  const BodyPoint<Scalar> side_a = c.body_point();
  if (side_a.body < 0 || side_a.body >= B_)
    detail::throw_invalid(name, "a.body must name a body of the scene (" + std::to_string(B_) + " bodies)",
                          side_a.body);
  const PlaneDirection<Scalar> t = c.tangent_direction(), n = c.normal_direction();
  t.validate(name, "tangent");
  n.validate(name, "normal");
  if (!(std::abs(t.x * n.x + t.y * n.y) <= Scalar(1e-9)))
    detail::throw_invalid(name, "tangent must be perpendicular to the normal, t . n =", t.x * n.x + t.y * n.y);
  const Scalar e = c.restitution_coefficient();
  if (!(e >= Scalar(0) && e <= Scalar(1))) detail::throw_invalid(name, "restitution must lie in [0, 1]", e);
  detail::require_non_negative(name, "initial_gap", c.gap_at_reference());
  Wn_.row(i) = c.normal_row(frame, basis, name).transpose();
  unilateral_[iu] = 1;
  body_of_[iu] = side_a.body;
  point_[iu] = side_a.point;
  tdir_[iu] = Vector2(t.x, t.y);
  ndir_[iu] = Vector2(n.x, n.y);
  restitution_[i] = e;
  gap0_[i] = c.gap_at_reference();
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::load_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                                                const Load& load, Index l) -> Vector {
  const std::string where = "PointLoad[" + std::to_string(l) + "]";
  const MemberShapes<Scalar> shapes = shapes_at_point(frame, basis, StructurePoint<Scalar>{load.member, load.coordinate}, where);
  return load_direction_row(shapes.evaluate(load.coordinate), shapes.cos(), shapes.sin(), load.direction);
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
    if (s == ContactState::Stick || s == ContactState::SlipPositive || s == ContactState::SlipNegative) continue;
    if (s == ContactState::Separated && unilateral(i)) continue;
    detail::throw_invalid(where, "mode[" + std::to_string(i) + "] must be Stick, SlipPositive or SlipNegative" +
                                     (unilateral(i) ? " or Separated" : " under a held normal") + ", got",
                          static_cast<int>(s));
  }
  for (Index p = 0; p < num_moving(); ++p) {
    const auto& side = moving_[static_cast<std::size_t>(p)];
    const Scalar X = x[contact_offset() + p];
    const bool beyond = (X < Scalar(0) && !extends_[static_cast<std::size_t>(2 * p)]) ||
                        (X > side.shapes.length() && !extends_[static_cast<std::size_t>(2 * p + 1)]);
    if (beyond || !std::isfinite(X))
      detail::throw_invalid(where, "x[" + std::to_string(contact_offset() + p) + "], the contact coordinate X of contact " +
                                       std::to_string(side.contact) + ", must lie on member " +
                                       std::to_string(side.shapes.member()) + " ([0, " +
                                       detail::format_value(side.shapes.length()) + "]), got",
                            X);
  }
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::spring_extension(const State& x, Index b, const BodySpring<Scalar>& spring,
                                                        Scalar& delta, Scalar& rate,
                                                        Eigen::Matrix<Scalar, 3, 1>& row) const {
  spring_extension(x, b, detail::turn_of(x[body_offset(b) + 2]), spring, delta, rate, row);
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::spring_extension(const State& x, Index b, const Vector2& turn,
                                                        const BodySpring<Scalar>& spring, Scalar& delta, Scalar& rate,
                                                        Eigen::Matrix<Scalar, 3, 1>& row) const {
  const Index o = body_offset(b);
  const Vector2 d(spring.direction.x, spring.direction.y);
  const Vector2 Rr = detail::rotated(turn, spring.point);
  row = detail::body_point_row(d, Rr);
  delta = d.x() * x[o] + d.y() * x[o + 1] + d.dot(Rr - spring.point);
  rate = row.dot(x.template segment<3>(m_ + o));
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
  dxdt.head(m_) = x.segment(m_, m_);
  dxdt.segment(m_, m_) = e_.qdd;
  for (Index p = 0; p < num_moving(); ++p) {  // X' = (t . u) v
    const auto& side = moving_[static_cast<std::size_t>(p)];
    dxdt[contact_offset() + p] = side.sigma_t * e_.v[side.contact];
  }
  if (options_.energy_audit) {
    const auto qd = x.segment(m_, n_);
    Scalar external = 0, viscous = damping_.dot(qd.cwiseAbs2());
    for (std::size_t l = 0; l < loads_.size(); ++l)
      external += loads_[l].value(t) * Phi_.col(static_cast<Index>(l)).dot(qd);
    Index k = 0;  // the springs' rates at x, from solve()
    for (Index b = 0; b < B_; ++b) {
      const Body& body = bodies_[static_cast<std::size_t>(b)];
      const Index o = m_ + body_offset(b);
      for (const auto& load : body.loads) external += load(t) * (load.direction.x * x[o] + load.direction.y * x[o + 1]);
      for (const auto& spring : body.springs) {
        const Scalar rate = spring_rate_[k++];
        viscous += spring.damping * rate * rate;
      }
    }
    dxdt[audit_offset()] = external;
    dxdt[audit_offset() + 1] = viscous;
    dxdt[audit_offset() + 2] = -(e_.f.dot(e_.v) + e_.N.dot(e_.vn));
  }
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::mechanical_energy(const State& x) const -> Scalar {
  const auto q = x.head(n_), qd = x.segment(m_, n_);
  Scalar E = Scalar(0.5) * (qd.squaredNorm() + omega2_.dot(q.cwiseAbs2()));
  for (Index b = 0; b < B_; ++b) {
    const Body& body = bodies_[static_cast<std::size_t>(b)];
    const auto V = x.template segment<3>(m_ + body_offset(b));
    E += Scalar(0.5) * (body.mass * V.template head<2>().squaredNorm() + body.inertia * V[2] * V[2]);
    for (const auto& spring : body.springs) {
      Scalar delta, rate;
      Eigen::Matrix<Scalar, 3, 1> row;
      spring_extension(x, b, spring, delta, rate, row);
      E += Scalar(0.5) * spring.stiffness * delta * delta;
    }
  }
  return E;
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
  rates.reserve(static_cast<std::size_t>(2 * n_ + 4 * B_));
  auto add = [&](Scalar mass, Scalar c, Scalar k) {
    const std::complex<Scalar> half(-c / (2 * mass), 0);
    const std::complex<Scalar> root = std::sqrt(std::complex<Scalar>(c * c / (4 * mass * mass) - k / mass, 0));
    rates.push_back(half + root);
    rates.push_back(half - root);
  };
  for (Index j = 0; j < n_; ++j) add(Scalar(1), damping_[j], omega2_[j]);
  for (const Body& body : bodies_) {  // every spring's stiffness on translation and on rotation
    Scalar k = 0, c = 0, kr = 0, cr = 0;
    for (const auto& s : body.springs) {
      k += s.stiffness;
      c += s.damping;
      kr += s.stiffness * s.point.squaredNorm();
      cr += s.damping * s.point.squaredNorm();
    }
    add(body.mass, c, k);
    add(body.inertia, cr, kr);
  }
  return rates;
}

}  // namespace stickslip

#include <stickslip/model/detail/contact_system_events.hpp>
#include <stickslip/model/detail/contact_system_moving.hpp>
#include <stickslip/model/detail/contact_system_solve.hpp>
#include <stickslip/model/detail/contact_impulse.hpp>
