#pragma once
/// \file rosenbrock23.hpp
/// \brief Linearly implicit, L-stable Rosenbrock (W-) method of order 2 with an order-3 error
/// estimate and a continuous extension (Shampine & Reichelt, "The MATLAB ODE suite", SIAM J. Sci.
/// Comput. 18, 1997: ode23s), for stiff modes; optional user Jacobian and df/dt, and reuse of the
/// Jacobian and of the LU factors across accepted steps.

#include <stickslip/ode/detail/step_control.hpp>
#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

namespace stickslip {

namespace detail {
template <class S, class J, class = void>
struct has_jacobian : std::false_type {};
template <class S, class J>
struct has_jacobian<S, J,
                    std::void_t<decltype(std::declval<S&>().jacobian(
                        std::declval<const typename S::Mode&>(),
                        std::declval<typename S::Scalar>(),
                        std::declval<const typename S::State&>(), std::declval<J&>()))>>
    : std::true_type {};

template <class S, class = void>
struct has_time_derivative : std::false_type {};
template <class S>
struct has_time_derivative<
    S, std::void_t<decltype(std::declval<S&>().time_derivative(
           std::declval<const typename S::Mode&>(), std::declval<typename S::Scalar>(),
           std::declval<const typename S::State&>(), std::declval<typename S::State&>()))>>
    : std::true_type {};
}  // namespace detail

/// True when S supplies `jacobian(mode, t, x, J)`, J = df/dx as Eigen::Matrix<Scalar, n, n>.
template <class S>
inline constexpr bool has_jacobian_v =
    detail::has_jacobian<S, Eigen::Matrix<typename S::Scalar, S::State::RowsAtCompileTime,
                                          S::State::RowsAtCompileTime>>::value;

/// True when S supplies `time_derivative(mode, t, x, dfdt)`, dfdt = df/dt at fixed x.
template <class S>
inline constexpr bool has_time_derivative_v = detail::has_time_derivative<S>::value;

/// When Rosenbrock23 evaluates the Jacobian J = df/dx (and T = df/dt) and factorises I - h d J.
enum class JacobianUpdate : std::uint8_t {
  /// J and T at every step start point; a new LU whenever h changes (the classical method,
  /// `Rosenbrock23`).
  EveryStep,
  /// J and T kept across accepted steps (`Rosenbrock23Reuse`). Re-evaluated at a mode start,
  /// to retry a rejected step, and when the kept J no longer linearises f along the first stage:
  /// |h d (f(t + h/2, x0 + h/2 k1) - f0 - h/2 (T + J k1))| > 0.01 |h/2 k1| (weighted RMS; the
  /// step is then redone with the new J). The LU of I - h_f d J is kept while
  /// h_f / h lies in [0.93, 1.1]. For modes whose f is linear or nearly so in the stiff
  /// directions; see docs/ode.md for where it wins and where it loses.
  Reuse
};

/// Method tag: Rosenbrock 2(3) of Shampine & Reichelt (ode23s), d = 1/(2 + sqrt 2):
///
///     W = I - h d J,  k1 = W^-1 (f0 + h d T),  k2 = W^-1 (f(t + h/2, x0 + h/2 k1) - k1) + k1,
///     x1 = x0 + h k2,  k3 = W^-1 (f1 - (6 + sqrt 2)(k2 - F1) - 2 (k1 - f0) + h d T),
///     err = h/6 (k1 - 2 k2 + k3),
///
/// J = df/dx, T = df/dt. Order 2, L-stable with the exact J; two right-hand-side evaluations per
/// step plus, when J is (re-)evaluated, the system's `jacobian(mode, t, x, J)` (J of type
/// Eigen::Matrix<Scalar, n, n>, n = State::RowsAtCompileTime) or forward differences (n extra
/// evaluations), and the system's `time_derivative(mode, t, x, T)` or a forward difference in t
/// (one extra evaluation). The two-stage formula is a W-method (Steihaug & Wolfbrandt 1979; any
/// matrix in place of J keeps order 2), which `Update = Reuse` exploits; the order-3 error
/// estimate and L-stability hold only with the exact J. Dense output
/// x0 + h (theta(1-theta) k1 + theta(theta-2d) k2)/(1-2d).
/// Choose it when retained modes reach frequencies far above those of interest (stiff).
template <JacobianUpdate Update>
struct BasicRosenbrock23 {
  /// Adaptive step: the embedded error estimate controls the step (rtol, atol).
  static constexpr bool adaptive = true;
  /// Order of the propagated solution.
  static constexpr int order = 2;
  static constexpr int error_order = 2;  ///< the estimate is O(h^3): exponent 1/3
  /// Name of the method in reports ("Rosenbrock23" or "Rosenbrock23Reuse").
  static constexpr const char* name =
      Update == JacobianUpdate::Reuse ? "Rosenbrock23Reuse" : "Rosenbrock23";
  /// When the Jacobian is formed (template parameter `Update`).
  static constexpr JacobianUpdate jacobian_update = Update;

