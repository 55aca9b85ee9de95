#pragma once
/// \file shooting_options.hpp
/// \brief Options of the periodic-orbit solvers (shooting, monodromy, Floquet analysis).

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/stepper_options.hpp>
#include <stickslip/steady_state/interrupt.hpp>
#include <stickslip/steady_state/progress.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace stickslip {

namespace detail {
/// Throws std::invalid_argument("<where>: <name> must be >= options.stepper.min_step * max(1, |t|)
/// ...") when the period T is below the stepper's smallest step at the largest |t| of the run
/// (|t0| + span): there t0 + T rounds to (nearly) t0, and a run of "one period" returns its
/// start, which would close for any state.
template <class Scalar>
void require_resolved_period(const std::string& where, const char* name, Scalar t0, Scalar T,
                             const StepperOptions<Scalar>& stepper, Scalar span = Scalar(0)) {
  using std::abs;
  const Scalar t_max = abs(t0) + span;
  const Scalar floor = stepper.smallest_step(t_max);
  if (!(T >= floor))
    throw_invalid(where,
                  std::string(name) + " must be >= options.stepper.min_step * max(1, |t|) = " +
                      format_value(floor) + " at |t| = " + format_value(t_max) +
                      ", or t0 + T does not resolve the period",
                  T);
}
}  // namespace detail

/// How the monodromy matrix dx(T)/dx(0) of an orbit is computed.
enum class MonodromyMethod : std::uint8_t {
  /// Variational equations Phi' = (df/dx) Phi integrated with the orbit, with a saltation matrix
  /// at every event (see VariationalSystem).
  Variational,
  /// Central differences of re-shot orbits: column j = (x(T; x0 + h e_j) - x(T; x0 - h e_j)) / 2h
  /// (2 n plain runs; a cross-check of the variational monodromy).
  FiniteDifference
};

/// Human-readable name of a monodromy method.
inline const char* to_string(MonodromyMethod m) noexcept {
  return m == MonodromyMethod::FiniteDifference ? "finite_difference" : "variational";
}

/// Integrator of the orbit runs (run_period, hence Shooting and Continuation).
enum class OrbitIntegrator : std::uint8_t {
  /// HybridStepper with DormandPrince54 (any hybrid system).
  DormandPrince54,
  /// ExactLinearStepper (systems with linear_part, stickslip/ode/linear_part.hpp): exact
  /// propagation in linear modes, whatever their fastest mode; the monodromy is then always by
  /// central differences of exact runs (MonodromyMethod::FiniteDifference).
  Exponential
};

/// Human-readable name of an orbit integrator.
inline const char* to_string(OrbitIntegrator i) noexcept {
  return i == OrbitIntegrator::Exponential ? "exponential" : "dopri5";
}

/// Options of Shooting and Continuation. Tolerances are on the components declared periodic.
template <class Scalar>
struct ShootingOptions {
  /// Options of the runs (HybridStepper with DormandPrince54, or ExactLinearStepper: see
  /// `integrator`). Tight by default: the Newton residual cannot be smaller than the
  /// integration error.
  StepperOptions<Scalar> stepper = tight_stepper();
  /// Integrator of the runs. Exponential needs a system with linear_part and ignores
  /// `monodromy` and `control_sensitivities` (finite differences of exact runs).
  OrbitIntegrator integrator = OrbitIntegrator::DormandPrince54;
  /// Indices of the state components that must repeat after a period (x_i(T) = x_i(0)); empty:
  /// all. The others (e.g. energy quadratures) keep their initial values and are not solved for.
  std::vector<Eigen::Index> periodic;
  /// Newton converges when max_i |x_i(T) - x_i(0)| <= tolerance * max(1, max_i |x_i(0)|), i periodic.
  Scalar tolerance = Scalar(1e-9);
  /// Newton iterations allowed (each one orbit run, plus the monodromy).
  int max_iterations = 30;
  /// How the monodromy (the Newton Jacobian and the Floquet multipliers) is computed.
  MonodromyMethod monodromy = MonodromyMethod::Variational;
  /// Variational monodromy: true keeps the sensitivities Phi under the runs' error control (the
  /// steps resolve x and Phi); false leaves them out (the steps of a plain run of x, Phi
  /// integrated on them by the same Runge-Kutta formula: the usual choice of shooting codes).
  bool control_sensitivities = true;
  /// Relative step h of the finite differences (monodromy, guard gradients, reset Jacobians,
  /// the parameter derivative of continuation): h_j = fd_step * max(1, |x_j|).
  Scalar fd_step = Scalar(1e-6);
  /// Samples per period (dense output) for the amplitude measures, besides every step and event.
  int samples_per_period = 256;
  /// Components whose max |x_i| over the orbit is reported; empty: the periodic components.
  std::vector<Eigen::Index> amplitude_components;
  /// Linear outputs y_j = outputs.row(j) x measured over each orbit's own period (OrbitSignal:
  /// extremes, mean, harmonics), e.g. a tip displacement from modal coordinates. 0 rows: none;
  /// else one column per state component.
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> outputs;
  /// Harmonics 1 .. output_harmonics of each output (their Fourier coefficients need
  /// samples_per_period > 2 output_harmonics).
  int output_harmonics = 0;
  /// A multiplier with |mu| > 1 + multiplier_tolerance makes the orbit unstable.
  Scalar multiplier_tolerance = Scalar(1e-6);
  /// Asked after every step of every orbit run (empty: never); true stops the computation: the
  /// run ends with Status::StoppedByObserver and a message starting "interrupted", Shooting
  /// returns IntegrationFailed, Continuation the status Interrupted (see InterruptCheck).
  InterruptCheck interrupt;
  /// Called after the run of the guess and after every Newton iteration of Shooting (empty:
  /// never) with the residual, the CPU seconds so far and an estimate of the seconds left
  /// (ShootingProgress): a long orbit (many modes, many events) tells what it costs as it goes.
  ShootingProgressCallback progress;

