// Python bindings of bifurcations and branch switching on the branches continue_orbits computes
// (docs/python_branches.md): locate_bifurcations and Branch.bifurcations, PeriodDoubling (the flip
// located, the period-2T branch), SymmetricBranches (a multiplier through +1 classified by the
// symmetry of its Floquet vector, the pitchfork located, the asymmetric branch and the mirror image
// of a point). The C++ classes keep a reference to the system and std::functions; the Python
// classes keep the system and the callables as Python objects and build the C++ class per call,
// with the system locked and the GIL released (the callables take it back), as continue_orbits does.

#include "call_guard.hpp"
#include "continuation_support.hpp"

#include <stickslip/steady_state/bifurcation.hpp>
#include <stickslip/steady_state/period_doubling.hpp>
#include <stickslip/steady_state/pitchfork.hpp>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace {

using namespace stickslip_python;

/// A point as locate_bifurcations reads it: the parameter and the orbit's multipliers.
struct MultiplierPoint {
  using Scalar = double;
  double parameter = 0;
  struct {
    FloquetMultipliers<double> floquet;
  } orbit;
};

/// Attribute `name` of the Python object h as T (TypeError "<what>.<name> must be <kind>, got ..."
/// otherwise; AttributeError when h has no such attribute).
template <class T>
T attribute(const py::handle& h, const char* name, const std::string& what, const char* kind) {
  return cast_as<T>(h.attr(name), what + "." + name + " must be " + kind);
}

/// A Branch or a list of points (anything with .parameter and .orbit.multipliers) as the points
/// locate_bifurcations reads.
std::vector<MultiplierPoint> multiplier_points(const py::handle& points, const std::string& where) {
  py::object list = py::reinterpret_borrow<py::object>(points);
  if (py::isinstance<PyContinuation>(points)) list = points.attr("points");
  std::vector<MultiplierPoint> out;
  std::size_t i = 0;
  for (const py::handle pt : list) {
    const std::string name = where + ": points[" + std::to_string(i++) + "]";
    MultiplierPoint m;
    m.parameter = attribute<double>(pt, "parameter", name, "a float");
    m.orbit.floquet.multipliers =
        attribute<Eigen::VectorXcd>(pt.attr("orbit"), "multipliers", name + ".orbit", "a 1-D array of complex");
    out.push_back(std::move(m));
  }
  return out;
}

/// The system types of continue_orbits: f(py_system) for the one `system` is (TypeError otherwise).
template <class F>
auto dispatch(const py::handle& system, const std::string& where, F&& f) {
  if (py::isinstance<PySystem>(system)) return f(system.cast<PySystem&>());
  if (py::isinstance<PyContactSystem>(system)) return f(system.cast<PyContactSystem&>());
  if (py::isinstance<PyBodyContactSystem>(system)) return f(system.cast<PyBodyContactSystem&>());
  if (py::isinstance<PyMixedContactSystem>(system)) return f(system.cast<PyMixedContactSystem&>());
  throw py::type_error(where +
                       ": system must be a FrictionDampedSystem, ContactSystem, BodyContactSystem or "
                       "MixedContactSystem, got " +
                       std::string(py::str(py::type::of(system).attr("__name__"))));
}

/// The C++ orbit of a Python PeriodicOrbit (or any object with t0, period, x0, mode, monodromy and
/// optionally status) of `system`: ValueError naming `what` for an x0 or mode that does not fit the
/// system or a monodromy that is not square over the periodic components.
template <class Py>
PeriodicOrbit<typename Py::Wrapped> orbit_from_python(const Py& system, const ShootingOptions<double>& so,
                                                      const py::handle& h, const std::string& what) {
  PeriodicOrbit<typename Py::Wrapped> o;
  o.t0 = attribute<double>(h, "t0", what, "a float");
  o.period = attribute<double>(h, "period", what, "a float");
  o.x0 = attribute<State>(h, "x0", what, "a 1-D array of floats");
  o.mode = to_mode(attribute<std::vector<ContactState>>(h, "mode", what, "a list of ContactState"));
  o.monodromy = attribute<Eigen::MatrixXd>(h, "monodromy", what, "a 2-D array of floats");
  o.status = py::hasattr(h, "status") ? attribute<ShootingStatus>(h, "status", what, "a ShootingStatus")
                                      : ShootingStatus::Converged;
  detail::require_finite(what, "t0", o.t0);
  detail::require_positive(what, "period", o.period);
  check_start(system, o.mode, o.x0, what);
  if (!detail::all_finite(o.x0)) throw std::invalid_argument(what + ": x0 must be finite");
  const auto np = static_cast<Index>(so.periodic_indices(o.x0.size()).size());
  if (o.monodromy.rows() != np || o.monodromy.cols() != np)
    detail::throw_invalid(what,
                          "monodromy must be square over the periodic components (" + std::to_string(np) + "), rows",
                          o.monodromy.rows());
  if (!detail::all_finite(o.monodromy)) throw std::invalid_argument(what + ": monodromy must be finite");
  o.floquet = floquet_multipliers<double>(o.monodromy, false, so.multiplier_tolerance);
  return o;
}

/// The C++ point of a Python ContinuationPoint (or any object with parameter and orbit).
template <class Py>
ContinuationPoint<typename Py::Wrapped> point_from_python(const Py& system, const ShootingOptions<double>& so,
                                                          const py::handle& h, const std::string& what) {
  ContinuationPoint<typename Py::Wrapped> pt;
  pt.parameter = attribute<double>(h, "parameter", what, "a float");
  detail::require_finite(what, "parameter", pt.parameter);
  pt.orbit = orbit_from_python(system, so, h.attr("orbit"), what + ".orbit");
  return pt;
}

