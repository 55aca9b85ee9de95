#pragma once
/// \file jacobian.hpp
/// \brief FrictionDampedSystem, the Jacobian df/dx (variational equations of shooting): A_m of
/// an exact mode, the tangent of the solve (A + L^T F) du = rho - L^T dr0 where contacts slide
/// under a CoulombLaw, the closed-form columns of the moving contacts' X, central differences
/// elsewhere (docs/model_solve.md, "Jacobian df/dx").

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

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
  if (!linear_part(mode, t, x, jac_.lp)) {
    J.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
    return;
  }
  STICKSLIP_ASSERT(jac_.lp.exact && "FrictionDampedSystem::jacobian: exact_mode disagrees with linear_part");
  const Index P = linear_size();
  J.setZero();
  J.topLeftCorner(P, P) = jac_.lp.A;
  if (jac_.lp.has_quadrature_forms()) {  // d(z^T Q z)/dz = (Q + Q^T) z, its first P entries
    const Index K = static_cast<Index>(jac_.lp.omega.size());
    jac_.z.resize(P + 1 + 2 * K);
    jac_.z.head(P) = x.head(P);
    jac_.z[P] = Scalar(1);
    using std::cos;
    using std::sin;
    for (Index k = 0; k < K; ++k) {
      const Scalar w = jac_.lp.omega[static_cast<std::size_t>(k)];
      jac_.z[P + 1 + 2 * k] = cos(w * t);
      jac_.z[P + 2 + 2 * k] = sin(w * t);
    }
    for (std::size_t q = 0; q < jac_.lp.quadrature_forms.size(); ++q) {
      const Matrix& Q = jac_.lp.quadrature_forms[q];
      auto row = J.row(P + static_cast<Index>(q)).head(P).transpose();
      row.noalias() = Q.topRows(P) * jac_.z;
      row.noalias() += Q.leftCols(P).transpose() * jac_.z;
    }
  }
  if (options_.moving_contact && !contact_columns(mode, t, x, J, false))
    for (Index i = 0; i < D_; ++i) jacobian_column(mode, t, x, contact_offset() + i, J);
}

/// Column j of J by central differences of rhs (h = 1e-6 max(1, |x_j|)).
template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::jacobian_column(const Mode& mode, Scalar t, const State& x, Index j,
                                                                Matrix& J) {
  using std::abs;
  const Scalar h = Scalar(1e-6) * std::max(Scalar(1), abs(x[j]));
  jac_.x = x;
  jac_.x[j] = x[j] + h;
  rhs(mode, t, jac_.x, jac_.fp);
  jac_.x[j] = x[j] - h;
  rhs(mode, t, jac_.x, jac_.fm);
  J.col(j) = (jac_.fp - jac_.fm) / (Scalar(2) * h);
}

/// The tangent's (and contact_columns') condition: no damper in flight or resting at a wall,
/// and every slipping damper's coefficient a constant (a CoulombLaw's mu_k).
template <class Scalar_, class Law_, int Modes>
inline bool FrictionDampedSystem<Scalar_, Law_, Modes>::tangent_applies(const Mode& mode) const {
  using std::isnan;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    if (mode[i] == ContactState::Separated || mode.wall(i) != WallRest::None) return false;
    const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
    if (!stuck && isnan(kinetic_constant_[iu])) return false;
  }
  return true;
}

