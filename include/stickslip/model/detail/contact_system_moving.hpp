#pragma once
/// \file contact_system_moving.hpp
/// \brief ContactSystem's contacts whose side b moves along its member (contact_system.hpp,
/// docs/contacts.md "A moving contact point"): their assembly, their rows at the current contact
/// coordinate X and the rates those rows add (the convective terms of paper eqs 17-19).
///
/// Side b is the member point under the body point at X, with the member's local axes u (along)
/// and w (normal); t = sigma_t u and n = sigma_n w. The structure parts of the rows are the shapes
/// at X, -sigma_t psi_u(X) (sliding) and -sigma_n psi_w(X) (normal), so that v and v_n are the
/// relative velocities over the material point at X, along which the contact forces act. X moves
/// with the sliding, X' = sigma_t v. The gap g = n . c + g0 - sigma_n psi_w(X) . q (c: the body
/// point's displacement) has the rate
///     g' = v_n - s X',                 s = sigma_n psi_w'(X) . q (the member's slope along n),
/// so a closed contact holds g'' = 0 on the row h - sigma_t s g (gap_rate_row), whose rate adds
///     -sigma_n (2 (psi_w' . q') X' + (psi_w'' . q) X'^2) - sigma_t s (rate of g),
/// and the sliding row's rate adds -(psi_u' . q') v (detail::convective_*). Where a contact slides
/// on the slope, N v_n = N s X' is the normal force's work on it (the paper's slope work), booked
/// with the friction work in the audit's contact term.

#include <stickslip/model/contact_system.hpp>

namespace stickslip {

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::assemble_moving_side(Index i, const Contact& c, const FrameModel<Scalar>& frame,
                                                            const ModalBasis<Scalar>& basis, const std::string& name) {
  const auto side_b = c.structure_side();
  if (!side_b) detail::throw_invalid(name, "contact_point = Moving needs a side b on the structure (b)", 0);
  const StructurePoint<Scalar> b = *side_b;
  shapes_at_point(frame, basis, b, name + ": side b");  // checks the member and X0 on it
  MemberShapes<Scalar> shapes(frame, b.member, basis, EndPolicy::Extrapolate);
  if (!(b.coordinate > Scalar(0) && b.coordinate < shapes.length()))
    detail::throw_invalid(name, "side b of a moving contact point must start inside member " +
                                    std::to_string(b.member) + " (0 < b.coordinate < " +
                                    detail::format_value(shapes.length()) + ")",
                          b.coordinate);
  const PlaneDirection<Scalar> t = c.tangent_direction(), n = c.normal_direction();
  const Scalar sigma_t = t.x * shapes.cos() + t.y * shapes.sin();  // t . u
  const Scalar sigma_n = -n.x * shapes.sin() + n.y * shapes.cos();  // n . w
  using std::abs;
  if (!(abs(abs(sigma_t) - Scalar(1)) <= Scalar(1e-9)))
    detail::throw_invalid(name, "the normal of a moving contact point must be normal to member " +
                                    std::to_string(b.member) + " (its tangent along the member's axis), t . u =",
                          sigma_t);
  moving_of_[static_cast<std::size_t>(i)] = num_moving();
  moving_.emplace_back(i, std::move(shapes), sigma_t > 0 ? Scalar(1) : Scalar(-1), sigma_n > 0 ? Scalar(1) : Scalar(-1),
                       b.coordinate);
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::initial_state() const -> State {
  State x = State::Zero(state_size());
  for (Index p = 0; p < num_moving(); ++p) x[contact_offset() + p] = moving_[static_cast<std::size_t>(p)].start;
  return x;
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::moving_rows(const State& x) const {
  // The structure parts of the rows at the current X (before the sliding and normal velocities).
  for (Index p = 0; p < num_moving(); ++p) {
    auto& side = moving_[static_cast<std::size_t>(p)];
    const Index i = side.contact;
    const Scalar X = x[contact_offset() + p];
    e_.X[i] = X;  // a non-finite X makes the evaluation not finite (solve), the shapes stay finite
    using std::isfinite;
    side.shapes.evaluate(isfinite(X) ? X : side.start, side.values, side.cursor);
    G_.row(i).head(n_) = -side.sigma_t * side.values.psi_u.transpose();
    H_.row(i).head(n_) = -side.sigma_n * side.values.psi_w.transpose();
  }
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::moving_rates(const State& x) const {
  // The convective terms of the rows' rates and the gap-rate rows (after the velocities).
  const auto q = x.head(n_), qd = x.segment(m_, n_);
  for (Index p = 0; p < num_moving(); ++p) {
    const auto& side = moving_[static_cast<std::size_t>(p)];
    const auto& s = side.values;
    const Index i = side.contact;
    const Scalar v = e_.v[i], Xd = side.sigma_t * v;
    gdot_[i] -= side.sigma_t * detail::convective_velocity_rate(s.dpsi_u.dot(qd), Xd);
    const Scalar slope = side.sigma_n * s.dpsi_w.dot(q);
    hdot_[i] -= side.sigma_n * detail::convective_displacement_acceleration(s.dpsi_w.dot(qd), s.ddpsi_w.dot(q), Xd) +
                side.sigma_t * slope * gdot_[i];
    Hc_.row(i) = H_.row(i) - (side.sigma_t * slope) * G_.row(i);
  }
}

}  // namespace stickslip
