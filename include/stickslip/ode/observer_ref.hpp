#pragma once
/// \file observer_ref.hpp
/// \brief ObserverRef: a non-owning, type-erased reference to an observer of a hybrid run.

#include <stickslip/ode/hybrid_system.hpp>

#include <type_traits>

namespace stickslip {

/// A non-owning reference to any observer of a hybrid run (see docs/ode.md, "Observers and
/// output"): on_step, on_event and on_sample forwarded through one function pointer each, to an
/// observer that must outlive the reference. An observer with only on_event(record) is called
/// with the record alone. No allocation; one indirect call per step, event and sample.
///
/// It lets a run be compiled once for every observer: simulate() passes its observer through an
/// ObserverRef, so the steppers are instantiated once per system type, and the compiled mode
/// (stickslip::compiled, docs/compiled.md) can instantiate them ahead of time.
template <class Scalar, class State, class Mode>
class ObserverRef {
 public:
  /// The event record passed to on_event.
  using Record = EventRecord<Scalar, Mode>;

  /// Refers to `observer` (kept by address).
  template <class Observer,
            class = std::enable_if_t<!std::is_same_v<std::remove_cv_t<Observer>, ObserverRef>>>
  ObserverRef(Observer& observer) noexcept  // NOLINT(google-explicit-constructor): a reference
      : object_(const_cast<void*>(static_cast<const void*>(&observer))),
        step_(&step_of<Observer>),
        event_(&event_of<Observer>),
        sample_(&sample_of<Observer>) {}

  /// After each accepted step; false stops the run.
  bool on_step(Scalar t, const State& x, const Mode& mode) const { return step_(object_, t, x, mode); }
  /// After each transition, with the state after it.
  void on_event(const Record& record, const State& x_after) const { event_(object_, record, x_after); }
  /// At each output time; false stops the run.
  bool on_sample(Scalar t, const State& x, const Mode& mode) const {
    return sample_(object_, t, x, mode);
  }

 private:
  template <class Observer>
  static bool step_of(void* o, Scalar t, const State& x, const Mode& mode) {
    return static_cast<Observer*>(o)->on_step(t, x, mode);
  }
  template <class Observer>
  static void event_of(void* o, const Record& record, const State& x_after) {
    detail::notify_event(*static_cast<Observer*>(o), record, x_after);
  }
  template <class Observer>
  static bool sample_of(void* o, Scalar t, const State& x, const Mode& mode) {
    return static_cast<Observer*>(o)->on_sample(t, x, mode);
  }

  void* object_;
  bool (*step_)(void*, Scalar, const State&, const Mode&);
  void (*event_)(void*, const Record&, const State&);
  bool (*sample_)(void*, Scalar, const State&, const Mode&);
};

}  // namespace stickslip
