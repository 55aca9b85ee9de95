#pragma once
/// \file rosenbrock23.hpp
/// \brief Linearly implicit, L-stable Rosenbrock (W-) method of order 2 with an order-3 error
/// estimate and a continuous extension (Shampine & Reichelt, "The MATLAB ODE suite", SIAM J. Sci.
/// Comput. 18, 1997: ode23s), for stiff modes.

#include <stickslip/ode/detail/step_control.hpp>
#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
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
}  // namespace detail

/// Method tag: Rosenbrock 2(3) of Shampine & Reichelt (ode23s), d = 1/(2 + sqrt 2):
///
///     W = I - h d J,  k1 = W^-1 (f0 + h d T),  k2 = W^-1 (f(t + h/2, x0 + h/2 k1) - k1) + k1,
///     x1 = x0 + h k2,  k3 = W^-1 (f1 - (6 + sqrt 2)(k2 - F1) - 2 (k1 - f0) + h d T),
///     err = h/6 (k1 - 2 k2 + k3),
///
/// J = df/dx, T = df/dt (forward difference in t). Order 2, L-stable; two right-hand-side
/// evaluations per step, plus one LU factorisation per step-size change and one Jacobian per
/// step start point. J is the system's `jacobian(mode, t, x, J)` when it has one (J of type
/// Eigen::Matrix<Scalar, n, n>, n = State::RowsAtCompileTime), otherwise forward differences
/// (n extra evaluations). Dense output x0 + h (theta(1-theta) k1 + theta(theta-2d) k2)/(1-2d).
/// Choose it when retained modes reach frequencies far above those of interest (stiff).
struct Rosenbrock23 {
  static constexpr bool adaptive = true;
  static constexpr int order = 2;
  static constexpr int error_order = 2;  ///< the estimate is O(h^3): exponent 1/3
  static constexpr const char* name = "Rosenbrock23";

  /// Stage workspace, Jacobian and LU of W for one system type.
  template <class System>
  class Core {
   public:
    using Scalar = typename System::Scalar;
    using State = typename System::State;
    using Mode = typename System::Mode;
    static constexpr int N = State::RowsAtCompileTime;
    using Matrix = Eigen::Matrix<Scalar, N, N>;
    static constexpr bool user_jacobian = detail::has_jacobian<System, Matrix>::value;

    /// Size the workspace like `prototype` (allocates only for dynamic sizes, once).
    void initialize(const State& prototype) {
      const Eigen::Index n = prototype.size();
      for (State* v : {&k1_, &k2_, &k3_, &xs_, &f_half_, &ft_, &dfdt_, &rhs_}) {
        v->resizeLike(prototype);
      }
      jac_.resize(n, n);
      w_.resize(n, n);
      if (lu_.rows() != n) lu_ = Eigen::PartialPivLU<Matrix>(n);
      jac_valid_ = false;
      h_factored_ = Scalar(0);
    }
    /// The next step starts at a new point (or mode): the Jacobian is re-evaluated there.
    void new_point() noexcept { jac_valid_ = false; }

    /// One step of size h from (t, x0) with f0 = f(t, x0); writes x1, f1 = f(t + h, x1) and
    /// returns the weighted RMS norm of the error estimate.
    Scalar step(System& sys, const Mode& m, Scalar t, const State& x0, const State& f0, Scalar h,
                State& x1, State& f1, Scalar rtol, Scalar atol, StepperStats& stats) {
      const Scalar d = Scalar(1) / (Scalar(2) + std::sqrt(Scalar(2)));
      const Scalar e32 = Scalar(6) + std::sqrt(Scalar(2));
      if (!jac_valid_) {
        evaluate_jacobian(sys, m, t, x0, f0, rtol, atol, stats);
        jac_valid_ = true;
        h_factored_ = Scalar(0);
      }
      if (h != h_factored_) {
        w_ = -(h * d) * jac_;
        w_.diagonal().array() += Scalar(1);
        lu_.compute(w_);
        h_factored_ = h;
      }
      rhs_.noalias() = f0 + (h * d) * dfdt_;
      k1_.noalias() = lu_.solve(rhs_);
      xs_.noalias() = x0 + (h / Scalar(2)) * k1_;
      sys.rhs(m, t + h / Scalar(2), xs_, f_half_);
      rhs_.noalias() = f_half_ - k1_;
      k2_.noalias() = lu_.solve(rhs_);
      k2_ += k1_;
      x1.noalias() = x0 + h * k2_;
      sys.rhs(m, t + h, x1, f1);
      rhs_.noalias() = f1 - e32 * (k2_ - f_half_) - Scalar(2) * (k1_ - f0) + (h * d) * dfdt_;
      k3_.noalias() = lu_.solve(rhs_);
      stats.rhs_evaluations += 2;
      xs_.noalias() = (h / Scalar(6)) * (k1_ - Scalar(2) * k2_ + k3_);
      return detail::weighted_rms(xs_, x0, x1, rtol, atol);
    }

    /// Continuous extension at t0 + theta h, theta in [0, 1] (order 2).
    void dense(Scalar theta, Scalar h, const State& x0, const State&, const State&, const State&,
               State& out) const {
      const Scalar d = Scalar(1) / (Scalar(2) + std::sqrt(Scalar(2)));
      const Scalar s = h / (Scalar(1) - Scalar(2) * d);
      out.noalias() = x0 + (s * theta * (Scalar(1) - theta)) * k1_ +
                      (s * theta * (theta - Scalar(2) * d)) * k2_;
    }

   private:
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
      const Scalar dt = root_eps * std::max(abs(t), Scalar(1));
      sys.rhs(m, t + dt, x0, ft_);
      dfdt_.noalias() = (ft_ - f0) / dt;
      stats.rhs_evaluations += 1;
      stats.jacobian_evaluations += 1;
    }

    State k1_, k2_, k3_, xs_, f_half_, ft_, dfdt_, rhs_;
    Matrix jac_, w_;
    Eigen::PartialPivLU<Matrix> lu_;
    bool jac_valid_ = false;
    Scalar h_factored_ = 0;
  };
};

}  // namespace stickslip
