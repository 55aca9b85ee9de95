#pragma once
/// \file scene.hpp
/// \brief FrictionDampedSystem, the scene: checks the dampers, loads and options, builds one
/// MemberShapes per member a damper or load touches, the per-damper flags every evaluation reads
/// (stick state, inertial normal load, moving contact, flight slot, member ends), the loads' modal
/// vectors psi_l, the workspace of the solve, and the step rates an explicit method must resolve.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

template <class Scalar_, class Law_, int Modes>
FrictionDampedSystem<Scalar_, Law_, Modes>::FrictionDampedSystem(const FrameModel<Scalar>& model,
                                                                 const ModalBasis<Scalar>& basis,
                                                                 std::vector<Damper> dampers,
                                                                 std::vector<Load> loads,
                                                                 ModelOptions<Scalar> options)
    : dampers_(std::move(dampers)), loads_(std::move(loads)), options_(options) {
  n_ = basis.size();
  D_ = static_cast<Index>(dampers_.size());
  if (n_ < 1) detail::throw_invalid("FrictionDampedSystem", "basis must hold >= 1 mode", n_);
  if (Modes != Eigen::Dynamic && n_ != Modes)
    detail::throw_invalid("FrictionDampedSystem",
                          "basis must hold exactly Modes = " + std::to_string(Modes) +
                              " modes (use ModalBasis::truncated), basis size",
                          n_);
  if (D_ > DamperStates::max_dampers)
    detail::throw_invalid("FrictionDampedSystem", "at most 64 dampers", D_);
  detail::require_enumerator("FrictionDampedSystem", "options.normal_load", "NormalLoad", options_.normal_load,
                             NormalLoad::Inertial);
  detail::require_enumerator("FrictionDampedSystem", "options.end_policy", "EndPolicy", options_.end_policy,
                             EndPolicy::Extrapolate);
  for (Index i = 0; i < D_; ++i) dampers_[static_cast<std::size_t>(i)].validate(i);  // before their fields are read
  for (const Damper& d : dampers_) {
    const bool moving = options_.moving_contact && d.contact_point == ContactPoint::Moving;
    moving_.push_back(moving);
  }
  // The state carries contact coordinates when at least one contact moves.
  options_.moving_contact = std::find(moving_.begin(), moving_.end(), true) != moving_.end();
  if (!options_.moving_contact) options_.convective_terms = false;

  omega2_ = basis.omega().array().square().matrix();
  // c_j of the basis (2 zeta_j omega_j, or alpha + beta omega_j^2 with Rayleigh damping, which
  // keeps alpha on a rigid-body mode): not recomputed from zeta, which is 0 for a rigid mode.
  modal_damping_ = basis.damping_coefficients();

  // One MemberShapes per member touched by a damper or a load.
  auto shapes_for = [&](Index member) -> Index {
    for (std::size_t s = 0; s < shape_members_.size(); ++s)
      if (shape_members_[s] == member) return static_cast<Index>(s);
    if (member < 0 || member >= model.num_members())
      detail::throw_invalid("FrictionDampedSystem", "member index does not exist", member);
    // The model watches the member ends itself (guards on X, policy Throw), so the shapes
    // extrapolate for the trial stages an integrator may take just past an end.
    shapes_.emplace_back(model, member, basis,
                         options_.end_policy == EndPolicy::Clamp ? EndPolicy::Clamp : EndPolicy::Extrapolate);
    shape_members_.push_back(member);
    {  // the member's nodal values transposed (3 per node x n): an element's 6 x n block has
       // each mode's six values contiguous, for the projections of moving_damper()
      const Shapes& sh = shapes_.back();
      Matrix t(3 * (sh.num_elements() + 1), n_);
      for (Index el = 0; el < sh.num_elements(); ++el)
        t.template middleRows<6>(3 * el) = sh.element_block(el).transpose();
      nodal_t_.push_back(std::move(t));
    }
    shape_direction_.emplace_back(model.member(member).cos, model.member(member).sin);
    return static_cast<Index>(shapes_.size() - 1);
  };

  for (Index i = 0; i < D_; ++i) {
    const Damper& d = dampers_[static_cast<std::size_t>(i)];
    const Index s = shapes_for(d.member);
    const Shapes& sh = shapes_[static_cast<std::size_t>(s)];
    if (!(d.contact_coordinate >= Scalar(0) && d.contact_coordinate <= sh.length()))
      detail::throw_invalid("PointDamper[" + std::to_string(i) + "]",
                            "contact_coordinate must lie on member " + std::to_string(d.member) +
                                " (valid range [0, " + detail::format_value(sh.length()) + "])",
                            d.contact_coordinate);
    damper_shape_.push_back(s);
    has_stick_.push_back(detail::law_has_stick_state(d.law));
    // A CoulombLaw's kinetic coefficient does not depend on the speed: read once here, so
    // that the slip rows need no dispatch on the law.
    kinetic_constant_.push_back(detail::with_law(d.law, [](const auto& l) -> Scalar {
      if constexpr (std::is_same_v<std::decay_t<decltype(l)>, CoulombLaw<Scalar>>)
        return l.kinetic_coefficient(Scalar(0));
      else
        return std::numeric_limits<Scalar>::quiet_NaN();
    }));
    inertial_.push_back(options_.normal_load == NormalLoad::Inertial && d.normal_load == NormalLoad::Inertial);
    if (d.separation == Separation::Separate) {  // N must be able to reach zero, and be watched
      const std::string where = "PointDamper[" + std::to_string(i) + "]";
      if (!inertial_.back())
        detail::throw_invalid(where, "separation = Separate needs an inertial normal load (a constant N never "
                                     "reaches zero): PointDamper::normal_load and ModelOptions::normal_load "
                                     "must be Inertial", std::string("normal_load Constant"));
      if (!options_.watch_lift_off)
        detail::throw_invalid(where, "separation = Separate needs ModelOptions::watch_lift_off = true (an "
                                     "unwatched normal force never separates the damper)",
                              std::string("watch_lift_off = false"));
    }
    const bool separable = d.separation == Separation::Separate && watch_lift_off(i);
    flight_slot_.push_back(separable ? num_separable_++ : Index(-1));
    const MemberEnd fallback = options_.end_policy == EndPolicy::Throw ? MemberEnd::Stop : MemberEnd::Extend;
    const auto resolved = [&](MemberEnd e) { return e == MemberEnd::Default ? fallback : e; };
    end_kind_.push_back({resolved(d.start_end), resolved(d.finish_end)});
    has_impacts_ = has_impacts_ || separable || end_kind_.back()[0] == MemberEnd::Wall ||
                   end_kind_.back()[1] == MemberEnd::Wall;
    has_walls_ = has_walls_ || (moving_[static_cast<std::size_t>(i)] &&
                                (end_kind_.back()[0] == MemberEnd::Wall || end_kind_.back()[1] == MemberEnd::Wall));
  }

  load_psi_.resize(n_, static_cast<Index>(loads_.size()));
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    const Load& load = loads_[l];
    load.validate(static_cast<Index>(l));
    const std::size_t s = static_cast<std::size_t>(shapes_for(load.member));
    load_psi_.col(static_cast<Index>(l)) = load_vector(s, load);
  }

  allocate_workspace();
  // Fixed contact points: the shapes never change; evaluate them once.
  for (Index i = 0; i < D_; ++i)
    if (!moving_[static_cast<std::size_t>(i)])
      evaluate_shapes(i, dampers_[static_cast<std::size_t>(i)].contact_coordinate);
}

