#pragma once
/// \file energy.hpp
/// \brief FrictionDampedSystem, the energy audit: the rates of the audit integrals
/// (W_ext' = sum_l F_l psi_l^T q', D_visc' = q'^T c q', D_fric' = -f V, W_slope' = -N slope V), the
/// mechanical energy E, the balance E - E0 = W_ext - D_visc - D_fric + W_slope - D_imp, and the
/// rates as quadratic forms for the exponential method.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

/// The rates of the audit integrals into dxdt from an evaluation (rhs): W_ext' = sum_l F_l(t)
/// psi_l^T q', D_visc' = q'^T c q', D_fric' = -f . V, W_slope' = -sum_i N_i slope_i V_i (a moving
/// contact only), and D_imp' = 0 (the impact losses change at impacts only).
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::audit_rates(const Evaluation& e, Scalar t, const State& x,
                                                                    State& dxdt) const {
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
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::energy_balance(
    const Mode& mode, Scalar t, const State& x, Scalar E0) -> EnergyBalance {
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
  if (options_.end_policy == EndPolicy::Clamp)
    for (std::size_t i = 0; i < dampers_.size(); ++i)
      if (moving_[i] && (end_kind_[i][0] == MemberEnd::Extend || end_kind_[i][1] == MemberEnd::Extend))
        b.applies = false;
  return b;
}

/// The energy audit's rates (rhs) as quadratic forms z^T Q_j z of an exact mode
/// (LinearPart::quadrature_forms): W_ext' = sum_l F_l(t) psi_l . q' with F_l in the clock
/// components of z, D_visc' = q'^T diag(c) q', D_fric' = -f . V with f = lp_.fz z and
/// V = lp_.vz z, W_slope' = 0 (a stuck damper has V = 0, an exact slipping one a fixed contact).
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::audit_forms(Index P, Index K, LinearPart<Scalar>& lp) const {
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
  lp.quadrature_forms[2].noalias() = -lp_.fz.transpose() * lp_.vz;
}

}  // namespace stickslip
