#pragma once
/// \file contact_system_linear.hpp
/// \brief ContactSystem's linear part per discrete mode, x_L' = A_m x_L + b_m(t) + r_m
/// (stickslip/ode/linear_part.hpp), for the exponential method (Integrator::Exponential).
///
/// With x_L = (z, z') and the known generalised forces r = K z + D z' + r_c + sum_l phi_l F_l(t)
/// (modal stiffness -omega^2 and damping -c on the diagonal; a body spring's -k g g^T and
/// -c g g^T along its point's row g; r_c the slipping contacts' friction forces), the coupled
/// solve gives the unknowns lambda = L r + lambda_r and the accelerations
///
///     z'' = M^-1 (r + B^T lambda) = Q r + a_r,   L = -C^-1 G M^-1,   Q = M^-1 (I + B^T L),
///
/// with C = G M^-1 B^T the capacitance matrix of the constrained rows G (directions B),
/// lambda_r = -C^-1 G' z' and a_r = M^-1 B^T lambda_r (docs/contacts.md). So
///
///     A_m = [0, I; Q K, Q D],   b_m(t) = (0, Q (r_c + sum_l phi_l F_l(t)) + a_r).
///
/// Exact where nothing of it depends on x: every contact a PointContact (constant rows) with a
/// constant normal force, stuck, or slipping under Coulomb friction (r_c = -mu_k N sgn(v) g,
/// constant), no rigid bodies (their rows and springs rotate with theta) and loads without a
/// time function. Its guards are then affine: a stuck contact's mu_s N -/+ lambda_a (lambda_a
/// = L_a r + lambda_r,a), a slipping one's v = g . z'. Elsewhere (a regularised or Stribeck
/// law, bodies, unilateral contacts) the rows, rotations and friction forces are frozen at
/// (t, x) and b0 absorbs the rest at x (r_m(t, x) = 0 there), as the Lawson steps expect.

#include <stickslip/model/contact_system.hpp>

#include <type_traits>

