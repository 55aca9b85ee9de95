#pragma once
/// \file period_run.hpp
/// \brief run_period: one period of a hybrid system from (mode, t0, x0), with its monodromy
/// matrix, its events and the amplitude of chosen components.

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/dormand_prince54.hpp>
#include <stickslip/ode/exact_linear_stepper.hpp>
#include <stickslip/ode/hybrid_stepper.hpp>
#include <stickslip/steady_state/orbit_signal.hpp>
#include <stickslip/steady_state/shooting_options.hpp>
#include <stickslip/steady_state/variational_system.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace stickslip {

/// One event of an orbit: time and the modes before and after.
template <class Scalar, class Mode>
struct OrbitEvent {
  Scalar t;   ///< event time
  Mode from;  ///< mode before
  Mode to;    ///< mode after
};

/// What run_period reports.
template <class System>
struct PeriodRun {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// Mode of the system.
  using Mode = typename System::Mode;
  /// Dynamic matrix type.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  Status status = Status::Success;  ///< how the run ended
  std::string message;              ///< the run's message when status != Success
  State x_end;                      ///< x(t0 + T)
  Mode mode_end{};                  ///< mode at t0 + T
  Matrix monodromy;                 ///< dx(t0 + T)/dx(t0), n x n (empty when not asked for)
  std::vector<OrbitEvent<Scalar, Mode>> events;  ///< events in (t0, t0 + T]
  /// max |x_i(t)| over the period (steps, events and samples) per amplitude component.
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> amplitudes;
  /// The linear outputs of options.outputs over this run's period (OrbitSignal).
  std::vector<OrbitSignal<Scalar>> outputs;
  StepperStats stats;   ///< counters (of the nominal run)
  long grazing_events = 0;  ///< events whose saltation was skipped (tangent flow)
  bool interrupted = false;  ///< options.interrupt stopped the run (status StoppedByObserver)
  /// status == Status::Success.
  bool ok() const noexcept { return status == Status::Success; }
};

namespace detail {
/// Records events and max |x_i| (i in `components`) of a run; reads x[i], so it serves the plain
/// and the augmented (variational) state alike.
template <class Scalar, class Mode>
struct OrbitObserver {
  const std::vector<Eigen::Index>* components;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1>* amplitudes;
  std::vector<OrbitEvent<Scalar, Mode>>* events;
  SignalAccumulator<Scalar>* signals;

  template <class X>
  void track(const X& x) {
    signals->extremes(x);
    track_amplitudes(x);
  }
  template <class X>
  void track_amplitudes(const X& x) {
    for (std::size_t k = 0; k < components->size(); ++k) {
      const auto i = (*components)[k];
      auto& a = (*amplitudes)[static_cast<Eigen::Index>(k)];
      a = std::max(a, std::abs(x[i]));
    }
  }
  template <class X>
  bool on_step(Scalar, const X& x, const Mode&) {
    track(x);
    return true;
  }
  template <class X>
  bool on_sample(Scalar t, const X& x, const Mode&) {
    signals->sample(t, x);
    track_amplitudes(x);
    return true;
  }
  template <class X>
  void on_event(const EventRecord<Scalar, Mode>& r, const X& x_after) {
    events->push_back({r.t, r.from, r.to});
    track(x_after);
  }
};
}  // namespace detail