  /// The indices 0 .. count-1 (e.g. the mechanical states of a system whose last components are
  /// quadratures).
  static std::vector<Eigen::Index> first(Eigen::Index count) {
    std::vector<Eigen::Index> v(static_cast<std::size_t>(count > 0 ? count : 0));
    std::iota(v.begin(), v.end(), Eigen::Index{0});
    return v;
  }

  /// The default run options: rtol 1e-10, atol 1e-12.
  static StepperOptions<Scalar> tight_stepper() {
    StepperOptions<Scalar> o;
    o.rtol = Scalar(1e-10);
    o.atol = Scalar(1e-12);
    return o;
  }

  /// Throws std::invalid_argument("<where>: options.<name> ...") for an option out of range, for
  /// state size n.
  void validate(const std::string& where, Eigen::Index n) const {
    stepper.validate(where);
    if (integrator != OrbitIntegrator::DormandPrince54 && integrator != OrbitIntegrator::Exponential)
      detail::throw_invalid(where, "options.integrator must be an OrbitIntegrator enumerator",
                            static_cast<int>(integrator));
    detail::require_positive(where, "options.tolerance", tolerance);
    if (max_iterations <= 0)
      detail::throw_invalid(where, "options.max_iterations must be > 0", max_iterations);
    if (!(fd_step > 0 && fd_step < Scalar(0.1)))
      detail::throw_invalid(where, "options.fd_step must be in (0, 0.1)", fd_step);
    if (samples_per_period < 0)
      detail::throw_invalid(where, "options.samples_per_period must be >= 0", samples_per_period);
    detail::require_non_negative(where, "options.multiplier_tolerance", multiplier_tolerance);
    detail::require_indices(where, "options.periodic", periodic, n);
    detail::require_indices(where, "options.amplitude_components", amplitude_components, n);
    if (output_harmonics < 0)
      detail::throw_invalid(where, "options.output_harmonics must be >= 0", output_harmonics);
    if (outputs.rows() > 0) {
      if (outputs.cols() != n)
        detail::throw_invalid(where, "options.outputs must have one column per state component (" +
                                         std::to_string(n) + "), columns",
                              outputs.cols());
      if (!detail::all_finite(outputs))
        throw std::invalid_argument(where + ": options.outputs must be finite");
      if (samples_per_period <= 2 * output_harmonics)
        detail::throw_invalid(where,
                              "options.samples_per_period must be > 2 options.output_harmonics "
                              "when options.outputs is set",
                              samples_per_period);
    }
  }

  /// The periodic indices in use for state size n (all when `periodic` is empty).
  std::vector<Eigen::Index> periodic_indices(Eigen::Index n) const {
    return periodic.empty() ? first(n) : periodic;
  }
  /// The amplitude components in use for state size n.
  std::vector<Eigen::Index> amplitude_indices(Eigen::Index n) const {
    return amplitude_components.empty() ? periodic_indices(n) : amplitude_components;
  }

};

}  // namespace stickslip