namespace stickslip {

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::exact_mode(const Mode& mode) const {
  if (body_contacts || B_ > 0) return false;
  for (const Load& l : loads_)
    if (l.time_function) return false;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    if constexpr (std::is_same_v<Contact, PointContact<Scalar>>) {
      if (contacts_[iu].normal.time_function) return false;
    } else {
      return false;  // a kind of its own: its normal force may vary in time
    }
    if (mode[i] == ContactState::Stick && has_stick_state(i)) continue;
    const bool coulomb = detail::with_law(machines_[iu], [](const auto& m) {
      return std::is_same_v<std::decay_t<decltype(m)>, CoulombContact<CoulombLaw<Scalar>>>;
    });
    if (!coulomb || !is_slipping(mode[i])) return false;
  }
  return true;
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::linear_part(const Mode& mode, Scalar t, const State& x,
                                                   LinearPart<Scalar>& lp) {
  static const char* where = "ContactSystem::linear_part";
  validate_state(mode, x, where);
  solve(mode, t, x);
  if (!e_.finite) return false;
  using std::abs;
  using std::cos;
  using std::sin;
  detail::ContactLinearWorkspace<Scalar>& w = lin_;
  w.resize(m_, D_);
  const bool exact = exact_mode(mode);
  const Index P = 2 * m_, U = static_cast<Index>(unknown_.size());

  // Stiffness and damping of the known forces: the modes' diagonal, each body spring's
  // -k g g^T and -c g g^T along its point's row g at the current rotation.
  w.K.setZero();
  w.Dm.setZero();
  w.K.diagonal().head(n_) = -omega2_;
  w.Dm.diagonal().head(n_) = -damping_;
  for (Index b = 0; b < B_; ++b) {
    const Index o = body_offset(b);
    for (const auto& spring : bodies_[static_cast<std::size_t>(b)].springs) {
      Scalar delta, rate;
      Eigen::Matrix<Scalar, 3, 1> row;
      spring_extension(x, b, spring, delta, rate, row);
      w.K.template block<3, 3>(o, o).noalias() -= spring.stiffness * row * row.transpose();
      w.Dm.template block<3, 3>(o, o).noalias() -= spring.damping * row * row.transpose();
    }
  }
  // The known friction forces of held contacts that are not stuck (constant in an exact mode).
  w.known.setZero();
  for (Index i = 0; i < D_; ++i)
    if (!unilateral(i) && !(mode[i] == ContactState::Stick && has_stick_state(i)))
      w.known += e_.f[i] * G_.row(i).transpose();

  // The coupled solve's maps: L = -C^-1 G M^-1 (column by column through the factorised
  // capacitance matrix of solve()'s unknowns, padded to 2D x 2D), Q = M^-1 (I + B^T L).
  w.Q.setZero();
  w.Q.diagonal() = minv_;
  w.acc_rate.setZero();
  if (U > 0) {
    w.lu.compute(padded_capacitance());
    for (Index c = 0; c < m_; ++c) {
      w.rhs.setZero();
      w.rhs.head(U) = -minv_[c] * rows_.col(c).head(U);
      w.col = w.lu.solve(w.rhs);
      w.L.col(c) = w.col;
    }
    w.rhs.setZero();
    w.rhs.head(U) = -rate_.head(U);
    w.lambda_rate = w.lu.solve(w.rhs);
    auto direction = w.b.head(m_);  // scratch: M^-1 B_a^T
    for (Index a = 0; a < U; ++a) {
      direction = minv_.cwiseProduct(cols_.row(a).transpose());
      w.Q.noalias() += direction * w.L.row(a);
      w.acc_rate += w.lambda_rate[a] * direction;
    }
  }

  // A_m and b_m.
  lp.A.setZero(P, P);
  lp.A.topRightCorner(m_, m_).setIdentity();
  lp.A.bottomLeftCorner(m_, m_).noalias() = w.Q * w.K;
  lp.A.bottomRightCorner(m_, m_).noalias() = w.Q * w.Dm;
  lp.b0.setZero(P);
  lp.b0.tail(m_).noalias() = w.Q * w.known;
  lp.b0.tail(m_) += w.acc_rate;
  lp.omega.clear();
  detail::add_load_frequencies(loads_, lp.omega);
  const Index K = static_cast<Index>(lp.omega.size());
  lp.bc.setZero(P, K);
  lp.bs.setZero(P, K);

  // Affine guards of an exact mode: per contact in order, stuck mu_s N -/+ lambda_a, slipping v.
  const Index G = exact ? num_guards(mode) : 0;
  lp.Gx.setZero(G, G > 0 ? P : 0);
  lp.g0.setZero(G);
  lp.gc.setZero(G, K);
  lp.gs.setZero(G, K);
  for (Index i = 0, k = 0; G > 0 && i < D_; k += guards_of(mode, i), ++i) {
    if (is_slipping(mode[i])) {
      lp.Gx.row(k).segment(m_, m_) = G_.row(i);
      continue;
    }
    Index a = 0;
    while (a < U && unknown_[static_cast<std::size_t>(a)] != i) ++a;
    const Scalar capacity = detail::with_law(machines_[static_cast<std::size_t>(i)], [&](const auto& m) {
      if constexpr (std::decay_t<decltype(m)>::has_stick_state)
        return m.stick_capacity(e_.N[i]);
      else
        return Scalar(0);
    });
    // lambda_a = L_a (K z + D z' + r_c + sum_l phi_l F_l) + lambda_r,a; g = capacity -/+ lambda_a.
    lp.Gx.row(k).head(m_).noalias() = -w.L.row(a) * w.K;
    lp.Gx.row(k).tail(m_).noalias() = -w.L.row(a) * w.Dm;
    lp.Gx.row(k + 1) = -lp.Gx.row(k);
    const Scalar lambda0 = w.L.row(a).dot(w.known) + w.lambda_rate[a];
    lp.g0[k] = capacity - lambda0;
    lp.g0[k + 1] = capacity + lambda0;
  }
  // Loads: F = a sin(w t + phi) + offset = a sin(phi) cos(w t) + a cos(phi) sin(w t) + offset.
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    const Load& load = loads_[l];
    if (load.time_function) continue;  // left to the remainder (an inexact mode)
    const auto phi = Phi_.col(static_cast<Index>(l));
    const Scalar cosine = load.amplitude * sin(load.phase), sine = load.amplitude * cos(load.phase);
    const Scalar constant = load.offset + (load.omega == Scalar(0) ? cosine : Scalar(0));
    Index kk = -1;
    Scalar s = 0;
    if (load.omega != Scalar(0)) {
      kk = static_cast<Index>(std::find(lp.omega.begin(), lp.omega.end(), abs(load.omega)) - lp.omega.begin());
      s = load.omega < 0 ? -sine : sine;  // sin(-w t + phi) = sin(phi) cos(w t) - cos(phi) sin(w t)
    }
    for (Index c = 0; c < n_; ++c) {  // the load's acceleration Q phi, column by column of Q
      const Scalar pc = phi[c];
      if (pc == Scalar(0)) continue;
      lp.b0.tail(m_) += constant * pc * w.Q.col(c);
      if (kk >= 0) {
        lp.bc.col(kk).tail(m_) += cosine * pc * w.Q.col(c);
        lp.bs.col(kk).tail(m_) += s * pc * w.Q.col(c);
      }
    }
    for (Index i = 0, k = 0; G > 0 && i < D_; k += guards_of(mode, i), ++i) {
      if (is_slipping(mode[i])) continue;
      Index a = 0;
      while (a < U && unknown_[static_cast<std::size_t>(a)] != i) ++a;
      const Scalar la = w.L.row(a).head(n_).dot(phi);  // lambda_a per unit load
      lp.g0[k] -= constant * la;
      lp.g0[k + 1] += constant * la;
      if (kk >= 0) {
        lp.gc(k, kk) -= cosine * la;
        lp.gc(k + 1, kk) += cosine * la;
        lp.gs(k, kk) -= s * la;
        lp.gs(k + 1, kk) += s * la;
      }
    }
  }
  lp.quadrature_forms.clear();
  lp.exact = exact;
  if (!exact || !w.exact_valid || !(mode == w.mode)) ++w.version;
  w.exact_valid = exact;
  w.mode = mode;
  lp.version = w.version;
  if (exact) return true;
  // r_m(t, x) = f(t, x) - A x_L - b(t) into b0: the remainder vanishes at x. (e_ still holds
  // the solve at (t, x).)
  w.f.head(m_) = x.segment(m_, m_);
  w.f.tail(m_) = e_.qdd;
  lp.load(t, w.b);
  w.f -= w.b;
  w.f.noalias() -= lp.A * x.head(P);
  lp.b0 += w.f;
  return true;
}

}  // namespace stickslip
