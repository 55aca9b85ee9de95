#pragma once
// What the steady-state bindings share (stickslip_module.cpp's find_periodic_orbit and
// continue_orbits, branch_bindings.cpp's branch switching): the Python views of orbits, points and
// branches (PyOrbit, PyContinuationPoint, PyContinuation) made from the C++ results, the shooting
// options built from the Python keywords, and the Python callables of a continuation as the C++
// std::functions.
#include "call_guard.hpp"

#include <stickslip/stickslip.hpp>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace stickslip_python {

using namespace stickslip;
using Index = Eigen::Index;
using State = System::State;
using Mode = System::Mode;

/// A DamperStates as a Python list of ContactState.
inline std::vector<ContactState> to_list(const Mode& mode) {
  std::vector<ContactState> v(static_cast<std::size_t>(mode.size()));
  for (Index i = 0; i < mode.size(); ++i) v[static_cast<std::size_t>(i)] = mode[i];
  return v;
}

/// A Python list of ContactState as a DamperStates.
inline Mode to_mode(const std::vector<ContactState>& states) {
  Mode mode(static_cast<Index>(states.size()));
  for (std::size_t i = 0; i < states.size(); ++i) mode[static_cast<Index>(i)] = states[i];
  return mode;
}

/// A Python argument or callable result as T, else TypeError "<what>, got <its type[ and shape]>"
/// (what: the parameter and what it must be), instead of pybind11's RuntimeError.
template <class T>
T cast_as(const py::handle& h, const std::string& what) {
  try {
    return h.cast<T>();
  } catch (const py::cast_error&) {
  } catch (const py::reference_cast_error&) {
  }
  std::string got = py::str(py::type::of(h).attr("__name__"));
  if (py::hasattr(h, "shape")) got += " of shape " + std::string(py::str(h.attr("shape")));
  throw py::type_error(what + ", got " + got);
}

/// Checks a run's start: x0 of state_size() entries (ValueError naming x0, with both sizes), then
/// its mode (validate_state: num_dampers() states, ...).
template <class Sys>
void check_start(const Sys& system, const Mode& mode, const State& x, const std::string& where) {
  if (x.size() != system.state_size())
    throw std::invalid_argument(where + ": x0 has size " + std::to_string(x.size()) +
                                ", expected state_size() = " + std::to_string(system.state_size()));
  system.validate_state(mode, x, where.c_str());
}

/// One transition seen by simulate()'s observer (the stepper's record: every damper's state).
struct Transition {
  double t = 0;
  std::vector<ContactState> from, to;
};

/// A periodic orbit of Shooting<System>::forced as Python sees it.
struct PyOrbit {
  ShootingStatus status = ShootingStatus::NoConvergence;
  std::string message;
  double t0 = 0, period = 0, residual = 0;
  int iterations = 0;
  State x0;
  std::vector<ContactState> mode;
  Eigen::MatrixXd monodromy;
  Eigen::VectorXcd multipliers;
  double max_modulus = 0;
  bool stable = false;
  Instability instability = Instability::None;
  Eigen::VectorXd amplitudes;
  std::vector<Transition> events;
  std::vector<double> stick_fractions;  // per damper (orbit_contact_statistics)
  std::vector<int> switches;            // per damper
  std::vector<OrbitSignal<double>> outputs;  // the outputs= rows over the period
};

/// The C++ orbit as PyOrbit (no Python objects: callable with the GIL released).
template <class Sys>
PyOrbit to_py(const PeriodicOrbit<Sys>& orbit) {
  PyOrbit out;
  out.status = orbit.status;
  out.message = orbit.message;
  out.t0 = orbit.t0;
  out.period = orbit.period;
  out.residual = orbit.residual;
  out.iterations = orbit.iterations;
  out.x0 = orbit.x0;
  out.mode = to_list(orbit.mode);
  out.monodromy = orbit.monodromy;
  out.multipliers = orbit.floquet.multipliers;
  out.max_modulus = orbit.floquet.max_modulus;
  out.stable = orbit.floquet.stable;
  out.instability = orbit.floquet.instability;
  out.amplitudes = orbit.amplitudes;
  out.outputs = orbit.outputs;
  for (const auto& e : orbit.events) out.events.push_back(Transition{e.t, to_list(e.from), to_list(e.to)});
  for (Index i = 0; i < orbit.mode.size(); ++i) {
    const auto c = orbit_contact_statistics(orbit, i);
    out.stick_fractions.push_back(c.stick_fraction);
    out.switches.push_back(c.switches);
  }
  return out;
}