/// J of an inexact mode by the tangent of the solve (every column but the moving contacts'
/// X, which the caller takes by differences); false, J untouched, where it does not apply (a
/// damper in flight or resting at a wall, or slipping under a law whose coefficient varies
/// with V).
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
  if (jac_.rho.rows() != D2 || jac_.rho.cols() != N) {
    jac_.rho.setZero(D2, N);
    jac_.du.setZero(D2, N);
    for (auto* g : {&jac_.gV, &jac_.gs, &jac_.gh, &jac_.gd, &jac_.gc}) g->setZero(N);
    jac_.shape.resize(n);
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
  auto rho = jac_.rho.topRows(U);
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
    jac_.gV.setZero();
    jac_.gV[xd_offset() + i] = Scalar(1);
    jac_.gV.segment(qd0, n) = -v.psi_u.transpose();
    jac_.gs.setZero();
    jac_.gs.head(n) = sd * v.dpsi_w.transpose();
    jac_.gh = (Scalar(2) * dw_qd + Scalar(2) * ddw_q * V) * jac_.gV;
    jac_.gh.head(n) += (V * V * sd) * v.ddpsi_w.transpose();
    jac_.gh.segment(qd0, n) += (Scalar(2) * V * sd) * v.dpsi_w.transpose();
    jac_.gd = du_qd * jac_.gV;
    jac_.gd.segment(qd0, n) += V * v.dpsi_u.transpose();
    // rho_j = (dc - dA N - dL^T q'') / s_j with dc = -m dh + (k x_d + m dd) dsc + sc k dx_d +
    // m sc ddd, dA = -mu dsc, dL = -m b dsc
    jac_.gc = -m * jac_.gh + (k * xi + m * dd + mu * e.N[i] + m * v.psi_u.dot(e.qdd)) * jac_.gs +
              (m * sc) * jac_.gd;
    jac_.gc[x_offset() + i] += sc * k;
    using std::abs;
    const Scalar diag = Scalar(1) - sc * mu;
    const Scalar s_j = diag != Scalar(1) && abs(diag) >= Scalar(0.5) ? diag : Scalar(1);
    rho.row(j) = jac_.gc / s_j;
  }
  // dq'' = dr0 + F du (n x N), J's q'' rows; dr0 = -omega^2 dq - c dq'.
  auto qdd_rows = J.middleRows(n, n);
  if (U > 0) {
    const auto F = F_.topLeftCorner(n, U);
    const auto L = L_.topLeftCorner(n, U);
    rho.leftCols(n).noalias() += L.transpose() * omega2_.asDiagonal();
    rho.middleCols(qd0, n).noalias() += L.transpose() * modal_damping_.asDiagonal();
    Eigen::PartialPivLU<Matrix>& lu = tangent_lu(U);
    auto du = jac_.du.topRows(U);
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
    if (unknown >= 0) J.row(xd_offset() + i) = (-mu / m) * jac_.du.row(unknown);
    J(xd_offset() + i, x_offset() + i) -= k / m;
    // V = x_d' - b^T q' (b at X)
    jac_.gV.setZero();
    jac_.gV[xd_offset() + i] = Scalar(1);
    if (moving_[iu]) {
      jac_.gV.segment(qd0, n) = -modal(slip_b_.col(i)).transpose();
      J.row(contact_offset() + i) = jac_.gV;
    } else {
      jac_.gV.segment(qd0, n) = -C_.col(D_ + i).head(n).transpose();
    }
    if (!audit) continue;
    const Scalar V = e.V[i], Ni = e.N[i], fi = e.f[i];
    // D_fric' = -sum f V: -(V df + f dV), df = -mu dN
    if (unknown >= 0) J.row(o + 2) += (V * mu) * jac_.du.row(unknown);
    J.row(o + 2) -= fi * jac_.gV;
    if (options_.moving_contact && moving_[iu]) {  // W_slope' = -sum N slope V
      const Scalar sl = e.slope[i];
      if (unknown >= 0) J.row(o + 3) -= (sl * V) * jac_.du.row(unknown);
      J.row(o + 3) -= (Ni * sl) * jac_.gV;
      J.row(o + 3).head(n) -= (Ni * V * dmp.side) * jacobian_shapes(i, e.X[i]).dpsi_w.transpose();
    }
  }
  return true;
}