template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::allocate_workspace() {
  const Index D2 = 2 * D_;
  values_.resize(static_cast<std::size_t>(D_));
  cursors_.assign(static_cast<std::size_t>(D_), ElementCursor{});
  for (auto& v : values_) v.resize(n_);
  C_.setZero(n_, D2);
  dpsi_w_.setZero(n_, D_);
  S_.setZero(D2, D2);
  key_.setZero(4 * D2);
  shapes_X_.setConstant(D_, std::numeric_limits<Scalar>::quiet_NaN());  // nothing evaluated yet
  factor_key_.setZero(4 * D2);
  factor_unknowns_ = -1;
  lu_sized_.assign(static_cast<std::size_t>(D2 + 1), Eigen::PartialPivLU<Matrix>());
  rhs_.setZero(D2);
  r0_.setZero(n_);
  for (Vector* v : {&b_n_, &res_n_, &dz_n_}) v->setZero(n_);
  for (Vector* v : {&b_u_, &res_u_, &dz_u_}) v->setZero(D2);
  d_.setZero(D_);
  mu_.setZero(D_);
  // (rows n..padded_order(n) stay zero: the fixed-size mode-space form reads K = padded_order(n)
  // rows of every column for n <= 8; everything else reads and writes the first n)
  F_.setZero(padded_order(n_), D2);
  L_.setZero(padded_order(n_), D2);
  A_.setZero(D2);
  c_.setZero(D2);
  u_.setZero(D2);
  unknown_of_.assign(static_cast<std::size_t>(D2), 0);
  slip_b_.setZero(n_, D_);
  Mn_.setZero(n_, n_);
  lun_ = Eigen::PartialPivLU<Matrix>(n_);
  eval_.qdd.setZero(n_);
  for (Vector* v : {&eval_.N, &eval_.f, &eval_.V, &eval_.Vdot, &eval_.xdd, &eval_.X, &eval_.slope, &eval_.y, &eval_.gap,
                    &eval_.wall_force})
    v->setZero(D_);
  flying_.assign(static_cast<std::size_t>(D_), 0);
  impacts_.reserve(has_impacts_ ? 1024 : 0);
  if (has_impacts_) {  // the impulse response of transition() works in the probe workspace
    allocate_linear_part_workspace();
    response_.setZero(n_, 2);
    response_x_.setZero(D_, 2);
    impulse_dir_.setZero(n_, 2);
  }
  cache_x_.resize(0);
  events_.reserve(1024);
  involved_.reserve(static_cast<std::size_t>(D_));
}

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::load_vector(std::size_t shape,
                                                                    const Load& load) const -> Vector {
  const Shapes& shapes = shapes_[shape];
  if (!shapes.contains(load.coordinate))
    detail::throw_invalid("PointLoad", "coordinate must lie on member " + std::to_string(load.member) +
                                           " (valid range [0, " + detail::format_value(shapes.length()) + "])",
                          load.coordinate);
  const typename Shapes::Values v = shapes.evaluate(load.coordinate);
  return load_direction_row(v, shape_direction_[shape].first, shape_direction_[shape].second, load.direction);
}

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::point_shape(MemberId member, Scalar eps,
                                                                    LoadDirection direction) const -> Vector {
  for (std::size_t s = 0; s < shape_members_.size(); ++s)
    if (shape_members_[s] == member) {
      Load probe;
      probe.member = member;
      probe.coordinate = eps;
      probe.direction = direction;
      return load_vector(s, probe);
    }
  detail::throw_invalid("FrictionDampedSystem::point_shape", "no damper or load on member", member);
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::step_rates() const -> std::vector<StepRate<Scalar>> {
  using std::sqrt;
  using C = std::complex<Scalar>;
  std::vector<StepRate<Scalar>> rates;
  // Roots of lambda^2 + 2 sigma lambda + w^2 = 0 (w > 0 or sigma > 0): the upper one of a
  // complex pair, both when real (critically damped or more; the slow one as w^2 / the stiff
  // one, without the cancellation of -sigma + sqrt(sigma^2 - w^2)).
  auto add_roots = [&rates](Scalar sigma, Scalar w, const std::string& source) {
    if (sigma < w) {
      rates.push_back({C(-sigma, sqrt(w * w - sigma * sigma)), source});
    } else {
      const Scalar stiff = -sigma - sqrt((sigma - w) * (sigma + w));
      rates.push_back({C(stiff, Scalar(0)), source});
      rates.push_back({C(w * w / stiff, Scalar(0)), source});
    }
  };
  for (Index j = 0; j < n_; ++j) {
    const std::string name = "mode " + std::to_string(j + 1);
    const Scalar w = sqrt(omega2_[j]), c = modal_damping_[j];
    if (!(w > 0)) {  // rigid-body mode q'' + c q' = 0: rates 0 and -c
      if (c > 0) rates.push_back({C(-c, Scalar(0)),
                                 name + " (rigid-body, damping c = " + detail::format_value(c) + " 1/s)"});
      continue;
    }
    std::string source = name + " (" + detail::format_frequency(w);
    if (c > 0) source += ", zeta " + detail::format_value(c / (Scalar(2) * w));
    add_roots(c / Scalar(2), w, source + ")");
  }
  // Regularised dampers: c_i = mu_i'(0) N0_i (the friction force's slope at V = 0) and beta_i,
  // the largest |psi_u|^2 the contact can see: at X0 for a fixed contact, else the largest at the
  // member's nodes (psi_u is linear on each element, so |psi_u|^2 is convex there).
  std::vector<Scalar> slope(dampers_.size(), Scalar(0));
  Scalar member_sum = 0;  // sum_j c_j beta_j
  for (std::size_t i = 0; i < dampers_.size(); ++i) {
    const Damper& d = dampers_[i];
    slope[i] = detail::with_law(d.law, [](const auto& l) -> Scalar {
      if constexpr (std::decay_t<decltype(l)>::has_stick_state)
        return Scalar(0);
      else
        return l.coefficient_derivative(Scalar(0));
    }) * d.preload;
    if (!(slope[i] > 0)) continue;
    const std::size_t s = static_cast<std::size_t>(damper_shape_[i]);
    Scalar beta = 0;
    if (options_.moving_contact) {
      const Matrix& t = nodal_t_[s];
      for (Index k = 0; k < t.rows(); k += 3) beta = std::max(beta, t.row(k).squaredNorm());
    } else {
      beta = shapes_[s].evaluate(d.contact_coordinate).psi_u.squaredNorm();
    }
    member_sum += slope[i] * beta;
  }
  for (std::size_t i = 0; i < dampers_.size(); ++i) {
    const Damper& d = dampers_[i];
    const std::string name = "damper " + std::to_string(i);
    const Scalar w = sqrt(d.effective_stiffness() / d.effective_mass());
    if (w > 0) rates.push_back({C(Scalar(0), w),
                               name + " slip oscillator sqrt(k/m) (" + detail::format_frequency(w) + ")"});
    if (flight_slot_[i] >= 0)  // separated: y_d'' = N0/m, a double integrator
      rates.push_back({C(Scalar(0), Scalar(0)), name + " flight y_d'' = N0/m (rate 0)"});
    if (!(slope[i] > 0)) continue;
    const Scalar two_sigma = slope[i] / d.effective_mass() + member_sum;
    add_roots(two_sigma / Scalar(2), w,
              name + " regularised friction slope mu'(0) N0 / m + sum mu'(0) N0 |psi_u|^2 = " +
                  detail::format_value(two_sigma) + " 1/s");
  }
  return rates;
}

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::linear_rates() const -> std::vector<std::complex<Scalar>> {
  std::vector<std::complex<Scalar>> rates;
  for (const auto& r : step_rates()) rates.push_back(r.lambda);
  return rates;
}

}  // namespace stickslip
