#pragma once
/// \file variational_system.hpp
/// \brief VariationalSystem: a hybrid system together with its variational equations, whose
/// sensitivity matrix jumps by the saltation matrix at every event.

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/hybrid_system.hpp>
#include <stickslip/ode/rosenbrock23.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>
#include <utility>

namespace stickslip {

namespace detail {
template <class S, class = void>
struct has_reset_jacobian : std::false_type {};
template <class S>
struct has_reset_jacobian<
    S, std::void_t<decltype(std::declval<S&>().reset_jacobian(
           std::declval<const typename S::Mode&>(), std::declval<const TriggeredGuards&>(),
           std::declval<typename S::Scalar>(), std::declval<const typename S::State&>(),
           std::declval<Eigen::Matrix<typename S::Scalar, Eigen::Dynamic, Eigen::Dynamic>&>()))>>
    : std::true_type {};
}  // namespace detail

/// True when S supplies `reset_jacobian(from, which, t, x_before, R)`: R = dx+/dx- of the state
/// reset its transition applies (n x n, dynamic), for the mode `from` and the guards `which`.
template <class S>
inline constexpr bool has_reset_jacobian_v = detail::has_reset_jacobian<S>::value;

/// The hybrid system (x, Phi) of a hybrid system `System` and its variational equations:
///
///     x' = f_m(t, x),   Phi' = (df_m/dx)(t, x) Phi,
///
/// with the state stored as X = [x; vec(Phi)] (Phi column-major, n x n). At an event of the guard
/// g (the first one that fired), with x- and f- = f_m-(t, x-) before and x+ = r(x-),
/// f+ = f_m+(t, x+) after the transition, Phi jumps by the saltation matrix
///
///     S = R + (f+ - R f-) g_x^T / (g_x^T f- + g_t),   Phi+ = S Phi-,   R = dr/dx-
///
/// (Aizerman & Gantmacher 1958; Leine & Nijmeijer, Dynamics and Bifurcations of Non-Smooth
/// Mechanical Systems, 2004, Sec. 7.2). A stick entry that puts the velocity onto the surface
/// (x'+ = v_belt) has a zero row in R: S collapses the sensitivities onto the stick manifold.
///
/// Where the pieces come from:
///  - df/dx: the system's `jacobian(mode, t, x, J)` when it has one (has_jacobian_v), else central
///    differences of rhs with h_j = fd_step * max(1, |x_j|) (2 n evaluations);
///  - g_x, g_t: central differences of the guard that fired (in the mode before the event);
///  - R: the system's `reset_jacobian(from, which, t, x-, R)` when it has one
///    (has_reset_jacobian_v), else central differences of `transition` on a copy of the system
///    made at construction (System must then be copy-constructible, and its transition a function
///    of (mode, which, t, x)); a perturbation that changes the mode after the transition is not
///    used (one-sided then; the identity column when both sides change the mode).
/// A grazing event (|g_x^T f- + g_t| below 1e-12 (|g_x| |f-| + |g_t|)) keeps S = R and is
/// counted in grazing_events(). The transition of the wrapped system itself runs once per event,
/// as in a plain run.
template <class System>
class VariationalSystem {
  static_assert(is_hybrid_system_v<System>,
                "VariationalSystem: System must model the hybrid system concept (docs/ode.md)");
  static_assert(has_reset_jacobian_v<System> || std::is_copy_constructible_v<System>,
                "VariationalSystem: System needs reset_jacobian(from, which, t, x, R) or a copy "
                "constructor (finite differences of transition on a copy)");