/// The run budget of the steady-state functions: max_steps step attempts per run (> 0).
inline long checked_max_steps(long max_steps, const std::string& where) {
  if (max_steps <= 0)
    detail::throw_invalid(where, "max_steps must be > 0 (step attempts allowed per run)", max_steps);
  return max_steps;
}

/// The periodic components the steady-state functions compare: `periodic` (ValueError naming it
/// when empty - C++'s "all", here the audit integrals too - or out of range) or by default q,
/// q', x_d, x_d' (the first 2n + 2D), not the contact coordinates X (a neutral direction) nor
/// the audit integrals.
/// The default periodic components: q, q', x_d, x_d' of a FrictionDampedSystem (2n + 2D), z, z' of
/// a ContactSystem (z = q and the bodies' coordinates: 2n + 6B).
inline Index default_periodic_size(const System& system) { return 2 * system.num_modes() + 2 * system.num_dampers(); }
template <class Contact>
Index default_periodic_size(const ContactSystem<double, Contact>& system) { return 2 * system.num_coordinates(); }

template <class Sys>
std::vector<Index> periodic_set(const Sys& system, const std::optional<std::vector<Index>>& periodic,
                                const std::string& where) {
  if (!periodic) return ShootingOptions<double>::first(default_periodic_size(system));
  if (periodic->empty())
    throw std::invalid_argument(where + ": periodic must not be empty (None: the default q, q', x_d, x_d')");
  detail::require_indices(where, "periodic", *periodic, system.state_size());
  return *periodic;
}

/// outputs= and output_harmonics= of find_periodic_orbit and continue_orbits into `opt` (samples
/// raised to 2 H + 1 where below), and progress= (a callable or None) called with the GIL.
inline void set_outputs_and_progress(ShootingOptions<double>& opt, const std::optional<Eigen::MatrixXd>& outputs,
                                     int output_harmonics, const py::object& progress, const std::string& where) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw std::invalid_argument(where + ": progress must be None or a callable progress(report)");
  if (output_harmonics < 0) detail::throw_invalid(where, "output_harmonics must be >= 0", output_harmonics);
  if (outputs) {
    opt.outputs = *outputs;
    opt.output_harmonics = output_harmonics;
    if (opt.samples_per_period <= 2 * output_harmonics) opt.samples_per_period = 2 * output_harmonics + 1;
  }
  if (!progress.is_none())
    opt.progress = [&progress](const ShootingProgress& p) {
      py::gil_scoped_acquire gil;
      progress(p);
    };
}

/// The MonodromyMethod named `name` ("variational" or "finite_difference"); ValueError naming
/// `monodromy` otherwise.
inline MonodromyMethod monodromy_method(const std::string& name, const std::string& where) {
  if (name == "variational") return MonodromyMethod::Variational;
  if (name == "finite_difference") return MonodromyMethod::FiniteDifference;
  throw std::invalid_argument(where + ": monodromy must be 'variational' or 'finite_difference', got '" + name + "'");
}

/// The shooting options of find_periodic_orbit and continue_orbits. Default periodic set: q, q',
/// x_d, x_d' (2n + 2D), i.e. not the contact coordinates X (a neutral direction) nor the energy
/// quadratures (docs/steady_state.md).
template <class Sys>
ShootingOptions<double> shooting_options(const Sys& system, const std::optional<std::vector<Index>>& periodic,
                                         const std::string& monodromy, double tolerance, int max_iterations,
                                         double rtol, double atol, long max_steps, OrbitIntegrator integrator,
                                         const std::string& where) {
  ShootingOptions<double> opt;
  opt.integrator = integrator;
  opt.stepper.rtol = rtol;
  opt.stepper.atol = atol;
  opt.stepper.max_steps = checked_max_steps(max_steps, where);
  opt.tolerance = tolerance;
  opt.max_iterations = max_iterations;
  opt.monodromy = monodromy_method(monodromy, where);
  opt.periodic = periodic_set(system, periodic, where);
  return opt;
}