/// The columns of the moving contacts' X in closed form (docs/model_solve.md, "Jacobian df/dx"),
/// where the tangent applies (no damper in flight or at a wall, Coulomb slip); false, J
/// untouched, elsewhere. `lu_ready`: tangent_jacobian has just factorised A + L^T F at x.
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
  if (U > 0) lu = lu_ready ? &jac_.lu[static_cast<std::size_t>(U)] : &tangent_lu(U);
  jac_.d3w.resize(n);
  jac_.g.resize(n);
  jac_.dqdd.resize(n);
  jac_.dux.resize(std::max<Index>(U, 1));
  jac_.sol.resize(std::max<Index>(U, 1));
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
      jac_.d3w.noalias() = w3 * (B.col(1) - B.col(4)) + t3 * (B.col(2) + B.col(5));
    }
    const auto& v = jacobian_shapes(i, e.X[i]);
    const Scalar sd = dmp.side, m = dmp.effective_mass(), k = dmp.effective_stiffness();
    const Scalar xi = x[x_offset() + i];
    const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
    const Index jN = unknown_row(i), jf = unknown_row(D_ + i);  // N_i's and (stuck) f_i's rows
    // d/dX of the solve: (A + L^T F) du = rho - L^T g, dq'' = g + F du, with
    // rho_j = (dc_j - dA_j u_j - dL_j^T q'') / s_j in damper i's rows and g = dr0 + dF u.
    jac_.g.setZero();
    jac_.dux.setZero();
    const Scalar slope = sd * v.dpsi_w.dot(q), dslope = sd * v.ddpsi_w.dot(q);
    Scalar dV = 0;  // dV/dX of a slipping damper (V = x_d' - b^T q')
    if (stuck) {
      if (jN >= 0) {  // N + m a^T q'' = N0: F_j = a, L_j = m a
        jac_.g.noalias() += (sd * u_[jN]) * v.dpsi_w;
        jac_.dux[jN] = -m * sd * v.dpsi_w.dot(qdd);
      } else {  // N0 a in r0
        jac_.g.noalias() += (sd * dmp.preload) * v.dpsi_w;
      }
      if (jf >= 0) {  // f - m b^T q'' = k x_d: F_j = -b, L_j = -m b
        jac_.g.noalias() -= u_[jf] * v.dpsi_u;
        jac_.dux[jf] = m * v.dpsi_u.dot(qdd);
      }
    } else {
      const Scalar mu = mu_[i], V = e.V[i];
      dV = -v.dpsi_u.dot(qd);
      if (jN >= 0) {  // F_j = a + mu b, L_j = m (a - sc b), A_j = 1 - sc mu, c_j = N0 - m h + sc k x_d + m sc dd
        const Scalar Ni = u_[jN];
        jac_.g.noalias() += Ni * (sd * v.dpsi_w + mu * v.dpsi_u);
        Scalar rho = -m * sd * v.dpsi_w.dot(qdd), diag = Scalar(1);
        if (convective) {
          const Scalar sc = slope, dsc = dslope;
          const Scalar dw_qd = sd * v.dpsi_w.dot(qd), ddw_q = sd * v.ddpsi_w.dot(q);
          const Scalar d_dw_qd = sd * v.ddpsi_w.dot(qd), d_ddw_q = sd * jac_.d3w.dot(q);
          const Scalar du_qd = v.dpsi_u.dot(qd), dd = du_qd * V, d_dd = du_qd * dV;
          const Scalar dh = Scalar(2) * (d_dw_qd * V + dw_qd * dV) + d_ddw_q * V * V + Scalar(2) * ddw_q * V * dV;
          const Scalar dc = -m * dh + dsc * k * xi + m * dsc * dd + m * sc * d_dd;
          const Scalar dA = -dsc * mu;
          // dL = m (a' - sc' b - sc b')
          rho += dc - dA * Ni + m * (dsc * v.psi_u.dot(qdd) + sc * v.dpsi_u.dot(qdd));
          diag = Scalar(1) - sc * mu;
        }
        const Scalar s_j = diag != Scalar(1) && abs(diag) >= Scalar(0.5) ? diag : Scalar(1);
        jac_.dux[jN] = rho / s_j;
      } else {  // N0 (a + mu b) in r0
        jac_.g.noalias() += dmp.preload * (sd * v.dpsi_w + mu * v.dpsi_u);
      }
    }
    auto du = jac_.sol.head(U);
    if (U > 0) {
      jac_.dux.head(U).noalias() -= L_.topLeftCorner(n, U).transpose() * jac_.g;
      du.noalias() = lu->solve(jac_.dux.head(U));
      jac_.dqdd.noalias() = jac_.g + F_.topLeftCorner(n, U) * du;
    } else {
      jac_.dqdd = jac_.g;
    }
    auto col = J.col(cX);
    col.segment(n, n) = jac_.dqdd;
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
        col[xd_offset() + l] = bl.dot(jac_.dqdd) + (l == i ? v.dpsi_u.dot(qdd) : Scalar(0));
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

/// The LU of the tangent's capacitance matrix A + L^T F (U unknowns) of the last evaluation.
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::tangent_lu(Index U) -> Eigen::PartialPivLU<Matrix>& {
  if (jac_.lu.size() <= static_cast<std::size_t>(U))  // U <= 2D: one slot per count, made once
    jac_.lu.resize(static_cast<std::size_t>(std::max(U, 2 * D_) + 1));
  Eigen::PartialPivLU<Matrix>& lu = jac_.lu[static_cast<std::size_t>(U)];
  if (lu.rows() != U) lu = Eigen::PartialPivLU<Matrix>(U);
  jac_.S.noalias() = L_.topLeftCorner(n_, U).transpose() * F_.topLeftCorner(n_, U);
  jac_.S.diagonal() += A_.head(U);
  lu.compute(jac_.S);
  return lu;
}

/// The row of `column` (N_i: i; a stuck damper's f_i: D + i) among the last solve's unknowns,
/// or -1 (a constant normal load).
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::unknown_row(Index column) const -> Index {
  for (Index j = 0; j < num_unknowns_; ++j)
    if (unknown_of_[static_cast<std::size_t>(j)] == column) return j;
  return -1;
}

/// Damper i's shapes at its contact X into jac_.shape (MemberShapes::evaluate).
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::jacobian_shapes(
    Index i, Scalar X) -> const typename Shapes::Values& {
  const std::size_t iu = static_cast<std::size_t>(i);
  shapes_[static_cast<std::size_t>(damper_shape_[iu])].evaluate(X, jac_.shape, cursors_[iu]);
  return jac_.shape;
}

}  // namespace stickslip