 public:
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// Discrete mode of the wrapped system.
  using Mode = typename System::Mode;
  /// State of the wrapped system.
  using BaseState = typename System::State;
  /// Augmented state [x; vec(Phi)].
  using State = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Dynamic matrix (Phi, S, R, df/dx).
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// Wraps `system` (kept by reference) with state size n; fd_step is the relative step of the
  /// finite differences. With control_sensitivities = false, Phi is left out of the step's error
  /// control (controlled_size() = n: the steps are those of a plain run of x). Throws
  /// std::invalid_argument for n <= 0 or fd_step outside (0, 0.1).
  VariationalSystem(System& system, Eigen::Index n, Scalar fd_step, bool control_sensitivities = true)
      : sys_(system), n_(n), fd_(fd_step), control_(control_sensitivities) {
    if (n <= 0) detail::throw_invalid("VariationalSystem", "n must be > 0", n);
    if (!(fd_step > 0 && fd_step < Scalar(0.1)))
      detail::throw_invalid("VariationalSystem", "fd_step must be in (0, 0.1)", fd_step);
    if constexpr (!has_reset_jacobian_v<System>) copy_.emplace(system);
    for (BaseState* v : {&xb_, &fb_, &xp_, &fp_, &fm_, &xm_, &fminus_, &fplus_, &xr_})
      v->resize(n);
    J_.resize(n, n);
    R_.resize(n, n);
    S_.resize(n, n);
    tmp_.resize(n, n);
    gx_.resize(n);
  }

  /// The augmented initial state [x0; vec(I)].
  State initial_state(const BaseState& x0) const {
    State X = State::Zero(n_ + n_ * n_);
    X.head(n_) = x0;
    sensitivity(X).setIdentity();
    return X;
  }
  /// Phi as a view of the augmented state X.
  Eigen::Map<Matrix> sensitivity(State& X) const { return {X.data() + n_, n_, n_}; }
  /// Phi as a read-only view of the augmented state X.
  Eigen::Map<const Matrix> sensitivity(const State& X) const { return {X.data() + n_, n_, n_}; }

  /// Number of leading components of [x; vec(Phi)] under the error control of an adaptive step
  /// (DormandPrince54): all, or only x when the sensitivities are left out.
  Eigen::Index controlled_size() const noexcept { return control_ ? n_ + n_ * n_ : n_; }

  /// Events whose guard was (nearly) tangent to the flow: S = R was used.
  long grazing_events() const { return grazing_; }

  /// x' = f(t, x), Phi' = (df/dx) Phi.
  void rhs(const Mode& m, Scalar t, const State& X, State& dX) {
    xb_ = X.head(n_);
    sys_.rhs(m, t, xb_, fb_);
    dX.head(n_) = fb_;
    jacobian(m, t, xb_, J_);
    Eigen::Map<Matrix>(dX.data() + n_, n_, n_).noalias() = J_ * sensitivity(X);
  }
  /// The wrapped system's guard count in mode m.
  Eigen::Index num_guards(const Mode& m) const { return sys_.num_guards(m); }
  /// The wrapped system's guards at x = X.head(n).
  void guards(const Mode& m, Scalar t, const State& X, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& g) {
    xb_ = X.head(n_);
    sys_.guards(m, t, xb_, g);
  }
  /// The wrapped system's guard directions.
  CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    return sys_.guard_direction(m, i);
  }
  /// The wrapped system's transition on x, and Phi+ = S Phi- (see the class comment).
  TransitionAction transition(Mode& m, const TriggeredGuards& which, Scalar t, State& X);

 private:
  void jacobian(const Mode& m, Scalar t, const BaseState& x, Matrix& J);
  Scalar step_for(Scalar v) const { return fd_ * std::max(Scalar(1), std::abs(v)); }
  // For each component j: value(x + h e_j, true), value(x - h e_j, false), then column(j, 2 h).
  template <class Value, class Column>
  void central_differences(const BaseState& x, Value&& value, Column&& column) {
    xp_ = x;
    for (Eigen::Index j = 0; j < n_; ++j) {
      const Scalar h = step_for(x[j]);
      xp_[j] = x[j] + h;
      value(xp_, true);
      xp_[j] = x[j] - h;
      value(xp_, false);
      xp_[j] = x[j];
      column(j, Scalar(2) * h);
    }
  }
  void guard_gradient(const Mode& m, Eigen::Index i, Scalar t, const BaseState& x, Scalar& gt);
  void reset_jacobian(const Mode& from, const TriggeredGuards& which, Scalar t, const Mode& to);

  System& sys_;
  std::optional<System> copy_;
  Eigen::Index n_;
  Scalar fd_;
  bool control_;
  long grazing_ = 0;
  BaseState xb_, fb_, xp_, fp_, fm_, xm_, fminus_, fplus_, xr_;
  Matrix J_, R_, S_, tmp_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> gx_, gp_, gm_;
  using Fixed = Eigen::Matrix<Scalar, BaseState::RowsAtCompileTime, BaseState::RowsAtCompileTime>;
  Fixed jfixed_;
};