/// find_periodic_orbit's further ShootingOptions keywords (C++'s fields of the same names; the
/// orbit runs' max_step and guard_samples are the StepperOptions fields): validated by Shooting.
inline void set_orbit_details(ShootingOptions<double>& opt, int samples_per_period,
                              const std::optional<std::vector<Index>>& amplitude_components,
                              double multiplier_tolerance, double fd_step, bool control_sensitivities,
                              double max_step, long guard_samples) {
  opt.samples_per_period = samples_per_period;
  if (amplitude_components) opt.amplitude_components = *amplitude_components;
  opt.multiplier_tolerance = multiplier_tolerance;
  opt.fd_step = fd_step;
  opt.control_sensitivities = control_sensitivities;
  opt.stepper.max_step = max_step;
  opt.stepper.guard_samples = guard_samples;
}

/// The callables of a continuation (continue_orbits, PeriodDoubling, SymmetricBranches): ValueError
/// naming `parameter` unless callable, `start_mode` unless None or callable, `period` unless
/// callable or a float > 0 (TypeError when neither).
inline void check_callables(const std::string& where, const py::object& parameter, const py::object& period,
                            const py::object& start_mode) {
  if (!PyCallable_Check(parameter.ptr()))
    throw std::invalid_argument(where + ": parameter must be a callable parameter(system, p)");
  if (!PyCallable_Check(period.ptr())) {
    const double T = cast_as<double>(period, where + ": period must be a float or a callable period(p)");
    detail::require_positive(where, "period", T);
  }
  if (!start_mode.is_none() && !PyCallable_Check(start_mode.ptr()))
    throw std::invalid_argument(where + ": start_mode must be None or a callable start_mode(system, t, x, mode)");
}

/// The continuation options of continue_orbits' keywords over the range [p_min, p_max] (direction
/// +1; validated by the C++ classes that take them).
inline ContinuationOptions<double> continuation_options(double p_min, double p_max, double initial_step,
                                                        double min_step, double max_step, int max_points,
                                                        int max_corrector_iterations, int fast_iterations,
                                                        double growth, double section_margin, int chord_iterations,
                                                        bool wrap_section) {
  ContinuationOptions<double> co;
  co.parameter_min = p_min;
  co.parameter_max = p_max;
  co.initial_step = initial_step;
  co.min_step = min_step;
  co.max_step = max_step;
  co.max_points = max_points;
  co.max_corrector_iterations = max_corrector_iterations;
  co.fast_iterations = fast_iterations;
  co.growth = growth;
  co.section_margin = section_margin;
  co.chord_iterations = chord_iterations;
  co.wrap_section = wrap_section;
  return co;
}

/// One point of continue_orbits' branch.
struct PyContinuationPoint {
  double parameter = 0, step = 0;
  bool stability_changed = false;
  PyOrbit orbit;
};

/// The C++ point as PyContinuationPoint (no Python objects).
template <class Sys>
PyContinuationPoint to_py(const ContinuationPoint<Sys>& pt) {
  return PyContinuationPoint{pt.parameter, pt.step, pt.stability_changed, to_py(pt.orbit)};
}

/// The C++ points of a branch as PyContinuationPoints.
template <class Sys>
std::vector<PyContinuationPoint> to_py(const std::vector<ContinuationPoint<Sys>>& points) {
  std::vector<PyContinuationPoint> out;
  out.reserve(points.size());
  for (const auto& pt : points) out.push_back(to_py(pt));
  return out;
}

/// What wrap_section= does (continue_orbits, PeriodDoubling, SymmetricBranches).
constexpr const char* kWrapSectionDoc =
    "wrap_section (default True; ContinuationOptions::wrap_section) keeps the section in the first forcing period, "
    "t0 in [0, T(p)): the start's t0 becomes t0 - k T(p0), k = floor(t0 / T(p0)) (the forcing is T-periodic, so "
    "the orbit through (t0 - k T, x0) is the one through (t0, x0)), and a section moved past T(p) by "
    "section_margin goes back by whole periods; at a late section t0 = k T the state x0(t0) turns with the forcing "
    "phase w t0 as the frequency w varies, |dx0/dw| ~ |x| t0, which winds a frequency branch into a helix the "
    "predictor misses. False: t0 as given (a system whose time dependence is not T(p)-periodic).";

/// One part of continue_orbits(parts = n > 1) (SplitContinuation's ContinuationPart).
struct PyContinuationPart {
  double start_parameter = 0;
  ContinuationStatus status = ContinuationStatus::Completed;
  std::string message;
  std::size_t points = 0, kept = 0;
  bool joined = false;
  double cpu_seconds = 0;
  std::vector<PyContinuationPoint> dropped;  // the part's own points when the branch does not hold them
};

