#pragma once
/// \file runge_kutta4.hpp
/// \brief Classical fixed-step Runge-Kutta method of order 4 (the paper's integrator), with a
/// cubic Hermite dense output between step ends.

#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>

namespace stickslip {

/// Method tag: classical Runge-Kutta, order 4, fixed step `StepperOptions::fixed_step`.
/// Four right-hand-side evaluations per step (f at the step end is the next step's k1).
/// Dense output: cubic Hermite interpolation of x and f at the step ends (order 3, local
/// error O(h^4)). Use it as the reference point of the paper; prefer DormandPrince54 otherwise.
struct RungeKutta4 {
  /// Fixed step StepperOptions::fixed_step: no error estimate.
  static constexpr bool adaptive = false;
  /// Order of the method.
  static constexpr int order = 4;
  static constexpr int error_order = 4;  ///< unused: no error estimate, no step control
  /// Name of the method in reports.
  static constexpr const char* name = "RungeKutta4";

  /// Stage workspace and step of the method for one system type.
  template <class System>
  class Core {
   public:
    /// Floating-point type of the system.
    using Scalar = typename System::Scalar;
    /// Continuous state type of the system.
    using State = typename System::State;
    /// Discrete mode type of the system.
    using Mode = typename System::Mode;

    /// Size the workspace like `prototype` (allocates only for dynamic sizes, once).
    void initialize(const State& prototype) {
      k2_.resizeLike(prototype);
      k3_.resizeLike(prototype);
      k4_.resizeLike(prototype);
      xs_.resizeLike(prototype);
    }
    /// A new step start point (or a new mode) follows; nothing is cached across points.
    void new_point() noexcept {}

    /// One step x1 = x0 + h/6 (k1 + 2 k2 + 2 k3 + k4) with k1 = f0; writes f1 = f(t + h, x1).
    /// Returns 0 (no error estimate).
    Scalar step(System& sys, const Mode& m, Scalar t, const State& x0, const State& f0, Scalar h,
                State& x1, State& f1, Scalar /*rtol*/, Scalar /*atol*/, StepperStats& stats) {
      const Scalar h2 = h / Scalar(2);
      xs_.noalias() = x0 + h2 * f0;
      sys.rhs(m, t + h2, xs_, k2_);
      xs_.noalias() = x0 + h2 * k2_;
      sys.rhs(m, t + h2, xs_, k3_);
      xs_.noalias() = x0 + h * k3_;
      sys.rhs(m, t + h, xs_, k4_);
      x1.noalias() = x0 + (h / Scalar(6)) * (f0 + Scalar(2) * (k2_ + k3_) + k4_);
      sys.rhs(m, t + h, x1, f1);
      stats.rhs_evaluations += 4;
      return Scalar(0);
    }

    /// Cubic Hermite interpolant at t0 + theta h from (x0, f0) and (x1, f1), theta in [0, 1].
    void dense(Scalar theta, Scalar h, const State& x0, const State& f0, const State& x1,
               const State& f1, State& out) const {
      const Scalar t2 = theta * theta, t3 = t2 * theta;
      const Scalar h00 = Scalar(2) * t3 - Scalar(3) * t2 + Scalar(1);
      const Scalar h10 = t3 - Scalar(2) * t2 + theta;
      const Scalar h01 = Scalar(3) * t2 - Scalar(2) * t3;
      const Scalar h11 = t3 - t2;
      out.noalias() = h00 * x0 + h01 * x1 + (h * h10) * f0 + (h * h11) * f1;
    }

   private:
    State k2_, k3_, k4_, xs_;
  };
};

}  // namespace stickslip