template <class System>
void VariationalSystem<System>::jacobian(const Mode& m, Scalar t, const BaseState& x, Matrix& J) {
  if constexpr (has_jacobian_v<System>) {
    jfixed_.resize(n_, n_);
    sys_.jacobian(m, t, x, jfixed_);
    J = jfixed_;
  } else {
    central_differences(
        x, [&](const BaseState& xq, bool plus) { sys_.rhs(m, t, xq, plus ? fp_ : fm_); },
        [&](Eigen::Index j, Scalar width) { J.col(j) = (fp_ - fm_) / width; });
  }
}

template <class System>
void VariationalSystem<System>::guard_gradient(const Mode& m, Eigen::Index i, Scalar t,
                                               const BaseState& x, Scalar& gt) {
  const Eigen::Index ng = sys_.num_guards(m);
  gp_.resize(ng);
  gm_.resize(ng);
  central_differences(
      x, [&](const BaseState& xq, bool plus) { sys_.guards(m, t, xq, plus ? gp_ : gm_); },
      [&](Eigen::Index j, Scalar width) { gx_[j] = (gp_[i] - gm_[i]) / width; });
  const Scalar h = step_for(t);
  sys_.guards(m, t + h, x, gp_);
  sys_.guards(m, t - h, x, gm_);
  gt = (gp_[i] - gm_[i]) / (Scalar(2) * h);
}

template <class System>
void VariationalSystem<System>::reset_jacobian(const Mode& from, const TriggeredGuards& which,
                                               Scalar t, const Mode& to) {
  if constexpr (has_reset_jacobian_v<System>) {
    static_cast<void>(to);
    sys_.reset_jacobian(from, which, t, xm_, R_);
  } else {
    System& copy = *copy_;
    for (Eigen::Index j = 0; j < n_; ++j) {
      const Scalar h = step_for(xm_[j]);
      Mode mp = from, mm = from;
      xp_ = xm_;
      xp_[j] += h;
      copy.transition(mp, which, t, xp_);
      xr_ = xm_;
      xr_[j] -= h;
      copy.transition(mm, which, t, xr_);
      const bool plus = mp == to, minus = mm == to;
      if (plus && minus) {
        R_.col(j) = (xp_ - xr_) / (Scalar(2) * h);
      } else if (plus || minus) {
        // one side: the nominal reset of the copy, then a one-sided difference
        Mode m0 = from;
        fp_ = xm_;
        copy.transition(m0, which, t, fp_);
        R_.col(j) = plus ? BaseState((xp_ - fp_) / h) : BaseState((fp_ - xr_) / h);
      } else {
        R_.col(j).setZero();
        R_(j, j) = Scalar(1);
      }
    }
  }
}

template <class System>
TransitionAction VariationalSystem<System>::transition(Mode& m, const TriggeredGuards& which,
                                                       Scalar t, State& X) {
  xm_ = X.head(n_);
  const Mode from = m;
  sys_.rhs(from, t, xm_, fminus_);
  Scalar gt = 0;
  const bool has_guard = !which.empty();
  if (has_guard) guard_gradient(from, which.front(), t, xm_, gt);
  xb_ = xm_;
  TransitionAction action = sys_.transition(m, which, t, xb_);
  X.head(n_) = xb_;
  if (action.stop) return action;
  sys_.rhs(m, t, xb_, fplus_);
  reset_jacobian(from, which, t, m);
  S_ = R_;
  if (has_guard) {
    const Scalar denom = gx_.dot(fminus_) + gt;
    const Scalar scale = gx_.norm() * fminus_.norm() + std::abs(gt);
    if (std::abs(denom) > Scalar(1e-12) * scale && scale > 0) {
      fp_ = fplus_ - R_ * fminus_;
      S_.noalias() += (fp_ / denom) * gx_.transpose();
    } else {
      ++grazing_;
    }
  } else {
    ++grazing_;
  }
  auto Phi = sensitivity(X);
  tmp_.noalias() = S_ * Phi;
  Phi = tmp_;
  return action;
}

}  // namespace stickslip
