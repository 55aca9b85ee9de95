#pragma once
/// \file contact_system_solve.hpp
/// \brief ContactSystem's coupled solve (contact_system.hpp): the known generalised forces, the
/// contacts' rows at the current rotations and the capacitance system of the constrained rows
/// (the impulses are in contact_impulse.hpp).

#include <stickslip/model/contact_system.hpp>

namespace stickslip {

template <class Scalar_, class Contact_>
template <class Row, class Target>
void ContactSystem<Scalar_, Contact_>::add_row(const Row& row, Index body, Scalar s, Target&& target) const {
  target.head(n_) += s * row.head(n_).transpose();
  if (body >= 0) {
    const Index o = body_offset(body);
    target.template segment<3>(o) += s * row.template segment<3>(o).transpose();
  }
}

template <class Scalar_, class Contact_>
template <class Row, class Z>
auto ContactSystem<Scalar_, Contact_>::row_dot(const Row& row, Index body, const Z& z) const -> Scalar {
  Scalar sum = row.head(n_).dot(z.head(n_).transpose());
  if (body >= 0) {
    const Index o = body_offset(body);
    sum += row.template segment<3>(o).dot(z.template segment<3>(o).transpose());
  }
  return sum;
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::body_forces(Scalar t, const State& x) const {
  // Loads at the centre of mass, springs and dashpots at their points: -(k delta + c delta') times
  // the point's row [d, d . (k x R r)] (the generalised force of a force along d at the point).
  // Each body's cos theta, sin theta once, for its springs here and its contacts' rows.
  Index k = 0;
  for (Index b = 0; b < B_; ++b) {
    const Body& body = bodies_[static_cast<std::size_t>(b)];
    const Vector2& turn = turn_[static_cast<std::size_t>(b)] = detail::turn_of(x[body_offset(b) + 2]);
    Eigen::Matrix<Scalar, 3, 1> F = Eigen::Matrix<Scalar, 3, 1>::Zero();
    for (const auto& load : body.loads) {
      const Scalar value = load(t);
      F[0] += value * load.direction.x;
      F[1] += value * load.direction.y;
    }
    for (const auto& spring : body.springs) {
      Scalar delta, rate;
      Eigen::Matrix<Scalar, 3, 1> row;
      spring_extension(x, b, turn, spring, delta, rate, row);
      spring_rate_[k++] = rate;  // the audit's dashpot power c delta'^2 (rhs)
      F -= (spring.stiffness * delta + spring.damping * rate) * row;
    }
    r_.template segment<3>(body_offset(b)) = F;
  }
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::contact_kinematics(const State& x) const {
  // Rows of the sliding and normal velocities: the structure's constant part (set at assembly)
  // and the body point's [d, d . (k x R r)]; their rates times z' are -omega^2 d . R r (the
  // centripetal acceleration of the point); the gap n . ((x, y) + (R - I) r) + w_n . q + g0.
  const auto zd = x.segment(m_, m_);
  moving_rows(x);
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const Index body = body_of_[iu];
    if (body >= 0) {
      const Index o = body_offset(body);
      const Vector2 Rr = detail::rotated(turn_[static_cast<std::size_t>(body)], point_[iu]);
      const Scalar omega = zd[o + 2];
      G_.row(i).template segment<3>(o) = detail::body_point_row(tdir_[iu], Rr).transpose();
      H_.row(i).template segment<3>(o) = detail::body_point_row(ndir_[iu], Rr).transpose();
      gdot_[i] = -omega * omega * tdir_[iu].dot(Rr);
      hdot_[i] = -omega * omega * ndir_[iu].dot(Rr);
      e_.gap[i] = ndir_[iu].x() * x[o] + ndir_[iu].y() * x[o + 1] + ndir_[iu].dot(Rr - point_[iu]) +
                  H_.row(i).head(n_).dot(x.head(n_).transpose()) + gap0_[i];
    }
    e_.v[i] = row_dot(G_.row(i), body, zd);
    e_.vn[i] = row_dot(H_.row(i), body, zd);
  }
  moving_rates(x);
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::solve(const Mode& mode, Scalar t, const State& x) const {
  using std::isfinite;
  const auto q = x.head(n_), qd = x.segment(m_, n_);
  Evaluation& e = e_;
  e.finite = true;
  r_.head(n_) = -damping_.cwiseProduct(qd) - omega2_.cwiseProduct(q);
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    const Scalar F = loads_[l].value(t);
    r_.head(n_) += F * Phi_.col(static_cast<Index>(l));
  }
  body_forces(t, x);
  contact_kinematics(x);
  // The unknowns: a stuck contact's friction force (index i), a closed unilateral contact's
  // normal force (index D + i); every other contact's force is known.
  unknown_.clear();
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const ContactState s = mode[i];
    const bool stuck = s == ContactState::Stick && has_stick_state(i);
    e.f[i] = 0;
    mu_[i] = 0;
    if (unilateral(i)) {
      e.N[i] = 0;
      if (!is_in_contact(s)) continue;
      if (stuck) unknown_.push_back(i);
      else  // f = mu N with the law's force per unit normal force
        mu_[i] = detail::with_law(machines_[iu], [&](const auto& m) {
          return m.friction_force(s, e.v[i], Scalar(1), Scalar(0));
        });
      unknown_.push_back(D_ + i);
      continue;
    }
    e.N[i] = contacts_[iu].normal_force(t);
    if (body_of_[iu] >= 0) add_row(H_.row(i), body_of_[iu], e.N[i], r_);  // a held normal acts along n
    if (stuck) {
      unknown_.push_back(i);
      continue;
    }
    e.f[i] = detail::with_law(machines_[iu], [&](const auto& m) {
      return m.friction_force(s, e.v[i], e.N[i], Scalar(0));
    });
    if (fixed_row_[iu]) r_.head(n_) += e.f[i] * G_.row(i).head(n_).transpose();  // a fixed row lies on the modes
    else add_row(G_.row(i), body_of_[iu], e.f[i], r_);
  }
  e.qdd = minv_.cwiseProduct(r_);
  if (!unknown_.empty() && !constrained_solve()) {  // dependent constrained rows: no split of their forces
    e.finite = false;
    e.qdd.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
    return;
  }
  if (!(isfinite(e.qdd.sum()) && isfinite(e.f.sum()) && isfinite(e.N.sum()) && isfinite(e.X.sum())))
    e.finite = false;
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::gather_constrained() const {
  // Row a of the constrained rows, of the unknowns' directions and of the rows' rates times z'.
  for (Index a = 0; a < static_cast<Index>(unknown_.size()); ++a) {
    const Index k = unknown_[static_cast<std::size_t>(a)], i = k % D_;
    if (k >= D_) {
      rows_.row(a) = gap_rate_row(i);
      cols_.row(a) = H_.row(i) + mu_[i] * G_.row(i);
      rate_[a] = hdot_[i];
    } else {
      rows_.row(a) = G_.row(i);
      cols_.row(a) = G_.row(i);
      rate_[a] = gdot_[i];
    }
  }
}

template <class Scalar_, class Contact_>
template <class Block>
void ContactSystem<Scalar_, Contact_>::capacitance(Block&& C) const {
  // C = rows M^-1 cols^T of the gathered rows (gather_constrained), over the entries where both
  // can be nonzero: the modes (M^-1 = I there) and, for two unknowns on one body, its three.
  const Index U = static_cast<Index>(unknown_.size());
  for (Index a = 0; a < U; ++a) {
    const Index body = body_of_unknown(unknown_[static_cast<std::size_t>(a)]);
    for (Index c = 0; c < U; ++c) {
      Scalar sum = rows_.row(a).head(n_).dot(cols_.row(c).head(n_));
      if (body >= 0 && body == body_of_unknown(unknown_[static_cast<std::size_t>(c)])) {
        const Index o = body_offset(body);
        for (Index j = o; j < o + 3; ++j) sum += rows_(a, j) * (cols_(c, j) * minv_[j]);
      }
      C(a, c) = sum;
    }
  }
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::padded_capacitance() const -> const Matrix& {
  const Index U = static_cast<Index>(unknown_.size());
  gather_constrained();
  C_.setZero();
  capacitance(C_.topLeftCorner(U, U));
  Scalar scale = 0;
  for (Index a = 0; a < U; ++a) scale = std::max(scale, std::abs(C_(a, a)));
  for (Index a = U; a < 2 * D_; ++a) C_(a, a) = scale > 0 ? scale : Scalar(1);
  return C_;
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::constrained_solve() const {
  // C lambda = -(rows M^-1 r + rows' z'), C = rows M^-1 cols^T, with e_.qdd = M^-1 r on entry.
  // Where every unknown is the friction force of a stuck contact with a constant row (side a on
  // the structure, side b fixed: G_ row i is the same for all time and zero past the modes), C depends on the set of
  // unknowns only, and its factorisation comes from the cache keyed by the set.
  Evaluation& e = e_;
  const Index U = static_cast<Index>(unknown_.size());
  std::uint64_t key = 0;
  for (const Index k : unknown_) {
    if (k >= D_ || !fixed_row_[static_cast<std::size_t>(k)]) {
      key = 0;
      break;
    }
    key |= std::uint64_t(1) << k;
  }
  if (key != 0) {
    const detail::CapacitanceFactor<Scalar>* lu = capacitance_cache_.find(key);
    if (lu == nullptr) {
      detail::CapacitanceFactor<Scalar>& f = capacitance_cache_.insert(key);
      auto C = f.block(U);
      for (Index a = 0; a < U; ++a) {
        const auto ga = G_.row(unknown_[static_cast<std::size_t>(a)]).head(n_);
        for (Index c = a; c < U; ++c)  // symmetric: cols = rows; M^-1 = I on the modes
          C(a, c) = C(c, a) = ga.dot(G_.row(unknown_[static_cast<std::size_t>(c)]).head(n_));
      }
      f.factor(2 * D_);
      lu = &f;
    }
    if (!lu->regular()) return false;
    for (Index a = 0; a < U; ++a) {  // a fixed row lies on the modes, where M^-1 = I
      const Index i = unknown_[static_cast<std::size_t>(a)];
      lambda_[a] = -(G_.row(i).head(n_).dot(e.qdd.head(n_).transpose()) + gdot_[i]);
    }
    lu->solve(lambda_);
    for (Index a = 0; a < U; ++a) {
      const Index i = unknown_[static_cast<std::size_t>(a)];
      e.qdd.head(n_) += lambda_[a] * G_.row(i).head(n_).transpose();
      e.f[i] = lambda_[a];
    }
    return true;
  }
  gather_constrained();
  capacitance(fresh_factor_.block(U));
  fresh_factor_.factor(2 * D_);
  if (!fresh_factor_.regular()) return false;
  for (Index a = 0; a < U; ++a)
    lambda_[a] = -(row_dot(rows_.row(a), body_of_unknown(unknown_[static_cast<std::size_t>(a)]), e.qdd) + rate_[a]);
  fresh_factor_.solve(lambda_);
  for (Index a = 0; a < U; ++a) {  // z'' += lambda_a M^-1 cols_a
    const Index k = unknown_[static_cast<std::size_t>(a)], i = k % D_, body = body_of_unknown(k);
    e.qdd.head(n_) += lambda_[a] * cols_.row(a).head(n_).transpose();
    if (body >= 0)
      for (Index j = body_offset(body); j < body_offset(body) + 3; ++j) e.qdd[j] += lambda_[a] * (minv_[j] * cols_(a, j));
    if (k >= D_) e.N[i] = lambda_[a];
    else e.f[i] = lambda_[a];
  }
  for (Index i = 0; i < D_; ++i)
    if (mu_[i] != Scalar(0)) e.f[i] = mu_[i] * e.N[i];
  return true;
}

}  // namespace stickslip
