#pragma once
/// \file interrupt.hpp
/// \brief The cancellation hook of the steady-state solvers (ShootingOptions::interrupt,
/// PoincareOptions::interrupt): a predicate asked after every step of their runs, which stops
/// the computation when it returns true (e.g. a user's Ctrl-C, a deadline, a flag set by another
/// thread).

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/hybrid_system.hpp>

#include <functional>
#include <string>

namespace stickslip {

/// Asked after every accepted step (and output sample) of a steady-state computation's runs,
/// on the thread that runs them; true stops the computation (empty: never). It must be cheap
/// (e.g. read an atomic flag, or look at a clock and only now and then do more) and must not
/// throw.
using InterruptCheck = std::function<bool()>;

namespace detail {

/// `inner` (an observer of HybridStepper, held by reference) that also stops the run when
/// `interrupt` returns true: on_step and on_sample return false, so the run ends with
/// Status::StoppedByObserver. `interrupted` tells afterwards whether the interrupt stopped it.
template <class Inner>
struct InterruptibleObserver {
  Inner& inner;
  const InterruptCheck& interrupt;
  bool interrupted = false;

  bool stop() {
    if (!interrupted && interrupt && interrupt()) interrupted = true;
    return interrupted;
  }
  template <class Scalar, class X, class Mode>
  bool on_step(Scalar t, const X& x, const Mode& mode) {
    return inner.on_step(t, x, mode) && !stop();
  }
  template <class Scalar, class X, class Mode>
  bool on_sample(Scalar t, const X& x, const Mode& mode) {
    return inner.on_sample(t, x, mode) && !stop();
  }
  template <class Scalar, class Mode, class X>
  void on_event(const EventRecord<Scalar, Mode>& record, const X& x_after) {
    notify_event(inner, record, x_after);
  }
};

/// The message of a run stopped by the interrupt (at time t).
template <class Scalar>
std::string interrupted_message(Scalar t) {
  return "interrupted: options.interrupt returned true at t = " + format_value(t);
}

}  // namespace detail
}  // namespace stickslip
