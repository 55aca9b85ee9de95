#pragma once
// The Python module's guards of long calls (docs/python.md, "Threads and interrupts"):
//
// - PySystem, PyContactSystem and PyBodyContactSystem, the Python FrictionDampedSystem,
//   ContactSystem and BodyContactSystem: the C++
//   system and a lock. A system's evaluation
//   workspace, factorisation, event and impact logs are mutable (docs/architecture.md, "Thread
//   safety"), so two runs on one system at once would corrupt each other; every call that runs
//   or evaluates a system holds its lock, and calls on one system from several Python threads
//   run one after the other. The lock is recursive: a Python callable of a run (e.g.
//   continue_orbits' start_mode) may call the same system's methods on the run's thread.
// - SignalCheck: lets a call that released the GIL stop at Ctrl-C. From the calling thread it
//   re-acquires the GIL at most every kSignalInterval and runs Python's signal handlers
//   (PyErr_CheckSignals); once a handler raised (KeyboardInterrupt), it answers true to every
//   thread of the call, and rethrow() raises the handler's exception after the call.
//
// Lock order: the GIL is released first, then the system's lock is taken (SystemLock), never the
// other way round. A thread holding a system's lock may wait for the GIL (a Python callable of
// its run); a thread waiting for the lock holds no GIL, so it cannot block that thread.
#include <stickslip/stickslip.hpp>

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <thread>
#include <type_traits>
#include <utility>

namespace stickslip_python {

namespace py = pybind11;
using System = stickslip::FrictionDampedSystem<double>;

/// A Python system (FrictionDampedSystem, ContactSystem): the C++ system and the lock of the
/// calls that use it.
template <class Base>
class Locked : public Base {
 public:
  using Wrapped = Base;  ///< the C++ system
  using Base::Base;
  explicit Locked(const Base& s) : Base(s) {}
  /// A copy has its own (free) lock.
  Locked(const Locked& other) : Base(other) {}
  Locked& operator=(const Locked& other) {
    Base::operator=(other);
    return *this;
  }
  ~Locked() = default;
  /// The lock of the calls that run or evaluate this system.
  std::recursive_timed_mutex& mutex() const { return mutex_; }

 private:
  mutable std::recursive_timed_mutex mutex_;
};

/// The Python FrictionDampedSystem.
using PySystem = Locked<System>;
/// The Python ContactSystem.
using PyContactSystem = Locked<stickslip::ContactSystem<double>>;
/// The Python BodyContactSystem: a ContactSystem over contacts of rigid-body points.
using PyBodyContactSystem = Locked<stickslip::ContactSystem<double, stickslip::BodyContact<double>>>;
/// The Python MixedContactSystem: a ContactSystem over contacts of both kinds (AnyContact).
using PyMixedContactSystem = Locked<stickslip::ContactSystem<double, stickslip::AnyContact<double>>>;

/// How often a call with the GIL released looks for signals (and how long a wait for a system's
/// lock lasts between two looks): often enough for Ctrl-C to feel immediate, rarely enough that
/// the GIL round trip (~microseconds) costs nothing against the steps in between.
constexpr std::chrono::milliseconds kSignalInterval{20};

/// Python's signal handlers run from a call with the GIL released (see the file's comment).
/// Constructed with the GIL held, on the calling thread.
class SignalCheck {
 public:
  SignalCheck() : owner_(std::this_thread::get_id()), next_(std::chrono::steady_clock::now() + kSignalInterval) {}
  SignalCheck(const SignalCheck&) = delete;
  SignalCheck& operator=(const SignalCheck&) = delete;
  ~SignalCheck() = default;

  /// True once a signal handler raised. Called without the GIL, from any thread of the call;
  /// only the calling thread runs the handlers (Python runs them on the main thread only).
  bool operator()() {
    if (raised_.load(std::memory_order_relaxed)) return true;
    if (std::this_thread::get_id() != owner_) return false;
    const auto now = std::chrono::steady_clock::now();
    if (now < next_) return false;
    next_ = now + kSignalInterval;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() == 0) return false;
    error_.emplace();  // fetches (and clears) the handler's exception
    raised_.store(true, std::memory_order_relaxed);
    return true;
  }
  /// With the GIL held: raises the handler's exception (KeyboardInterrupt) when one was raised.
  void rethrow() {
    if (error_) throw *error_;
  }

 private:
  std::thread::id owner_;
  std::chrono::steady_clock::time_point next_;
  std::atomic<bool> raised_{false};
  std::optional<py::error_already_set> error_;
};

/// A system's lock, taken without the GIL; the wait looks for signals every kSignalInterval and
/// gives up when a handler raised (then owns() is false and the caller rethrows).
class SystemLock {
 public:
  template <class Base>
  SystemLock(const Locked<Base>& system, SignalCheck& signals) : mutex_(system.mutex()) {
    while (!mutex_.try_lock_for(kSignalInterval))
      if (signals()) return;
    owns_ = true;
  }
  SystemLock(const SystemLock&) = delete;
  SystemLock& operator=(const SystemLock&) = delete;
  ~SystemLock() {
    if (owns_) mutex_.unlock();
  }
  bool owns() const { return owns_; }

 private:
  std::recursive_timed_mutex& mutex_;
  bool owns_ = false;
};

/// f(signals) with the GIL released and `system`'s lock held, for a call that runs or evaluates
/// it (f must not touch Python objects, nor return one; a long f asks `signals` between steps and
/// stops when it answers true); then, with the GIL, KeyboardInterrupt when Ctrl-C came during the
/// wait for the lock or the call.
template <class Base, class F>
auto with_system(const Locked<Base>& system, F&& f) {
  using R = decltype(f(std::declval<SignalCheck&>()));
  SignalCheck signals;
  if constexpr (std::is_void_v<R>) {
    {
      py::gil_scoped_release release;
      SystemLock lock(system, signals);
      if (lock.owns()) f(signals);
    }
    signals.rethrow();
  } else {
    std::optional<R> out;
    {
      py::gil_scoped_release release;
      SystemLock lock(system, signals);
      if (lock.owns()) out.emplace(f(signals));
    }
    signals.rethrow();
    return std::move(*out);
  }
}

/// A copy of `system` made under its lock (e.g. a system returned by a Python callable, which
/// another thread may be running). Called with the GIL held.
template <class Base>
Base copy_of(const Locked<Base>& system) {
  return with_system(system, [&](SignalCheck&) { return Base(system); });
}

}  // namespace stickslip_python