/// A located flip as Python sees it (FlipPoint).
struct PyFlipPoint {
  bool ok = false;
  std::string message;
  double parameter = 0, multiplier = 0;
  PyOrbit orbit;
  Eigen::VectorXd eigenvector, tangent;
};

/// A multiplier through +1 on a symmetric branch as Python sees it (SymmetryBreakingPoint).
struct PySymmetryBreakingPoint {
  bool ok = false;
  std::string message;
  BifurcationKind kind = BifurcationKind::Fold;
  bool located = false;
  double parameter = 0, multiplier = 0;
  PyOrbit orbit;
  Eigen::VectorXd eigenvector, tangent;
};

/// A C++ branch as the Python Branch.
template <class Sys>
PyContinuation branch_to_py(const ContinuationResult<Sys>& r) {
  PyContinuation out;
  out.status = r.status;
  out.message = r.message;
  out.points = to_py(r.points);
  return out;
}

/// What PeriodDoubling and SymmetricBranches keep: the system and the callables (Python objects),
/// the shooting and continuation options built from the keywords.
struct PySwitching {
  py::object system, parameter, period, start_mode;
  ShootingOptions<double> shooting;
  ContinuationOptions<double> options;
};

/// The keywords shared by PeriodDoubling and SymmetricBranches into `s` (ValueError naming the
/// parameter for a bad one).
void set_up(PySwitching& s, const char* where, const py::object& system, const py::object& parameter,
            const py::object& period, double p_min, double p_max, const py::object& start_mode,
            const std::optional<std::vector<Index>>& periodic, const std::string& monodromy, double tolerance,
            int max_iterations, double rtol, double atol, double initial_step, double min_step, double max_step,
            int max_points, int max_corrector_iterations, int fast_iterations, double growth, double section_margin,
            int chord_iterations, long max_steps, const std::optional<Eigen::MatrixXd>& outputs, int output_harmonics,
            OrbitIntegrator integrator, bool wrap_section) {
  const std::string w = where;
  check_callables(w, parameter, period, start_mode);
  detail::require_finite(w, "p_min", p_min);
  detail::require_finite(w, "p_max", p_max);
  if (!(p_max > p_min)) detail::throw_invalid(w, "p_max must be > p_min", p_max);
  s.system = system;
  s.parameter = parameter;
  s.period = period;
  s.start_mode = start_mode;
  s.shooting = dispatch(system, w, [&](auto& sys) {
    ShootingOptions<double> so = shooting_options(sys, periodic, monodromy, tolerance, max_iterations, rtol, atol,
                                                  max_steps, integrator, w);
    set_outputs_and_progress(so, outputs, output_harmonics, py::none(), w);
    return so;
  });
  s.options = continuation_options(p_min, p_max, initial_step, min_step, max_step, max_points,
                                   max_corrector_iterations, fast_iterations, growth, section_margin, chord_iterations,
                                   wrap_section);
  s.options.validate(w);
}

/// The keyword arguments of set_up, after (system, parameter, period, p_min, p_max).
#define STICKSLIP_SWITCHING_ARGS                                                                                    \
  py::arg("start_mode") = py::none(), py::arg("periodic") = py::none(), py::arg("monodromy") = "variational",      \
  py::arg("tolerance") = 1e-9, py::arg("max_iterations") = 30, py::arg("rtol") = 1e-10, py::arg("atol") = 1e-12,   \
  py::arg("initial_step") = 0.01, py::arg("min_step") = 1e-6, py::arg("max_step") = 0.1,                          \
  py::arg("max_points") = 200, py::arg("max_corrector_iterations") = 8, py::arg("fast_iterations") = 3,            \
  py::arg("growth") = 1.5, py::arg("section_margin") = 0.02, py::arg("chord_iterations") = 0,                     \
  py::arg("max_steps") = StepperOptions<double>{}.max_steps, py::arg("outputs") = py::none(),                    \
  py::arg("output_harmonics") = 3, py::arg("integrator") = OrbitIntegrator::DormandPrince54,                      \
  py::arg("wrap_section") = true

/// The keywords' documentation (appended to the classes' constructors').
constexpr const char* kSwitchingKeywords =
    " parameter(system, p) returns the system at p and period is the forcing period T [s] (a float or period(p)), as "
    "for continue_orbits; [p_min, p_max] is the range of the continued branches (each goes away from its "
    "bifurcation until it leaves the range). The other keywords are continue_orbits' (their defaults: periodic "
    "None = the default components, monodromy 'variational', tolerance 1e-9, max_iterations 30, rtol 1e-10, "
    "atol 1e-12, initial_step 0.01, min_step 1e-6, max_step 0.1, max_points 200, max_corrector_iterations 8, "
    "fast_iterations 3, growth 1.5, section_margin 0.02, chord_iterations 0, outputs None, output_harmonics 3, "
    "integrator DormandPrince54, wrap_section True); use the same as for the branch the points come from. The "
    "methods lock the system, release the GIL (the callables take it back; a Python exception they raise "
    "propagates) and leave the system at the parameter of the last orbit; Ctrl-C stops them (KeyboardInterrupt).";

/// PeriodDoubling as Python sees it.
struct PyPeriodDoubling : PySwitching {};

