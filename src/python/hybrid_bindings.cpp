// Python bindings of a hybrid system written in Python (docs/python_hybrid.md): HybridSystem wraps
// a Python object that has C++'s hybrid-system members (rhs, num_guards, guards, guard_direction,
// transition; stickslip/ode/hybrid_system.hpp), HybridStepper runs it with the library's
// integrators and event location, and find_periodic_orbit shoots its forced or autonomous
// periodic orbits with their Floquet multipliers (C++: Shooting).
//
// The calls keep the GIL: every evaluation is a Python call. Python's signal handlers run after
// every step (Ctrl-C stops a run with KeyboardInterrupt), and an exception raised by the user's
// methods ends the call with that exception.

#include "continuation_support.hpp"

#include <stickslip/stickslip.hpp>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace {

using namespace stickslip;
using Index = Eigen::Index;
using Vector = Eigen::VectorXd;

/// The methods a Python hybrid system must have (C++'s concept, same names and arguments).
constexpr const char* kMethods[] = {"rhs", "num_guards", "guards", "guard_direction", "transition"};

/// The C++ side of a hybrid system written in Python: each member calls the Python method of the
/// same name. Scalar double, State a dynamic vector, Mode a Python int (the user's encoding of
/// the discrete state). Not to be shared between threads (it calls Python with the GIL held).
class PyHybridSystem {
 public:
  using Scalar = double;
  using State = Vector;
  using Mode = long;

  /// Throws std::invalid_argument naming the first missing method.
  explicit PyHybridSystem(py::object impl) : impl_(std::move(impl)) {
    for (const char* name : kMethods) {
      if (!py::hasattr(impl_, name) || !PyCallable_Check(impl_.attr(name).ptr()))
        throw std::invalid_argument(std::string("HybridSystem: the system has no method ") + name +
                                    "(...) (needed: rhs, num_guards, guards, guard_direction, transition; "
                                    "docs/python_hybrid.md)");
    }
  }

  const py::object& impl() const { return impl_; }

  /// dxdt = impl.rhs(mode, t, x).
  void rhs(const Mode& m, Scalar t, const State& x, State& dxdt) {
    vector_of(impl_.attr("rhs")(m, t, x), x.size(), "rhs", dxdt);
  }
  /// impl.num_guards(mode).
  Index num_guards(const Mode& m) const {
    const long n = py::cast<long>(impl_.attr("num_guards")(m));
    if (n < 0)
      throw std::invalid_argument("HybridSystem.num_guards(" + std::to_string(m) + ") returned " +
                                  std::to_string(n) + " (must be >= 0)");
    return static_cast<Index>(n);
  }
  /// g = impl.guards(mode, t, x), of num_guards(mode) values.
  void guards(const Mode& m, Scalar t, const State& x, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& g) {
    vector_of(impl_.attr("guards")(m, t, x), g.size(), "guards", g);
  }
  /// impl.guard_direction(mode, i): a CrossingDirection.
  CrossingDirection guard_direction(const Mode& m, Index i) const {
    return py::cast<CrossingDirection>(impl_.attr("guard_direction")(m, i));
  }
  /// impl.transition(mode, triggered, t, x): a new mode, (mode, x) or (mode, x, stop_reason);
  /// x None keeps the state, a non-empty stop_reason ends the run (StoppedBySystem).
  TransitionAction transition(Mode& m, const TriggeredGuards& which, Scalar t, State& x) {
    const std::vector<Index> triggered(which.begin(), which.end());
    const py::object out = impl_.attr("transition")(m, triggered, t, x);
    if (!py::isinstance<py::tuple>(out)) {
      m = mode_of(out);
      return TransitionAction::proceed();
    }
    const auto items = out.cast<py::tuple>();
    if (items.size() < 2 || items.size() > 3)
      throw std::invalid_argument("HybridSystem.transition must return a mode, (mode, x) or (mode, x, stop_reason); "
                                  "it returned a tuple of " + std::to_string(items.size()));
    m = mode_of(items[0]);
    if (!items[1].is_none()) {
      State reset(x.size());
      vector_of(items[1], x.size(), "transition", reset);
      x = reset;
    }
    if (items.size() == 3 && !items[2].is_none()) {
      auto reason = items[2].cast<std::string>();
      if (!reason.empty()) return TransitionAction::halt(std::move(reason));
    }
    return TransitionAction::proceed();
  }

