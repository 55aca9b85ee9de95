#pragma once
/// \file kinematics.hpp
/// \brief FrictionDampedSystem, contact kinematics: the mode shapes at each contact point
/// (a = side psi_w(X), b = psi_u(X), slope psi_w'(X)), the element-space rows of a slipping damper
/// whose contact moves, with the convective terms h = 2 (psi_w'^T q') V + (psi_w''^T q) V^2 and
/// (psi_u'^T q') V, a separated damper's flight rows, and the member's motion under a contact
/// (y, y', V, the gap and sliding accelerations of a damper in flight).

#include "stickslip/model/friction_damped_system.hpp"
#include "stickslip/model/detail/moving_contact.hpp"

namespace stickslip {

/// Shapes of damper i at contact coordinate X into C_ and its slope column. Kept while X
/// is unchanged (bitwise): a stuck damper's X is exactly constant over every stage of a stick
/// phase, so its shapes are evaluated once per phase.
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::evaluate_shapes(Index i, Scalar X) const {
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

/// A separated damper (no unknown: N = f = 0): its shapes at X, V = x' - b^T q', the member's
/// y = a^T q, slope and the gap y - y_d (its guard); e.y reports the damper's own y_d.
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::flight_rows(Index i, const State& x) const {
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
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::moving_damper(Index i, const Mode& mode, const State& x) const {
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
    h = detail::convective_displacement_acceleration(dw_qd, ddw_q, V);
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
template <class Scalar_, class Law_, int Modes>
template <class DstF, class DstL, class DstB, class Block6>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::slip_columns(DstF&& dstF, DstL&& dstL, DstB&& dstB,
                                                                     const Block6& B,
                                                                     const Eigen::Matrix<Scalar, 6, 1>& ca,
                                                                     const Eigen::Matrix<Scalar, 6, 1>& cb, Scalar mu,
                                                                     Scalar la, Scalar lb) {
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
template <class Scalar_, class Law_, int Modes>
template <bool Add, class Dst, class Block6>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::block_times(Dst&& dst, const Block6& B,
                                                                    const Eigen::Matrix<Scalar, 6, 1>& c) {
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

/// Gap acceleration g'' of separated damper i in flight at (mode, t, x):
///   g'' = a^T q'' + 2 s_d V + c V^2 + slope V' - N0/m,  V' = x'' - b^T q'' - (psi_u'^T q') V,
/// with s_d = side psi_w'^T q', c = side psi_w''^T q at X (the terms in V with a moving contact
/// only: d^2/dt^2 of y = side psi_w(X(t))^T q(t) with X' = V, minus y_d'' = N0/m).
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

/// Tangential acceleration V' of separated damper i in flight: x'' - b^T q'' - (psi_u'^T q') V.
template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::flight_sliding_acceleration(const Mode& mode, Index i, Scalar t,
                                                                             const State& x) -> Scalar {
  const std::size_t iu = static_cast<std::size_t>(i);
  const Evaluation& e = evaluate(mode, t, x);
  if (!moving_[iu]) return Scalar(0);
  evaluate_shapes(i, e.X[i]);
  const auto& v = values_[iu];
  const auto qd = x.template segment<Modes>(n_, n_);
  return e.xdd[i] - v.psi_u.dot(modal(e.qdd)) - detail::convective_velocity_rate(v.dpsi_u.dot(qd), e.V[i]);
}

}  // namespace stickslip