/// SymmetricBranches as Python sees it.
struct PySymmetricBranches : PySwitching {
  Eigen::MatrixXd symmetry;
  py::object mode_image;
  double symmetry_tolerance = 1e-6;
  bool half_period_shift = false;
  std::optional<State> centre;  // None: the map S x
};

/// SymmetricBranches::HalfPeriodMultipliers as Python sees it.
struct PyHalfPeriodMultipliers {
  bool ok = false;
  std::string message;
  double asymmetry = 0;
  Eigen::VectorXcd eigenvalues;
};

/// The continuation callables of `s` for the system type Py.
template <class Py>
ContinuationCallbacks<Py> callbacks(const PySwitching& s, const char* caller) {
  return ContinuationCallbacks<Py>{&s.parameter, &s.period, &s.start_mode, nullptr, nullptr, caller};
}

/// The C++ PeriodDoubling of `s` on `system`, interrupted by `signals`.
template <class Py>
PeriodDoubling<typename Py::Wrapped> make_period_doubling(const PySwitching& s, Py& system,
                                                          const ContinuationCallbacks<Py>& cb, SignalCheck& signals) {
  using Sys = typename Py::Wrapped;
  ShootingOptions<double> so = s.shooting;
  so.interrupt = [&signals] { return signals(); };
  PeriodDoubling<Sys> pd(
      system, [&cb](Sys& x, double p) { cb.set(x, p); }, [&cb](double p) { return cb.period_of(p); }, so, s.options);
  if (!s.start_mode.is_none())
    pd.start_mode([&cb](Sys& x, double t, const State& xs, const Mode& prev) { return cb.mode_of(x, t, xs, prev); });
  return pd;
}

/// The C++ SymmetricBranches of `s` on `system`, interrupted by `signals` (none: never).
template <class Py>
SymmetricBranches<typename Py::Wrapped> make_symmetric(const PySymmetricBranches& s, Py& system,
                                                        const ContinuationCallbacks<Py>& cb, SignalCheck* signals) {
  using Sys = typename Py::Wrapped;
  ShootingOptions<double> so = s.shooting;
  if (signals) so.interrupt = [signals] { return (*signals)(); };
  SymmetricBranches<Sys> sb(
      system, [&cb](Sys& x, double p) { cb.set(x, p); }, [&cb](double p) { return cb.period_of(p); }, s.symmetry, so,
      s.options);
  sb.symmetry_tolerance(s.symmetry_tolerance);
  sb.half_period_shift(s.half_period_shift);
  if (s.centre) sb.symmetry_centre(*s.centre);
  if (!s.start_mode.is_none())
    sb.start_mode([&cb](Sys& x, double t, const State& xs, const Mode& prev) { return cb.mode_of(x, t, xs, prev); });
  if (!s.mode_image.is_none()) {
    const py::object* f = &s.mode_image;
    sb.mode_image([f](const Mode& m) {
      py::gil_scoped_acquire gil;
      const std::string what = "SymmetricBranches: mode_image(mode)";
      Mode out = to_mode(
          cast_as<std::vector<ContactState>>((*f)(to_list(m)), what + " must return a list of ContactState"));
      if (out.size() != m.size())
        detail::throw_invalid(what, "must return one state per contact (" + std::to_string(m.size()) + "), got",
                              out.size());
      return out;
    });
  }
  return sb;
}

/// f(system, callbacks, a, b): the points a and b of a Python call as C++ points of the system type
/// of `s` (ValueError naming where: a or b), and its callables.
template <class S, class F>
auto with_points(const S& s, const py::object& a, const py::object& b, const std::string& where, const char* caller,
                 F&& f) {
  return dispatch(s.system, where, [&](auto& system) {
    using Py = std::decay_t<decltype(system)>;
    const auto pa = point_from_python(system, s.shooting, a, where + ": a");
    const auto pb = point_from_python(system, s.shooting, b, where + ": b");
    const auto cb = callbacks<Py>(s, caller);
    return f(system, cb, pa, pb);
  });
}

template <class Sys>
PyFlipPoint flip_to_py(const FlipPoint<Sys>& f) {
  return PyFlipPoint{f.ok, f.message, f.parameter, f.multiplier, to_py(f.orbit), f.eigenvector, f.tangent};
}

template <class Sys>
PySymmetryBreakingPoint symmetry_to_py(const SymmetryBreakingPoint<Sys>& c) {
  return PySymmetryBreakingPoint{c.ok,         c.message,     c.kind,        c.located, c.parameter,
                                 c.multiplier, to_py(c.orbit), c.eigenvector, c.tangent};
}

/// A flip or symmetry-breaking point of Python back in C++ (ok; parameter, multiplier, orbit,
/// eigenvector and tangent), checked against `system` and its periodic components (ValueError
/// naming `what`).
template <class Point, class From, class Py>
Point switching_point_from_python(const From& from, const Py& system, const ShootingOptions<double>& so,
                                  const std::string& what) {
  Point out;
  out.ok = true;
  out.parameter = from.parameter;
  out.multiplier = from.multiplier;
  out.orbit = orbit_from_python(system, so, py::cast(from.orbit), what + ".orbit");
  const auto np = static_cast<Index>(so.periodic_indices(out.orbit.x0.size()).size());
  if (from.eigenvector.size() != np)
    detail::throw_invalid(what, "eigenvector must have one entry per periodic component (" + std::to_string(np) +
                                    "), size",
                          from.eigenvector.size());
  if (from.tangent.size() != np + 1)
    detail::throw_invalid(what, "tangent must have the periodic components and p (" + std::to_string(np + 1) +
                                    "), size",
                          from.tangent.size());
  out.eigenvector = from.eigenvector;
  out.tangent = from.tangent;
  return out;
}

}  // namespace

