#pragma once
/// \file dormand_prince54.hpp
/// \brief Adaptive explicit Runge-Kutta pair of Dormand and Prince, order 5(4), with its
/// continuous extension of order 4.

#include <stickslip/ode/detail/step_control.hpp>
#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>

namespace stickslip {

/// Method tag: Dormand-Prince 5(4) (J. R. Dormand, P. J. Prince, J. Comput. Appl. Math. 6, 1980),
/// local extrapolation (the order-5 solution is propagated), FSAL: six new right-hand-side
/// evaluations per step. Error estimate of order 4 drives the step (exponent 1/5); over the first
/// `sys.controlled_size()` components only when the system has that member (detail::error_norm).
/// Dense output:
/// Hairer's order-4 continuous extension (local error O(h^5)), built only when an event or an
/// output sample needs it. The default method: non-stiff problems, tight tolerances.
struct DormandPrince54 {
  /// Adaptive step: the embedded error estimate controls the step (rtol, atol).
  static constexpr bool adaptive = true;
  /// Order of the propagated solution.
  static constexpr int order = 5;
  static constexpr int error_order = 4;  ///< the embedded estimate is O(h^5): exponent 1/5
  /// Name of the method in reports.
  static constexpr const char* name = "DormandPrince54";

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
      for (State* v : {&k_.k2, &k_.k3, &k_.k4, &k_.k5, &k_.k6, &k_.xs, &r3_, &r5_})
        v->resizeLike(prototype);
    }
    /// A new step start point (or a new mode) follows; nothing is cached across points.
    void new_point() noexcept {}

    /// One step of size h from (t, x0) with k1 = f0; writes x1 and f1 = f(t + h, x1) (= k7) and
    /// returns the weighted RMS norm of the embedded error estimate.
    Scalar step(System& sys, const Mode& m, Scalar t, const State& x0, const State& f0, Scalar h,
                State& x1, State& f1, Scalar rtol, Scalar atol, StepperStats& stats) {
      stats.rhs_evaluations += 6;
      dense_ready_ = false;
      if constexpr (!stages_in_registers) {
        return stages(sys, m, t, x0, f0, h, x1, f1, rtol, atol, k_.k2, k_.k3, k_.k4, k_.k5, k_.k6,
                      k_.xs);
      } else {
        // Small fixed size: the stages live in separate locals, kept in registers, and are
        // stored for the dense output once. Reading back as packets stages that the right-hand
        // side has just written element by element into memory costs a store-forwarding stall
        // per stage (a struct of locals is not split into registers either).
        State k2, k3, k4, k5, k6, xs, x1_local, f1_local;
        const Scalar err =
            stages(sys, m, t, x0, f0, h, x1_local, f1_local, rtol, atol, k2, k3, k4, k5, k6, xs);
        k_.k3 = k3;
        k_.k4 = k4;
        k_.k5 = k5;
        k_.k6 = k6;
        x1 = x1_local;
        f1 = f1_local;
        return err;
      }
    }

    /// Continuous extension at t0 + theta h, theta in [0, 1] (Hairer & Wanner, dopri5 CONTD5):
    /// x0 + theta (dx + (1-theta) (h f0 - dx + theta (dx - h f1 - (h f0 - dx) + (1-theta) r5))).
    void dense(Scalar theta, Scalar h, const State& x0, const State& f0, const State& x1,
               const State& f1, State& out) {
      const auto c = [](double v) { return static_cast<Scalar>(v); };
      if (!dense_ready_) {
        r3_.noalias() = h * f0 - (x1 - x0);
        r5_.noalias() = h * (c(-12715105075.0 / 11282082432.0) * f0 +
                             c(87487479700.0 / 32700410799.0) * k_.k3 +
                             c(-10690763975.0 / 1880347072.0) * k_.k4 +
                             c(701980252875.0 / 199316789632.0) * k_.k5 +
                             c(-1453857185.0 / 822651844.0) * k_.k6 +
                             c(69997945.0 / 29380423.0) * f1);
        dense_ready_ = true;
      }
      const Scalar s = Scalar(1) - theta;
      out.noalias() = x0 + theta * ((x1 - x0) +
                                    s * (r3_ + theta * ((x1 - x0) - h * f1 - r3_ + s * r5_)));
    }

   private:
    // Up to 32 bytes per vector (4 doubles): the eight vectors of a step fit 16 SSE registers.
    static constexpr bool stages_in_registers =
        State::SizeAtCompileTime != Eigen::Dynamic &&
        State::SizeAtCompileTime * static_cast<int>(sizeof(Scalar)) <= 32;

    struct Stages {
      State k2, k3, k4, k5, k6, xs;
    };

    // The Butcher tableau of the pair, stages k2..k6, scratch xs.
    static EIGEN_ALWAYS_INLINE Scalar stages(System& sys, const Mode& m, Scalar t, const State& x0,
                                             const State& f0, Scalar h, State& x1, State& f1,
                                             Scalar rtol, Scalar atol, State& k2, State& k3,
                                             State& k4, State& k5, State& k6, State& xs) {
      const auto c = [](double v) { return static_cast<Scalar>(v); };
      xs.noalias() = x0 + (h * c(1.0 / 5.0)) * f0;
      sys.rhs(m, t + h * c(1.0 / 5.0), xs, k2);
      xs.noalias() = x0 + h * (c(3.0 / 40.0) * f0 + c(9.0 / 40.0) * k2);
      sys.rhs(m, t + h * c(3.0 / 10.0), xs, k3);
      xs.noalias() = x0 + h * (c(44.0 / 45.0) * f0 - c(56.0 / 15.0) * k2 + c(32.0 / 9.0) * k3);
      sys.rhs(m, t + h * c(4.0 / 5.0), xs, k4);
      xs.noalias() = x0 + h * (c(19372.0 / 6561.0) * f0 - c(25360.0 / 2187.0) * k2 +
                               c(64448.0 / 6561.0) * k3 - c(212.0 / 729.0) * k4);
      sys.rhs(m, t + h * c(8.0 / 9.0), xs, k5);
      xs.noalias() = x0 + h * (c(9017.0 / 3168.0) * f0 - c(355.0 / 33.0) * k2 +
                               c(46732.0 / 5247.0) * k3 + c(49.0 / 176.0) * k4 -
                               c(5103.0 / 18656.0) * k5);
      sys.rhs(m, t + h, xs, k6);
      x1.noalias() = x0 + h * (c(35.0 / 384.0) * f0 + c(500.0 / 1113.0) * k3 +
                               c(125.0 / 192.0) * k4 - c(2187.0 / 6784.0) * k5 +
                               c(11.0 / 84.0) * k6);
      sys.rhs(m, t + h, x1, f1);
      xs.noalias() = h * (c(71.0 / 57600.0) * f0 - c(71.0 / 16695.0) * k3 +
                          c(71.0 / 1920.0) * k4 - c(17253.0 / 339200.0) * k5 +
                          c(22.0 / 525.0) * k6 - c(1.0 / 40.0) * f1);
      return detail::error_norm(sys, xs, x0, x1, rtol, atol);
    }

    Stages k_;
    State r3_, r5_;
    bool dense_ready_ = false;
  };
};

}  // namespace stickslip