 private:
  static Mode mode_of(const py::handle& h) {
    if (!py::isinstance<py::int_>(h))
      throw std::invalid_argument("HybridSystem.transition: the mode must be an int, got " +
                                  std::string(py::str(py::type::of(h).attr("__name__"))));
    return h.cast<Mode>();
  }
  template <class Out>
  static void vector_of(const py::handle& h, Index n, const char* what, Out& out) {
    auto v = py::cast<Vector>(h);
    if (v.size() != n)
      throw std::invalid_argument(std::string("HybridSystem.") + what + " returned " + std::to_string(v.size()) +
                                  " values where " + std::to_string(n) + " are needed");
    out = v;
  }

  py::object impl_;
};

static_assert(is_hybrid_system_v<PyHybridSystem>);

/// Checks Python's signal handlers (Ctrl-C): a handler's exception ends the call.
inline void check_signals() {
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

/// One located event of a run.
struct PyHybridEvent {
  double t = 0;
  long from = 0;
  long to = 0;
  std::vector<Index> triggered;
};

/// What HybridStepper.integrate returns.
struct PyHybridRun {
  Status status = Status::Success;
  double t = 0;
  Vector x;
  long mode = 0;
  std::string message;
  StepperStats stats;
  std::vector<PyHybridEvent> events;
  std::vector<double> sample_times;
  std::vector<Vector> samples;
  std::vector<long> sample_modes;
};

/// Records events and samples, runs the signal handlers after every step.
struct RunRecorder {
  PyHybridRun* run;
  bool on_step(double, const Vector&, const long&) {
    check_signals();
    return true;
  }
  void on_event(const EventRecord<double, long>& e) {
    run->events.push_back({e.t, e.from, e.to, std::vector<Index>(e.triggered->begin(), e.triggered->end())});
  }
  bool on_sample(double t, const Vector& x, const long& m) {
    run->sample_times.push_back(t);
    run->samples.push_back(x);
    run->sample_modes.push_back(m);
    return true;
  }
};

/// The Python HybridStepper: a system and RunOptions (integrator rk4, dopri5 or rosenbrock23).
struct PyHybridStepper {
  PyHybridSystem system;
  RunOptions<double> options;

  PyHybridRun integrate(long mode, double t0, const Vector& x0, double t_end) {
    static const std::string where = "HybridStepper.integrate";
    detail::require_finite(where, "t0", t0);
    detail::require_finite(where, "t_end", t_end);
    if (!(t_end >= t0)) detail::throw_invalid(where, "t_end must be >= t0", t_end);
    if (x0.size() == 0) throw std::invalid_argument(where + ": x0 must not be empty");
    if (!x0.allFinite()) throw std::invalid_argument(where + ": x0 must be finite");
    PyHybridRun run;
    RunRecorder rec{&run};
    const auto take = [&run](auto&& r) {
      run.status = r.status;
      run.t = r.t;
      run.x = r.x;
      run.mode = r.mode;
      run.message = r.message;
      run.stats = r.stats;
    };
    const auto run_with = [&](auto method) {
      HybridStepper<PyHybridSystem, decltype(method)> stepper(system, options.stepper);
      take(stepper.integrate(mode, t0, x0, t_end, rec));
    };
    if (options.integrator == Integrator::RungeKutta4)
      run_with(RungeKutta4{});
    else if (options.integrator == Integrator::Rosenbrock23)
      run_with(Rosenbrock23{});
    else
      run_with(DormandPrince54{});
    return run;
  }
};

/// What find_periodic_orbit returns for a HybridSystem (C++: PeriodicOrbit<System>, floquet flattened).
struct PyHybridOrbit {
  ShootingStatus status = ShootingStatus::NoConvergence;
  std::string message;
  double t0 = 0;
  double period = 0;
  long mode = 0;
  Vector x0;
  double residual = 0;
  int iterations = 0;
  Eigen::MatrixXd monodromy;
  Eigen::VectorXcd multipliers;
  std::complex<double> trivial{1.0, 0.0};
  double max_modulus = 0;
  bool stable = true;
  Instability instability = Instability::None;
  Vector amplitudes;
  std::vector<PyHybridEvent> events;
  StepperStats stats;
};

PyHybridOrbit to_py(const PeriodicOrbit<PyHybridSystem>& o) {
  PyHybridOrbit p;
  p.status = o.status;
  p.message = o.message;
  p.t0 = o.t0;
  p.period = o.period;
  p.mode = o.mode;
  p.x0 = o.x0;
  p.residual = o.residual;
  p.iterations = o.iterations;
  p.monodromy = o.monodromy;
  p.multipliers = o.floquet.multipliers;
  p.trivial = o.floquet.trivial;
  p.max_modulus = o.floquet.max_modulus;
  p.stable = o.floquet.stable;
  p.instability = o.floquet.instability;
  p.amplitudes = o.amplitudes;
  for (const auto& e : o.events) p.events.push_back({e.t, e.from, e.to, {}});
  p.stats = o.stats;
  return p;
}

}  // namespace