void bind_branches(py::module_& m) {
  py::enum_<BifurcationKind>(m, "BifurcationKind",
                             "What happened between two points of a branch (BifurcationPoint.kind).")
      .value("Fold", BifurcationKind::Fold,
             "a real multiplier through +1 where the branch turns back in the parameter")
      .value("Pitchfork", BifurcationKind::Pitchfork,
             "a real multiplier through +1 where the branch goes on in the same direction (a branch point: "
             "symmetry-breaking pitchfork or transcritical)")
      .value("PeriodDoubling", BifurcationKind::PeriodDoubling,
             "a real multiplier through -1 (flip): a branch of period-2T orbits is born")
      .value("NeimarkSacker", BifurcationKind::NeimarkSacker,
             "a complex pair through the unit circle: a torus (quasi-periodic response) is born");

  using BP = BifurcationPoint<double>;
  py::class_<BP>(m, "BifurcationPoint",
                 "A bifurcation between points `before` and `before + 1` of a branch (locate_bifurcations, "
                 "Branch.bifurcations; docs/python_branches.md).")
      .def_readonly("kind", &BP::kind, "which multiplier crossed, and how (BifurcationKind)")
      .def_readonly("before", &BP::before, "index of the point before the crossing (the next one is after it)")
      .def_readonly("parameter", &BP::parameter,
                    "the parameter where the crossing multiplier's modulus, interpolated linearly between the two "
                    "points, is 1 (units of the branch's p)")
      .def_readonly("destabilising", &BP::destabilising,
                    "True: a multiplier left the unit circle (one more outside at the second point); False: it came "
                    "back in")
      .def("__repr__", [](const BP& b) {
        return std::string("BifurcationPoint(kind=") + to_string(b.kind) + ", before=" + std::to_string(b.before) +
               ", parameter=" + std::string(py::str(py::float_(b.parameter))) +
               ", destabilising=" + (b.destabilising ? "True" : "False") + ")";
      });

  m.def(
      "locate_bifurcations",
      [](const py::object& points, double tolerance) {
        static const std::string where = "locate_bifurcations";
        detail::require_non_negative(where, "tolerance", tolerance);
        return locate_bifurcations(multiplier_points(points, where), tolerance);
      },
      py::arg("points"), py::arg("tolerance") = 1e-6,
      "The bifurcations along `points` (a Branch, or a list of ContinuationPoints or of any objects with "
      ".parameter and .orbit.multipliers, in branch order) as a list of BifurcationPoint: between consecutive "
      "points whose numbers of multipliers outside the unit circle (|mu| > 1 + tolerance) differ, the kind whose "
      "count changed the way the total did. A crossing through +1 is a Fold when the parameter steps around it "
      "change sign, a Pitchfork when they keep one sign (with one step known: a Fold). tolerance (default 1e-6, "
      "dimensionless, >= 0) also separates real from complex multipliers (|Im mu| > tolerance |mu|).");
  py::class_<PyContinuation>(py::reinterpret_borrow<py::class_<PyContinuation>>(m.attr("Branch")))
      .def_property_readonly(
          "bifurcations",
          [](const PyContinuation& c) {
            std::vector<MultiplierPoint> pts;
            for (const auto& pt : c.points) {
              MultiplierPoint mp;
              mp.parameter = pt.parameter;
              mp.orbit.floquet.multipliers = pt.orbit.multipliers;
              pts.push_back(std::move(mp));
            }
            return locate_bifurcations(pts, ShootingOptions<double>{}.multiplier_tolerance);
          },
          "where multipliers crossed the unit circle between points, and how: locate_bifurcations(branch) at the "
          "shooting's multiplier tolerance 1e-6 (C++: ContinuationResult::bifurcations)");

  py::class_<PyFlipPoint>(m, "FlipPoint",
                          "A flip (period doubling) of a branch located to a tolerance (PeriodDoubling.locate_flip).")
      .def_readonly("ok", &PyFlipPoint::ok, "located; otherwise `message` says why not")
      .def_readonly("message", &PyFlipPoint::message, "why the location failed (empty when ok)")
      .def_readonly("parameter", &PyFlipPoint::parameter, "p at the flip (units of the branch's p)")
      .def_readonly("multiplier", &PyFlipPoint::multiplier,
                    "the real multiplier nearest -1 there (-1 to the tolerance; dimensionless)")
      .def_readonly("orbit", &PyFlipPoint::orbit, "the period-T PeriodicOrbit at the flip")
      .def_readonly("eigenvector", &PyFlipPoint::eigenvector,
                    "real eigenvector of the multiplier over the periodic components (numpy, max norm 1): the "
                    "direction in which the period-2T orbits leave the period-T orbit")
      .def_readonly("tangent", &PyFlipPoint::tangent,
                    "the period-T branch's unit tangent in (x_P, p) at the flip (numpy: the periodic components, "
                    "then p; the secant of the two points)");

  py::class_<PyHalfPeriodMultipliers>(
      m, "HalfPeriodMultipliers",
      "An orbit run over half its period under a symmetry with a half-period shift "
      "(SymmetricBranches.half_period_multipliers).")
      .def_readonly("ok", &PyHalfPeriodMultipliers::ok, "the run succeeded; otherwise see message")
      .def_readonly("message", &PyHalfPeriodMultipliers::message, "why not (empty when ok)")
      .def_readonly("asymmetry", &PyHalfPeriodMultipliers::asymmetry,
                    "max |x(t0 + T/2) - (c + S (x0 - c))| over the periodic components (0 for a symmetric orbit; "
                    "units of the state)")
      .def_readonly("eigenvalues", &PyHalfPeriodMultipliers::eigenvalues,
                    "eigenvalues of the half-period map H = S dx(t0 + T/2)/dx(t0) over the periodic components "
                    "(numpy, complex; the orbit's Floquet multipliers are their squares)");

  py::class_<PySymmetryBreakingPoint>(
      m, "SymmetryBreakingPoint",
      "A multiplier through +1 between two points of a symmetric branch (SymmetricBranches.classify, .locate).")
      .def_readonly("ok", &PySymmetryBreakingPoint::ok,
                    "classified (and, for a pitchfork from locate(), located); otherwise see message")
      .def_readonly("message", &PySymmetryBreakingPoint::message, "why not (empty when ok)")
      .def_readonly("kind", &PySymmetryBreakingPoint::kind,
                    "BifurcationKind.Pitchfork: the crossing multiplier's Floquet vector is antisymmetric (S v = -v), "
                    "symmetry breaking; BifurcationKind.Fold: it is symmetric (S v = v)")
      .def_readonly("located", &PySymmetryBreakingPoint::located,
                    "True: `parameter` is where the multiplier is 1 to locate()'s tolerance; False: the linear "
                    "interpolation between the two points (classify(), or a fold)")
      .def_readonly("parameter", &PySymmetryBreakingPoint::parameter, "p at the crossing (units of the branch's p)")
      .def_readonly("multiplier", &PySymmetryBreakingPoint::multiplier,
                    "the crossing multiplier at `orbit` (dimensionless)")
      .def_readonly("orbit", &PySymmetryBreakingPoint::orbit,
                    "the symmetric PeriodicOrbit nearest the crossing (at `parameter` when located)")
      .def_readonly("eigenvector", &PySymmetryBreakingPoint::eigenvector,
                    "real Floquet vector of the crossing multiplier over the periodic components (numpy, max norm 1)")
      .def_readonly("tangent", &PySymmetryBreakingPoint::tangent,
                    "the symmetric branch's unit tangent in (x_P, p) (numpy; the secant of the two points)");

  const std::string pd_doc =
      std::string("Branch switching at a period doubling of a branch of continue_orbits on `system` (a "
                  "FrictionDampedSystem, ContactSystem, BodyContactSystem or MixedContactSystem; TypeError otherwise). "
                  "C++ PeriodDoubling; docs/python_branches.md.") +
      kSwitchingKeywords + " " + kWrapSectionDoc;
  py::class_<PyPeriodDoubling>(m, "PeriodDoubling",
                               "Branch switching at a period doubling (flip) of a branch of continue_orbits: the flip "
                               "located by a secant on the multiplier through -1 (locate_flip), and the branch of "
                               "period-2T orbits born there (period_doubled_branch). docs/python_branches.md.")
      .def(py::init([](const py::object& system, const py::object& parameter, const py::object& period, double p_min,
                       double p_max, const py::object& start_mode, std::optional<std::vector<Index>> periodic,
                       const std::string& monodromy, double tolerance, int max_iterations, double rtol, double atol,
                       double initial_step, double min_step, double max_step, int max_points,
                       int max_corrector_iterations, int fast_iterations, double growth, double section_margin,
                       int chord_iterations, long max_steps, std::optional<Eigen::MatrixXd> outputs,
                       int output_harmonics, OrbitIntegrator integrator, bool wrap_section) {
             PyPeriodDoubling s;
             set_up(s, "PeriodDoubling", system, parameter, period, p_min, p_max, start_mode, periodic, monodromy,
                    tolerance, max_iterations, rtol, atol, initial_step, min_step, max_step, max_points,
                    max_corrector_iterations, fast_iterations, growth, section_margin, chord_iterations, max_steps,
                    outputs, output_harmonics, integrator, wrap_section);
             return s;
           }),
           py::arg("system"), py::arg("parameter"), py::arg("period"), py::arg("p_min"), py::arg("p_max"),
           STICKSLIP_SWITCHING_ARGS, pd_doc.c_str())
      .def(
          "locate_flip",
          [](const PyPeriodDoubling& s, const py::object& a, const py::object& b, double tolerance) {
            static const std::string where = "PeriodDoubling.locate_flip";
            detail::require_positive(where, "tolerance", tolerance);
            return with_points(s, a, b, where, "PeriodDoubling", [&](auto& system, const auto& cb, const auto& pa,
                                                                     const auto& pb) {
              return with_system(system, [&](SignalCheck& signals) {
                return flip_to_py(make_period_doubling(s, system, cb, signals).locate_flip(pa, pb, tolerance));
              });
            });
          },
          py::arg("a"), py::arg("b"), py::arg("tolerance") = 1e-8,
          "The flip between points a and b of a period-T branch (ContinuationPoints; e.g. points[k.before] and "
          "points[k.before + 1] of a BifurcationKind.PeriodDoubling of Branch.bifurcations) as a FlipPoint: the "
          "real multiplier mu nearest -1 driven to |mu + 1| <= tolerance (default 1e-8, dimensionless) by a secant "
          "in p (the bracket [a, b] kept), each orbit shot at fixed p. Not ok (message) when the points lie on "
          "different sections t0, no multiplier crosses -1 between them, a shooting fails or the secant does not "
          "converge in 40 orbits. ValueError naming a or b for a point that does not fit the system.")
      .def(
          "period_doubled_branch",
          [](const PyPeriodDoubling& s, const PyFlipPoint& flip, double offset) {
            static const std::string where = "PeriodDoubling.period_doubled_branch";
            if (!flip.ok) throw std::invalid_argument(where + ": flip must be located (ok)");
            detail::require_positive(where, "offset", offset);
            return dispatch(s.system, where, [&](auto& system) {
              using Py = std::decay_t<decltype(system)>;
              const auto f = switching_point_from_python<FlipPoint<typename Py::Wrapped>>(flip, system, s.shooting,
                                                                                          where + ": flip");
              const auto cb = callbacks<Py>(s, "PeriodDoubling");
              return with_system(system, [&](SignalCheck& signals) {
                return branch_to_py(make_period_doubling(s, system, cb, signals).period_doubled_branch(f, offset));
              });
            });
          },
          py::arg("flip"), py::arg("offset"),
          "The branch of period-2T orbits born at `flip` (an ok FlipPoint) as a Branch: the first orbit by Newton on "
          "x_P(t0 + 2 T(p)) - x_P = 0 with (x_P, p) at arclength `offset` (> 0, in the norm of (x_P, p)) from the "
          "flip along its eigenvector made orthogonal to the period-T branch, then continued (period 2 T(p)) away "
          "from the flip in p within [p_min, p_max]. Status StartFailed (message) when that first orbit does not "
          "converge or is the period-T orbit (raise the offset). ValueError for a flip that is not ok or an offset "
          "<= 0.");

  const std::string sb_doc =
      std::string("Symmetry breaking on the branches of continue_orbits on `system` (a FrictionDampedSystem, "
                  "ContactSystem, BodyContactSystem or MixedContactSystem; TypeError otherwise). symmetry is the "
                  "matrix S (numpy, state_size x state_size; "
                  "e.g. a permutation with signs) of a linear involution of the state (S S = I) that maps solutions "
                  "onto solutions (ValueError naming symmetry otherwise); mode_image(mode) -> mode gives the contact "
                  "states of a mirrored state (default: the same; e.g. two mirrored contacts swapped); an orbit "
                  "counts as symmetric when max |S x0 - x0| over its periodic components is at most "
                  "symmetry_tolerance max(1, max |x0|). half_period_shift=True: the symmetry acts with a shift by "
                  "half the forcing period T, x(t) solves the equations iff S x(t + T/2) does (mirror-image "
                  "substructures forced in antiphase, e.g. the two blades of a disk at engine order 1); a symmetric "
                  "orbit then has x(t0 + T/2) = S x(t0), its monodromy is M = H^2 with the half-period map "
                  "H = S dx(t0 + T/2)/dx(t0), and a multiplier of M through +1 is a symmetry-breaking pitchfork where "
                  "an eigenvalue of H crosses -1, a fold where one crosses +1 (classify and locate then run half a "
                  "period per orbit). symmetry_centre=c (numpy, state_size entries, finite; ValueError naming "
                  "symmetry_centre otherwise): the state the symmetry keeps fixed, the map x -> c + S (x - c) "
                  "(default None: S x), for coordinates that a mirror maps affinely (e.g. contact positions X -> "
                  "L - X).") +
      kSwitchingKeywords + " " + kWrapSectionDoc;
  py::class_<PySymmetricBranches>(
      m, "SymmetricBranches",
      "Symmetry breaking on the branches of continue_orbits (C++ SymmetricBranches; docs/python_branches.md): a "
      "multiplier through +1 on a branch of symmetric orbits (S x = x) classified by the symmetry of its Floquet "
      "vector (antisymmetric: a symmetry-breaking pitchfork; symmetric: a fold), the pitchfork located, the pair of "
      "asymmetric branches born there and the mirror image of a point.")
      .def(py::init([](const py::object& system, const py::object& parameter, const py::object& period,
                       const Eigen::MatrixXd& symmetry, double p_min, double p_max, const py::object& mode_image,
                       double symmetry_tolerance, const py::object& start_mode,
                       std::optional<std::vector<Index>> periodic, const std::string& monodromy, double tolerance,
                       int max_iterations, double rtol, double atol, double initial_step, double min_step,
                       double max_step, int max_points, int max_corrector_iterations, int fast_iterations,
                       double growth, double section_margin, int chord_iterations, long max_steps,
                       std::optional<Eigen::MatrixXd> outputs, int output_harmonics, OrbitIntegrator integrator,
                       bool wrap_section, bool half_period_shift, std::optional<State> symmetry_centre) {
             static const char* where = "SymmetricBranches";
             PySymmetricBranches s;
             set_up(s, where, system, parameter, period, p_min, p_max, start_mode, periodic, monodromy, tolerance,
                    max_iterations, rtol, atol, initial_step, min_step, max_step, max_points, max_corrector_iterations,
                    fast_iterations, growth, section_margin, chord_iterations, max_steps, outputs, output_harmonics,
                    integrator, wrap_section);
             if (!mode_image.is_none() && !PyCallable_Check(mode_image.ptr()))
               throw std::invalid_argument(std::string(where) +
                                           ": mode_image must be None or a callable mode_image(mode)");
             s.symmetry = symmetry;
             s.mode_image = mode_image;
             s.symmetry_tolerance = symmetry_tolerance;
             s.half_period_shift = half_period_shift;
             s.centre = std::move(symmetry_centre);
             dispatch(system, where, [&](auto& sys) {
               using Py = std::decay_t<decltype(sys)>;
               if (symmetry.rows() != sys.state_size())
                 detail::throw_invalid(where,
                                       "symmetry must be state_size() x state_size() (" +
                                           std::to_string(sys.state_size()) + "), rows",
                                       symmetry.rows());
               if (s.centre && s.centre->size() != sys.state_size())
                 detail::throw_invalid(where,
                                       "symmetry_centre must have state_size() (" + std::to_string(sys.state_size()) +
                                           ") entries, size",
                                       s.centre->size());
               if (s.centre && !detail::all_finite(*s.centre))
                 throw std::invalid_argument(std::string(where) + ": symmetry_centre must be finite");
               const auto cb = callbacks<Py>(s, where);
               make_symmetric(s, sys, cb, nullptr);  // validates the symmetry and the options
               return 0;
             });
             return s;
           }),
           py::arg("system"), py::arg("parameter"), py::arg("period"), py::arg("symmetry"), py::arg("p_min"),
           py::arg("p_max"), py::arg("mode_image") = py::none(), py::arg("symmetry_tolerance") = 1e-6,
           STICKSLIP_SWITCHING_ARGS, py::arg("half_period_shift") = false, py::arg("symmetry_centre") = py::none(),
           sb_doc.c_str())
      .def_readonly("symmetry", &PySymmetricBranches::symmetry, "the symmetry S (numpy, state_size x state_size)")
      .def_readonly("half_period_shift", &PySymmetricBranches::half_period_shift,
                    "True: the symmetry maps a solution x(t) onto S x(t + T/2) (symmetric orbits: x(t0 + T/2) = "
                    "S x(t0)); False: onto S x(t) (symmetric orbits: S x = x)")
      .def_readonly("symmetry_centre", &PySymmetricBranches::centre,
                    "the state c the symmetry keeps fixed, x -> c + S (x - c) (numpy), or None: the map S x")
      .def(
          "asymmetry",
          [](const PySymmetricBranches& s, const State& x) {
            return dispatch(s.system, "SymmetricBranches.asymmetry", [&](auto& system) {
              using Py = std::decay_t<decltype(system)>;
              const auto cb = callbacks<Py>(s, "SymmetricBranches");
              return make_symmetric(s, system, cb, nullptr).asymmetry(x);
            });
          },
          py::arg("x"),
          "max |c + S (x - c) - x| over the periodic components (c: symmetry_centre, default 0; 0 for a state "
          "that the symmetry maps onto itself; units of the state), whatever half_period_shift (with the shift, a "
          "symmetric orbit's defect is half_period_multipliers(point).asymmetry). ValueError when x's size is not "
          "the symmetry's.")
      .def(
          "multipliers_by_symmetry",
          [](const PySymmetricBranches& s, const Eigen::MatrixXd& monodromy) {
            return dispatch(s.system, "SymmetricBranches.multipliers_by_symmetry", [&](auto& system) {
              using Py = std::decay_t<decltype(system)>;
              const auto cb = callbacks<Py>(s, "SymmetricBranches");
              return make_symmetric(s, system, cb, nullptr).multipliers_by_symmetry(monodromy, system.state_size());
            });
          },
          py::arg("monodromy"),
          "The multipliers of a symmetric orbit's monodromy (PeriodicOrbit.monodromy) split by the symmetry of their "
          "Floquet vectors: (those on V+ = {S v = v}, those on V- = {S v = -v}), two complex numpy arrays. "
          "ValueError when the monodromy is not square over the periodic components, or with half_period_shift "
          "(the split then needs the half-period map: half_period_multipliers).")
      .def(
          "half_period_multipliers",
          [](const PySymmetricBranches& s, const py::object& point) {
            static const std::string where = "SymmetricBranches.half_period_multipliers";
            if (!s.half_period_shift) throw std::invalid_argument(where + ": needs half_period_shift=True");
            return dispatch(s.system, where, [&](auto& system) {
              using Py = std::decay_t<decltype(system)>;
              const auto pt = point_from_python(system, s.shooting, point, where + ": point");
              const auto cb = callbacks<Py>(s, "SymmetricBranches");
              return with_system(system, [&](SignalCheck& signals) {
                const auto h = make_symmetric(s, system, cb, &signals).half_period_multipliers(pt);
                return PyHalfPeriodMultipliers{h.ok, h.message, h.asymmetry, h.eigenvalues};
              });
            });
          },
          py::arg("point"),
          "With half_period_shift=True: the orbit of `point` (a ContinuationPoint, or any object with parameter and "
          "orbit.t0, .period, .x0, .mode, .monodromy; the system set to its parameter) run over half its period "
          "with its sensitivity, as a HalfPeriodMultipliers: asymmetry = max |x(t0 + T/2) - (c + S (x0 - c))| over "
          "the periodic components (0 for a symmetric orbit) and the eigenvalues of the half-period map "
          "H = S dx(t0 + T/2)/dx(t0) over them (the orbit's Floquet multipliers are their squares, M = H^2; an "
          "eigenvalue near -1 belongs to an antisymmetric Floquet vector, one near +1 to a symmetric one). Not ok "
          "(message) when the run fails. ValueError without half_period_shift or for a point that does not fit "
          "the system. Locks the system and releases the GIL.")
      .def(
          "classify",
          [](const PySymmetricBranches& s, const py::object& a, const py::object& b) {
            static const std::string where = "SymmetricBranches.classify";
            return with_points(s, a, b, where, "SymmetricBranches", [&](auto& system, const auto& cb,
                                                                        const auto& pa, const auto& pb) {
              // With half_period_shift it runs the system (half a period per point).
              return with_system(system, [&](SignalCheck& signals) {
                return symmetry_to_py(make_symmetric(s, system, cb, &signals).classify(pa, pb));
              });
            });
          },
          py::arg("a"), py::arg("b"),
          "The multiplier through +1 between points a and b of a symmetric branch (ContinuationPoints, or any "
          "objects with parameter and orbit.t0, .period, .x0, .mode, .monodromy) as a SymmetryBreakingPoint: "
          "Pitchfork when det(M - I) on V- changes sign between them (a real multiplier with an antisymmetric "
          "Floquet vector crossed +1), Fold when det(M - I) on V+ does; `parameter` interpolates that determinant's "
          "zero linearly. Not ok (message) when an orbit is not symmetric or neither determinant changes sign. "
          "Without half_period_shift it runs nothing. With it: an orbit is symmetric when "
          "max |x(t0 + T/2) - (c + S (x0 - c))| <= symmetry_tolerance max(1, max |x0|), and the half-period map "
          "H = S dx(t0 + T/2)/dx(t0) of each point (half a period run with its sensitivity) decides: Pitchfork when "
          "det(H + I) changes sign (an eigenvalue of H crossed -1), Fold when det(H - I) does.")
      .def(
          "locate",
          [](const PySymmetricBranches& s, const py::object& a, const py::object& b, double tolerance) {
            static const std::string where = "SymmetricBranches.locate";
            detail::require_positive(where, "tolerance", tolerance);
            return with_points(s, a, b, where, "SymmetricBranches", [&](auto& system, const auto& cb,
                                                                        const auto& pa, const auto& pb) {
              return with_system(system, [&](SignalCheck& signals) {
                return symmetry_to_py(make_symmetric(s, system, cb, &signals).locate(pa, pb, tolerance));
              });
            });
          },
          py::arg("a"), py::arg("b"), py::arg("tolerance") = 1e-8,
          "classify(a, b), and a pitchfork located: the V- multiplier mu nearest +1 driven to |mu - 1| <= "
          "tolerance (default 1e-8, dimensionless) by a secant in p on det(M - I) over V- (the bracket [a, b] "
          "kept), each orbit shot at fixed p from the nearer orbit made symmetric. A fold is returned as classified "
          "(not located). Not ok when the points lie on different sections t0, a shooting fails or the secant does "
          "not converge in 40 orbits. With half_period_shift the secant is on det(H + I), each orbit shot from the "
          "nearer orbit as it is, until the eigenvalue h of H nearest -1 has |h^2 - 1| <= tolerance (the "
          "multiplier h^2 at 1).")
      .def(
          "asymmetric_branch",
          [](const PySymmetricBranches& s, const PySymmetryBreakingPoint& pitchfork, double offset) {
            static const std::string where = "SymmetricBranches.asymmetric_branch";
            if (!pitchfork.ok || pitchfork.kind != BifurcationKind::Pitchfork)
              throw std::invalid_argument(where + ": pitchfork must be an ok symmetry-breaking pitchfork");
            detail::require_finite(where, "offset", offset);
            if (offset == 0) throw std::invalid_argument(where + ": offset must not be 0");
            return dispatch(s.system, where, [&](auto& system) {
              using Py = std::decay_t<decltype(system)>;
              auto c = switching_point_from_python<SymmetryBreakingPoint<typename Py::Wrapped>>(
                  pitchfork, system, s.shooting, where + ": pitchfork");
              c.kind = pitchfork.kind;
              c.located = pitchfork.located;
              const auto cb = callbacks<Py>(s, "SymmetricBranches");
              return with_system(system, [&](SignalCheck& signals) {
                return branch_to_py(make_symmetric(s, system, cb, &signals).asymmetric_branch(c, offset));
              });
            });
          },
          py::arg("pitchfork"), py::arg("offset"),
          "One of the asymmetric pair born at a located pitchfork (an ok SymmetryBreakingPoint of kind Pitchfork) as "
          "a Branch: the first orbit by Newton with (x_P, p) at signed arclength `offset` (non-zero, in the norm of "
          "(x_P, p)) from the pitchfork along the antisymmetric Floquet vector (the other sign gives the mirror "
          "image), then continued away from the pitchfork in p within [p_min, p_max]. Status StartFailed (message) "
          "when the first orbit does not converge, is the symmetric orbit (raise |offset|) or lies outside the "
          "range.")
      .def(
          "image",
          [](const PySymmetricBranches& s, const py::object& point) {
            static const std::string where = "SymmetricBranches.image";
            return dispatch(s.system, where, [&](auto& system) {
              using Py = std::decay_t<decltype(system)>;
              const auto pt = point_from_python(system, s.shooting, point, where + ": point");
              const auto cb = callbacks<Py>(s, "SymmetricBranches");
              return with_system(system, [&](SignalCheck& signals) {
                return to_py(make_symmetric(s, system, cb, &signals).image(pt));
              });
            });
          },
          py::arg("point"),
          "The mirror image of a point (a ContinuationPoint) as a ContinuationPoint: the orbit from "
          "(mode_image(mode), S x0) at the same p and t0, shot again (its outputs, events and multipliers are the "
          "image's own; the multipliers equal the point's). Its orbit is not ok when that shooting fails.");
}

#undef STICKSLIP_SWITCHING_ARGS