/// Integrate `system` over one period [t0, t0 + T] from (mode, x0) with
/// HybridStepper<., DormandPrince54> (or ExactLinearStepper: options.integrator) and
/// options.stepper (samples every T /
/// options.samples_per_period for the amplitudes and the outputs of options.outputs, from this
/// run itself: with the monodromy, the variational run's own state). With `monodromy`, also M = dx(t0 + T)/dx(t0):
/// options.monodromy == Variational integrates VariationalSystem<System> (one run);
/// FiniteDifference re-shoots 2 n perturbed orbits (column j = (x(T; x0 + h e_j) -
/// x(T; x0 - h e_j)) / 2h, h = options.fd_step max(1, |x0_j|)), as the exponential runs always
/// do (options.integrator Exponential throws std::invalid_argument for a system without
/// linear_part). options.interrupt is asked
/// after every step of these runs (true: the run stops, `interrupted`). The numerical outcome is in
/// the result's status; throws std::invalid_argument for non-finite or empty x0, non-finite t0,
/// T <= 0 or invalid options.
template <class System>
PeriodRun<System> run_period(System& system, const typename System::Mode& mode,
                             typename System::Scalar t0, const typename System::State& x0,
                             typename System::Scalar T,
                             const ShootingOptions<typename System::Scalar>& options,
                             bool monodromy) {
  using Scalar = typename System::Scalar;
  using Mode = typename System::Mode;
  static const std::string where = "run_period";
  const Eigen::Index n = x0.size();
  if (n == 0) throw std::invalid_argument(where + ": x0 must not be empty");
  if (!detail::all_finite(x0)) throw std::invalid_argument(where + ": x0 must be finite");
  detail::require_finite(where, "t0", t0);
  detail::require_positive(where, "T", T);
  options.validate(where, n);
  detail::require_resolved_period(where, "T", t0, T, options.stepper);

  PeriodRun<System> run;
  const std::vector<Eigen::Index> comps = options.amplitude_indices(n);
  run.amplitudes.setZero(static_cast<Eigen::Index>(comps.size()));
  // The outputs from this run's own samples (the samples at t0 + k T / N, k = 0 .. N - 1).
  detail::SignalAccumulator<Scalar> signals{&options.outputs, &run.outputs};
  signals.start(t0, T, options.samples_per_period, options.output_harmonics);
  detail::OrbitObserver<Scalar, Mode> orbit_obs{&comps, &run.amplitudes, &run.events, &signals};
  detail::InterruptibleObserver<detail::OrbitObserver<Scalar, Mode>> obs{orbit_obs, options.interrupt};
  // The run's status and message, "interrupted" when options.interrupt stopped it.
  auto finish = [&](const auto& r) {
    run.status = r.status;
    run.interrupted = obs.interrupted;
    run.message = obs.interrupted ? detail::interrupted_message(r.t) : r.message;
  };
  StepperOptions<Scalar> so = options.stepper;
  if (options.samples_per_period > 0) so.output_interval = T / Scalar(options.samples_per_period);
  orbit_obs.track(x0);

  // Column j of the monodromy = (x(T; x0 + h e_j) - x(T; x0 - h e_j)) / 2h by `fd_stepper`'s
  // runs (no samples: only the end states).
  auto difference_monodromy = [&](auto& fd_stepper) {
    run.monodromy.resize(n, n);
    typename System::State xp = x0;
    NullObserver none;
    detail::InterruptibleObserver<NullObserver> fd_obs{none, options.interrupt};
    for (Eigen::Index j = 0; j < n; ++j) {
      const Scalar h = options.fd_step * std::max(Scalar(1), std::abs(x0[j]));
      xp[j] = x0[j] + h;
      const auto rp = fd_stepper.integrate(mode, t0, xp, t0 + T, fd_obs);
      xp[j] = x0[j] - h;
      const auto rm = fd_stepper.integrate(mode, t0, xp, t0 + T, fd_obs);
      xp[j] = x0[j];
      if (!rp.ok() || !rm.ok()) {
        const auto& bad = rp.ok() ? rm : rp;
        run.status = bad.status;
        run.interrupted = fd_obs.interrupted;
        run.message = "finite-difference monodromy, column " + std::to_string(j) + ": " +
                      (fd_obs.interrupted ? detail::interrupted_message(bad.t) : bad.message);
        return;
      }
      run.monodromy.col(j) = (rp.x - rm.x) / (Scalar(2) * h);
    }
  };
  StepperOptions<Scalar> plain = options.stepper;  // no samples: only the end state
  // The run from x0 by `stepper` (samples, amplitudes and events through obs); true when it
  // succeeded.
  auto nominal = [&](auto& stepper) {
    const auto r = stepper.integrate(mode, t0, x0, t0 + T, obs);
    finish(r);
    run.x_end = r.x;
    run.mode_end = r.mode;
    run.stats = r.stats;
    return r.ok();
  };

  if (options.integrator == OrbitIntegrator::Exponential) {
    if constexpr (has_linear_part_v<System>) {
      ExactLinearStepper<System> stepper(system, so);
      if (!nominal(stepper) || !monodromy) return run;
      ExactLinearStepper<System> fd_stepper(system, plain);  // its mode cache serves all 2n runs
      difference_monodromy(fd_stepper);
      return run;
    } else {
      detail::throw_invalid(where, "options.integrator Exponential needs a system with linear_part",
                            std::string(to_string(options.integrator)));
    }
  }

  if (monodromy && options.monodromy == MonodromyMethod::Variational) {
    VariationalSystem<System> var(system, n, options.fd_step, options.control_sensitivities);
    HybridStepper<VariationalSystem<System>, DormandPrince54> stepper(var, so);
    const auto r = stepper.integrate(mode, t0, var.initial_state(x0), t0 + T, obs);
    finish(r);
    run.x_end = r.x.head(n);
    run.mode_end = r.mode;
    run.stats = r.stats;
    run.monodromy = var.sensitivity(r.x);
    run.grazing_events = var.grazing_events();
    return run;
  }
  HybridStepper<System, DormandPrince54> stepper(system, so);
  if (!nominal(stepper) || !monodromy) return run;
  HybridStepper<System, DormandPrince54> fd_stepper(system, plain);
  difference_monodromy(fd_stepper);
  return run;
}

}  // namespace stickslip