void bind_hybrid(py::module_& m) {
  py::enum_<CrossingDirection>(m, "CrossingDirection",
                               "The direction in which a guard's zero crossing is an event (HybridSystem.guard_direction).")
      .value("Rising", CrossingDirection::Rising, "g goes from negative to positive")
      .value("Falling", CrossingDirection::Falling, "g goes from positive to negative")
      .value("Either", CrossingDirection::Either, "both directions");

  py::class_<PyHybridSystem>(
      m, "HybridSystem",
      "A hybrid (piecewise-smooth) system written in Python, run by HybridStepper and shot by "
      "find_periodic_orbit (docs/python_hybrid.md). It wraps an object with C++'s members: rhs(mode, t, x) -> "
      "dx/dt; num_guards(mode) -> int; guards(mode, t, x) -> g (num_guards values; an event is a zero crossing); "
      "guard_direction(mode, i) -> CrossingDirection; transition(mode, triggered, t, x) -> new mode, (mode, x) or "
      "(mode, x, stop_reason) (x None keeps the state; a non-empty stop_reason ends the run). The mode is an int. "
      "Not to be shared between threads.")
      .def(py::init([](py::object impl) { return PyHybridSystem(std::move(impl)); }), py::arg("impl"),
           "Wraps `impl`; ValueError naming the first of the five methods it lacks.")
      .def_property_readonly("impl", &PyHybridSystem::impl, "the wrapped Python object");

  py::class_<PyHybridEvent>(m, "HybridEvent", "One located event of a HybridSystem's run or orbit.")
      .def_readonly("t", &PyHybridEvent::t, "the located event time")
      .def_readonly("from_mode", &PyHybridEvent::from, "the mode before the transition (C++: from)")
      .def_readonly("to_mode", &PyHybridEvent::to, "the mode after the transition (C++: to)")
      .def_readonly("triggered", &PyHybridEvent::triggered,
                    "indices of the guards that fired together (empty in an orbit's events)");

  py::class_<PyHybridRun>(m, "HybridRun", "What HybridStepper.integrate returns (C++: HybridResult and an observer's records).")
      .def_readonly("status", &PyHybridRun::status, "how the run ended (Status)")
      .def_property_readonly("ok", [](const PyHybridRun& r) { return r.status == Status::Success; },
                             "status == Success")
      .def_readonly("t", &PyHybridRun::t, "the time reached (the failure time when not ok)")
      .def_readonly("x", &PyHybridRun::x, "the state at t")
      .def_readonly("mode", &PyHybridRun::mode, "the mode at t")
      .def_readonly("message", &PyHybridRun::message, "empty on success; otherwise what happened and where")
      .def_readonly("stats", &PyHybridRun::stats, "the stepper's counters (StepperStats)")
      .def_readonly("events", &PyHybridRun::events, "the located events, in order (HybridEvent)")
      .def_property_readonly(
          "sample_times", [](const PyHybridRun& r) { return Eigen::Map<const Vector>(r.sample_times.data(), static_cast<Index>(r.sample_times.size())).eval(); },
          "times of the samples (options.output_interval > 0: t0, t0 + dt, ...)")
      .def_property_readonly(
          "samples",
          [](const PyHybridRun& r) {
            Eigen::MatrixXd s(static_cast<Index>(r.samples.size()), r.x.size());
            for (std::size_t k = 0; k < r.samples.size(); ++k) s.row(static_cast<Index>(k)) = r.samples[k].transpose();
            return s;
          },
          "the state at each sample time, one row per sample (dense output)")
      .def_readonly("sample_modes", &PyHybridRun::sample_modes, "the mode at each sample time");

  py::class_<PyHybridStepper>(
      m, "HybridStepper",
      "Runs a HybridSystem (C++: HybridStepper<System, Method>) with options.integrator rk4, dopri5 or rosenbrock23 "
      "(rosenbrock23's Jacobian by finite differences) and the event location of docs/ode.md.")
      .def(py::init([](const PyHybridSystem& system, const RunOptions<double>& options) {
             static const std::string where = "HybridStepper";
             if (options.integrator != Integrator::RungeKutta4 && options.integrator != Integrator::DormandPrince54 &&
                 options.integrator != Integrator::Rosenbrock23)
               throw std::invalid_argument(where + ": options.integrator must be rk4, dopri5 or rosenbrock23 (" +
                                           to_string(options.integrator) +
                                           " needs the library's systems: a linear part or simulate())");
             options.stepper.validate(where);
             return PyHybridStepper{system, options};
           }),
           py::arg("system"), py::arg("options") = RunOptions<double>{Integrator::DormandPrince54},
           "HybridStepper(system, options=RunOptions(\"dopri5\")): ValueError naming a bad option.")
      .def("integrate", &PyHybridStepper::integrate, py::arg("mode"), py::arg("t0"), py::arg("x0"), py::arg("t_end"),
           "Runs from (mode, t0, x0) to t_end and returns a HybridRun: a failure (status, time, reason) is in it; bad "
           "arguments raise ValueError naming them, an exception of the system's methods ends the call with it.")
      .def_property_readonly("options", [](const PyHybridStepper& s) { return s.options; }, "the RunOptions in use");

  py::class_<PyHybridOrbit>(m, "HybridPeriodicOrbit",
                            "A HybridSystem's periodic orbit (C++: PeriodicOrbit, its floquet fields flattened).")
      .def_readonly("status", &PyHybridOrbit::status, "how the shooting ended (ShootingStatus)")
      .def_property_readonly("ok", [](const PyHybridOrbit& o) { return o.status == ShootingStatus::Converged; },
                             "status == Converged")
      .def_readonly("message", &PyHybridOrbit::message, "why it failed (empty when Converged)")
      .def_readonly("t0", &PyHybridOrbit::t0, "time of the section")
      .def_readonly("period", &PyHybridOrbit::period, "the period T (autonomous: the one found)")
      .def_readonly("mode", &PyHybridOrbit::mode, "the mode at t0")
      .def_readonly("x0", &PyHybridOrbit::x0, "the orbit's state at t0")
      .def_readonly("residual", &PyHybridOrbit::residual, "max |x_i(T) - x_i(0)| over the periodic components")
      .def_readonly("iterations", &PyHybridOrbit::iterations, "orbit runs made")
      .def_readonly("monodromy", &PyHybridOrbit::monodromy, "dx_P(T)/dx_P(0) over the periodic components P")
      .def_readonly("multipliers", &PyHybridOrbit::multipliers,
                    "Floquet multipliers by decreasing modulus (numpy, complex; autonomous: without the trivial one)")
      .def_readonly("trivial", &PyHybridOrbit::trivial, "autonomous orbits: the multiplier nearest 1 (the flow's)")
      .def_readonly("max_modulus", &PyHybridOrbit::max_modulus, "the largest |multiplier|")
      .def_readonly("stable", &PyHybridOrbit::stable, "every multiplier inside the unit circle")
      .def_readonly("instability", &PyHybridOrbit::instability, "how it is unstable (Instability; Stable when stable)")
      .def_readonly("amplitudes", &PyHybridOrbit::amplitudes, "max |x_i| over the orbit (the periodic components)")
      .def_readonly("events", &PyHybridOrbit::events, "the events of one period, in order")
      .def_readonly("stats", &PyHybridOrbit::stats, "the counters of the last orbit run");

  m.def(
      "find_periodic_orbit",
      [](PyHybridSystem& system, double period, const Vector& x0, double t0, long mode, bool autonomous,
         std::optional<std::vector<Index>> periodic, const std::string& monodromy, double tolerance,
         int max_iterations, double rtol, double atol, double max_step, long guard_samples, long max_steps,
         int samples_per_period, std::optional<std::vector<Index>> amplitude_components, double multiplier_tolerance,
         double fd_step, bool control_sensitivities) {
        static const std::string where = "find_periodic_orbit";
        ShootingOptions<double> opt;
        if (periodic) opt.periodic = *periodic;
        opt.monodromy = stickslip_python::monodromy_method(monodromy, where);
        opt.tolerance = tolerance;
        opt.max_iterations = max_iterations;
        opt.stepper.rtol = rtol;
        opt.stepper.atol = atol;
        opt.stepper.max_steps = stickslip_python::checked_max_steps(max_steps, where);
        stickslip_python::set_orbit_details(opt, samples_per_period, amplitude_components, multiplier_tolerance,
                                            fd_step, control_sensitivities, max_step, guard_samples);
        opt.interrupt = [] {
          check_signals();
          return false;
        };
        Shooting<PyHybridSystem> shooting(system, opt);
        if (autonomous) {
          if (t0 != 0) detail::throw_invalid(where, "t0 must be 0 for an autonomous orbit", t0);
          return to_py(shooting.autonomous(mode, x0, period));
        }
        return to_py(shooting.forced(mode, t0, x0, period));
      },
      py::arg("system"), py::arg("period"), py::arg("x0"), py::arg("t0") = 0.0, py::arg("mode") = 0,
      py::arg("autonomous") = false, py::arg("periodic") = py::none(), py::arg("monodromy") = "variational",
      py::arg("tolerance") = 1e-9, py::arg("max_iterations") = 30, py::arg("rtol") = 1e-10, py::arg("atol") = 1e-12,
      py::arg("max_step") = std::numeric_limits<double>::infinity(), py::arg("guard_samples") = 0,
      py::arg("max_steps") = StepperOptions<double>{}.max_steps, py::arg("samples_per_period") = 256,
      py::arg("amplitude_components") = py::none(), py::arg("multiplier_tolerance") = 1e-6, py::arg("fd_step") = 1e-6,
      py::arg("control_sensitivities") = true,
      "A HybridSystem's periodic orbit by shooting from the guess (mode, t0, x0) (C++: Shooting<System>): forced "
      "(period T given: x_P(t0 + T) = x_P(t0)) or, with autonomous=True, autonomous (T the guess, t0 = 0, a phase "
      "condition; the orbit's period is found), with the monodromy (variational with saltation matrices, or "
      "finite_difference) and the Floquet multipliers. The runs are dopri5 at rtol / atol (tight by default: the "
      "residual cannot be smaller than the integration error); max_step and guard_samples as in RunOptions (set "
      "them when a guard can cross and cross back inside one step); samples_per_period, amplitude_components, "
      "multiplier_tolerance, fd_step and control_sensitivities as for the library's systems. Returns a "
      "HybridPeriodicOrbit; bad input raises ValueError naming it.");
}