  /// Stage workspace, Jacobian and LU of W for one system type.
  template <class System>
  class Core {
   public:
    /// Floating-point type of the system.
    using Scalar = typename System::Scalar;
    /// Continuous state type of the system.
    using State = typename System::State;
    /// Discrete mode type of the system.
    using Mode = typename System::Mode;
    /// State size at compile time, or Eigen::Dynamic.
    static constexpr int N = State::RowsAtCompileTime;
    /// Jacobian and iteration matrix W, N x N.
    using Matrix = Eigen::Matrix<Scalar, N, N>;
    /// The system supplies jacobian(); else finite differences of rhs().
    static constexpr bool user_jacobian = has_jacobian_v<System>;
    /// The system supplies time_derivative(); else a finite difference of rhs() in t.
    static constexpr bool user_time_derivative = has_time_derivative_v<System>;

    /// Size the workspace like `prototype` (allocates only for dynamic sizes, once).
    void initialize(const State& prototype) {
      const Eigen::Index n = prototype.size();
      for (State* v : {&k1_, &k2_, &k3_, &xs_, &f_half_, &ft_, &dfdt_, &rhs_}) {
        v->resizeLike(prototype);
      }
      jac_.resize(n, n);
      w_.resize(n, n);
      if (lu_.rows() != n) lu_ = Eigen::PartialPivLU<Matrix>(n);
      new_mode();
    }
    /// A mode starts (run start or after a transition): J and T are re-evaluated there.
    void new_mode() noexcept {
      jac_valid_ = false;
      new_point();
    }
    /// The previous step was accepted; the next one starts at its end point.
    void new_point() noexcept {
      jac_current_ = false;
      retry_ = false;
    }

    /// One step of size h from (t, x0) with f0 = f(t, x0); writes x1, f1 = f(t + h, x1) and
    /// returns the weighted RMS norm of the error estimate.
    Scalar step(System& sys, const Mode& m, Scalar t, const State& x0, const State& f0, Scalar h,
                State& x1, State& f1, Scalar rtol, Scalar atol, StepperStats& stats) {
      const Scalar d = Scalar(1) / (Scalar(2) + std::sqrt(Scalar(2)));
      const Scalar e32 = Scalar(6) + std::sqrt(Scalar(2));
      // A second call from the same point after an error above 1 retries a rejected step.
      const bool after_rejection = retry_ && !(last_error_ <= Scalar(1));
      const bool stale = !jac_valid_ || (!jac_current_ && (Update == JacobianUpdate::EveryStep ||
                                                           after_rejection));
      if (stale) {
        evaluate_jacobian(sys, m, t, x0, f0, rtol, atol, stats);
        jac_valid_ = true;
        jac_current_ = true;
        h_factored_ = Scalar(0);
      }
      for (;;) {
        if (!lu_usable(h, after_rejection)) {
          w_ = -(h * d) * jac_;
          w_.diagonal().array() += Scalar(1);
          lu_.compute(w_);
          h_factored_ = h;
          ++stats.factorisations;
        }
        // W = I - h_f d J = I - h d (h_f / h) J: with a kept LU the step uses (h_f / h) J.
        rhs_.noalias() = f0 + (h_factored_ * d) * dfdt_;
        k1_.noalias() = lu_.solve(rhs_);
        xs_.noalias() = x0 + (h / Scalar(2)) * k1_;
        sys.rhs(m, t + h / Scalar(2), xs_, f_half_);
        stats.rhs_evaluations += 1;
        if (jac_current_ || linearisation_holds(h, x0, f0, rtol, atol)) break;
        evaluate_jacobian(sys, m, t, x0, f0, rtol, atol, stats);
        jac_current_ = true;
        h_factored_ = Scalar(0);
      }
      const Scalar hd = h_factored_ * d;
      rhs_.noalias() = f_half_ - k1_;
      k2_.noalias() = lu_.solve(rhs_);
      k2_ += k1_;
      x1.noalias() = x0 + h * k2_;
      sys.rhs(m, t + h, x1, f1);
      rhs_.noalias() = f1 - e32 * (k2_ - f_half_) - Scalar(2) * (k1_ - f0) + hd * dfdt_;
      k3_.noalias() = lu_.solve(rhs_);
      stats.rhs_evaluations += 1;
      xs_.noalias() = (h / Scalar(6)) * (k1_ - Scalar(2) * k2_ + k3_);
      last_error_ = detail::weighted_rms(xs_, x0, x1, rtol, atol);
      dense_d_ = hd / h;
      retry_ = true;
      return last_error_;
    }

    /// Continuous extension at t0 + theta h, theta in [0, 1] (order 2).
    void dense(Scalar theta, Scalar h, const State& x0, const State&, const State&, const State&,
               State& out) const {
      const Scalar s = h / (Scalar(1) - Scalar(2) * dense_d_);
      out.noalias() = x0 + (s * theta * (Scalar(1) - theta)) * k1_ +
                      (s * theta * (theta - Scalar(2) * dense_d_)) * k2_;
    }