/// What continue_orbits returns.
struct PyContinuation {
  ContinuationStatus status = ContinuationStatus::Completed;
  std::string message;
  std::vector<PyContinuationPoint> points;
  std::vector<PyContinuationPart> parts;  // empty for parts = 1
};

/// The contacts of a system (continue_orbits checks that parameter(system, p) keeps them).
inline Index num_contacts_of(const System& system) { return system.num_dampers(); }
template <class Contact>
Index num_contacts_of(const ContactSystem<double, Contact>& system) {
  return system.num_contacts();
}

/// The Python callables of continue_orbits (or of the branch switching classes: `caller`) as
/// Continuation's std::functions (Py: the Python system type). They hold no Python reference (the
/// callables outlive the run: they are the caller's arguments or members) and re-acquire the GIL,
/// which the run releases; a Python exception propagates as py::error_already_set through
/// Continuation::run (which catches nothing) to the caller.
template <class Py>
struct ContinuationCallbacks {
  using Sys = typename Py::Wrapped;

  const py::object* parameter = nullptr;   // parameter(system, p) -> the system at p
  const py::object* period = nullptr;      // a float or period(p)
  const py::object* start_mode = nullptr;  // None or start_mode(system, t, x, mode) -> mode
  const py::object* on_point = nullptr;    // None or on_point(point)
  const py::object* start = nullptr;       // None or start(system, p) -> (mode, t0, x0) (parts > 1)
  const char* caller = "continue_orbits";  // the Python function or class the messages name

  // The continued systems are Py objects (continue_orbits' system and its copies for parts > 1),
  // passed to the callables as themselves.
  static py::object as_python(Sys& system) {
    return py::cast(static_cast<Py*>(&system), py::return_value_policy::reference);
  }

  void set(Sys& system, double p) const {
    py::gil_scoped_acquire gil;
    const py::object r = (*parameter)(as_python(system), p);
    if (!py::isinstance<Py>(r))
      throw py::type_error(std::string(caller) + ": parameter(system, p) must return the " +
                           std::string(py::str(py::type::of<Py>().attr("__name__"))) + " at p, got " +
                           std::string(py::str(py::type::of(r).attr("__name__"))));
    const Py& next = r.cast<const Py&>();
    if (&next == &system) return;
    Sys copy = copy_of(next);  // under next's lock: another thread may be running it
    if (copy.state_size() != system.state_size() || num_contacts_of(copy) != num_contacts_of(system))
      throw std::invalid_argument(std::string(caller) +
                                  ": parameter(system, p) returned a system of another state size (" +
                                  std::to_string(copy.state_size()) + " instead of " +
                                  std::to_string(system.state_size()) + ")");
    system = std::move(copy);
  }
  double period_of(double p) const {
    // Called from the continuation's worker threads (parts > 1), which do not hold the GIL: even
    // reading a float object needs it.
    py::gil_scoped_acquire gil;
    if (!PyCallable_Check(period->ptr())) return period->cast<double>();  // checked by continue_orbits
    return cast_as<double>((*period)(p), std::string(caller) + ": period(p) must return a float");
  }
  Mode mode_of(Sys& system, double t, const State& x, const Mode& previous) const {
    py::gil_scoped_acquire gil;
    const py::object r = (*start_mode)(as_python(system), t, x, to_list(previous));
    const std::string what = std::string(caller) + ": start_mode(system, t, x, mode)";
    Mode mode = to_mode(cast_as<std::vector<ContactState>>(r, what + " must return a list of ContactState"));
    system.validate_state(mode, x, what.c_str());
    return mode;
  }
  void point(const ContinuationPoint<Sys>& pt) const {
    py::gil_scoped_acquire gil;
    (*on_point)(to_py(pt));
  }
  typename SplitContinuation<Sys>::Guess guess(Sys& system, double p) const {
    py::gil_scoped_acquire gil;
    const py::object r = (*start)(as_python(system), p);
    const std::string where = std::string(caller) + ": start(system, p)", what = where + " must return (mode, t0, x0)";
    const auto t = cast_as<std::tuple<py::object, py::object, py::object>>(r, what);
    typename SplitContinuation<Sys>::Guess g{
        to_mode(cast_as<std::vector<ContactState>>(std::get<0>(t), what + " with mode a list of ContactState")),
        cast_as<double>(std::get<1>(t), what + " with t0 a float"),
        cast_as<State>(std::get<2>(t), what + " with x0 a 1-D array of floats")};
    check_start(system, g.mode, g.x0, where);
    return g;
  }
};

}  // namespace stickslip_python