   private:
    // A kept J (and T) still describes f along the first stage when the residual of the
    // linearisation, r = f(t + h/2, x0 + h/2 k1) - f0 - h/2 (T + J k1), moves the step by less
    // than c of the stage increment: |h d r| <= c |h/2 k1| (weighted RMS). With the exact J, r is
    // of second order in h k1. c = 0.01: with 0.1 the regularised friction oscillator ran with
    // errors of 7e-3 at rtol 1e-5 and 1.5e-3 at rtol 1e-7 (stale J across |v| ~ v_eps), 50x
    // EveryStep's; with 0.01, 2-4x (benchmarks/ode/rosenbrock_work_precision.cpp).
    bool linearisation_holds(Scalar h, const State& x0, const State& f0, Scalar rtol,
                             Scalar atol) {
      const Scalar c = Scalar(kLinearisationTolerance);
      const Scalar d = Scalar(1) / (Scalar(2) + std::sqrt(Scalar(2)));
      rhs_.noalias() = f_half_ - f0 - (h / Scalar(2)) * dfdt_;
      rhs_.noalias() -= (h / Scalar(2)) * (jac_ * k1_);
      rhs_ *= h * d;
      ft_.noalias() = (h / Scalar(2)) * k1_;
      return detail::weighted_rms(rhs_, x0, x0, rtol, atol) <=
             c * detail::weighted_rms(ft_, x0, x0, rtol, atol);
    }
    static constexpr double kLinearisationTolerance = 0.01;

    // Keep the LU of I - h_f d J for a step h when h = h_f, or (Reuse, not right after a
    // rejection) when a = h_f / h lies in [0.93, 1.1]: the method is then A-stable and its
    // damping at infinity |R(-inf)| = |1 - 2u + u^2/2|, u = 1/(a d), is at most 0.4 (0 at a = 1).
    bool lu_usable(Scalar h, bool after_rejection) const {
      if (!(h_factored_ > 0)) return false;
      if (h == h_factored_) return true;
      if (Update == JacobianUpdate::EveryStep || after_rejection) return false;
      const Scalar a = h_factored_ / h;
      return a >= Scalar(0.93) && a <= Scalar(1.1);
    }

    void evaluate_jacobian(System& sys, const Mode& m, Scalar t, const State& x0, const State& f0,
                           Scalar rtol, Scalar atol, StepperStats& stats) {
      using std::abs;
      using std::sqrt;
      const Scalar root_eps = sqrt(std::numeric_limits<Scalar>::epsilon());
      if constexpr (user_jacobian) {
        sys.jacobian(m, t, x0, jac_);
      } else {
        // Forward differences, column j perturbed by sqrt(eps) max(|x_j|, atol / rtol).
        const Scalar typical =
            rtol > 0 ? std::max(atol / rtol, std::numeric_limits<Scalar>::min()) : Scalar(1);
        xs_ = x0;
        for (Eigen::Index j = 0; j < x0.size(); ++j) {
          const Scalar xj = x0[j];
          xs_[j] = xj + root_eps * std::max(abs(xj), typical);
          const Scalar dx = xs_[j] - xj;
          sys.rhs(m, t, xs_, ft_);
          jac_.col(j) = (ft_ - f0) / dx;
          xs_[j] = xj;
        }
        stats.rhs_evaluations += x0.size();
      }
      if constexpr (user_time_derivative) {
        sys.time_derivative(m, t, x0, dfdt_);
      } else {
        const Scalar dt = root_eps * std::max(abs(t), Scalar(1));
        sys.rhs(m, t + dt, x0, ft_);
        dfdt_.noalias() = (ft_ - f0) / dt;
        stats.rhs_evaluations += 1;
      }
      stats.jacobian_evaluations += 1;
    }

    State k1_, k2_, k3_, xs_, f_half_, ft_, dfdt_, rhs_;
    Matrix jac_, w_;
    Eigen::PartialPivLU<Matrix> lu_;
    bool jac_valid_ = false;    // J and T belong to the current mode
    bool jac_current_ = false;  // ... and were evaluated at the current step start point
    bool retry_ = false;        // step() was called from the current start point already
    Scalar last_error_ = 0;
    Scalar h_factored_ = 0;
    Scalar dense_d_ = Scalar(1) / (Scalar(2) + std::sqrt(Scalar(2)));
  };
};

/// Rosenbrock23 with J and T at every step start point (the classical method; the default).
struct Rosenbrock23 : BasicRosenbrock23<JacobianUpdate::EveryStep> {};
/// Rosenbrock23 keeping J, T and the LU across accepted steps while they still apply.
struct Rosenbrock23Reuse : BasicRosenbrock23<JacobianUpdate::Reuse> {};

}  // namespace stickslip
