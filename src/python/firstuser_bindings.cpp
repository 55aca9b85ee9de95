// Python bindings of the steady-state helpers for a first-time user: orbit outputs at probes in
// physical units (OrbitProbe, probe_rows, OrbitSignal) and the progress reports of shooting and
// continuation (ShootingProgress, ContinuationProgress). docs/steady_state.md.

#include "call_guard.hpp"

#include <stickslip/steady_state/orbit_probe.hpp>
#include <stickslip/steady_state/orbit_signal.hpp>
#include <stickslip/steady_state/progress.hpp>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace py = pybind11;

void bind_firstuser(py::module_& m) {
  using namespace stickslip;
  using Probe = OrbitProbe<double>;
  using Signal = OrbitSignal<double>;

  py::enum_<ProbeQuantity>(m, "ProbeQuantity", "What an OrbitProbe measures at its point.")
      .value("Displacement", ProbeQuantity::Displacement, "the displacement along the direction [m]")
      .value("Velocity", ProbeQuantity::Velocity, "the velocity along the direction [m/s]");

  py::class_<Probe>(m, "OrbitProbe",
                    "A point of the structure whose displacement (or velocity) along an in-plane unit direction "
                    "every periodic orbit reports over its own period (outputs=probe_rows(...) of "
                    "find_periodic_orbit and continue_orbits; docs/steady_state.md, \"Probes in physical units\").")
      .def(py::init([](const StructurePoint<double>& point, const PlaneDirection<double>& direction,
                       ProbeQuantity quantity) { return Probe{point, direction, quantity}; }),
           py::arg("point"), py::arg("direction") = PlaneDirection<double>::global_x(),
           py::arg("quantity") = ProbeQuantity::Displacement,
           "The probe at `point` (a StructurePoint) along `direction` (a unit PlaneDirection, default global X), "
           "measuring `quantity` (default Displacement).")
      .def_readwrite("point", &Probe::point, "the StructurePoint (member, coordinate [m])")
      .def_readwrite("direction", &Probe::direction, "the unit PlaneDirection of the measured displacement")
      .def_readwrite("quantity", &Probe::quantity, "Displacement [m] or Velocity [m/s]");

  m.def(
      "probe_rows",
      [](const FrameModel<double>& frame, const ModalBasis<double>& basis, const std::vector<Probe>& probes,
         const stickslip_python::PySystem& system) {
        if (basis.size() != system.num_modes())
          detail::throw_invalid("probe_rows", "basis must have the system's modes (" +
                                                  std::to_string(system.num_modes()) + "), modes",
                                basis.size());
        return probe_rows(frame, basis, probes, system.state_size(), system.q_offset(), system.qd_offset());
      },
      py::arg("frame"), py::arg("basis"), py::arg("probes"), py::arg("system"),
      "The output rows (numpy, one row per probe, one column per state component of `system`, a "
      "FrictionDampedSystem built on `frame` and `basis`) of the probes: row j . x is probe j's displacement [m] "
      "(velocity [m/s]) psi(point) . q (q'). Pass them as outputs= to find_periodic_orbit or continue_orbits: every "
      "orbit's outputs[j] then holds probe j's min, max, amplitude, mean and harmonics over the orbit's period. "
      "ValueError naming probes[j] for a point off the frame or a direction that is not a unit vector.");

  py::class_<Signal>(m, "OrbitSignal",
                     "A linear output y = c . x (e.g. an OrbitProbe) over one period of an orbit, from the run that "
                     "closed it: y(t) ~ mean + sum_h (cosines[h-1] cos(h w (t - t0)) + sines[h-1] sin(h w (t - t0))), "
                     "w = 2 pi / T (docs/steady_state.md).")
      .def_readonly("min", &Signal::min, "smallest y over the period (every step, event and sample)")
      .def_readonly("max", &Signal::max, "largest y over the period")
      .def_readonly("mean", &Signal::mean, "(1/T) integral of y over the period")
      .def_readonly("cosines", &Signal::cosines, "cos coefficients of harmonics 1 .. output_harmonics (numpy)")
      .def_readonly("sines", &Signal::sines, "sin coefficients of harmonics 1 .. output_harmonics (numpy)")
      .def_property_readonly("amplitude", &Signal::amplitude, "half the peak-to-peak, (max - min) / 2")
      .def("harmonic", &Signal::harmonic, py::arg("h"),
           "|y_h| = hypot(cosines[h-1], sines[h-1]) for h in 1 .. output_harmonics (0 outside)");

  py::class_<ShootingProgress>(m, "ShootingProgress",
                               "What find_periodic_orbit's progress(report) receives after the guess's run and after "
                               "every Newton iteration (times: CPU seconds of the computing thread).")
      .def_readonly("iteration", &ShootingProgress::iteration, "Newton iterations done (0: the run of the guess)")
      .def_readonly("max_iterations", &ShootingProgress::max_iterations, "the iterations allowed")
      .def_readonly("runs", &ShootingProgress::runs, "orbit runs so far (iterations and backtracking trials)")
      .def_readonly("residual", &ShootingProgress::residual, "max |x_i(T) - x_i(0)| over the periodic components")
      .def_readonly("tolerance", &ShootingProgress::tolerance, "the residual Newton stops at")
      .def_readonly("cpu_seconds", &ShootingProgress::cpu_seconds, "CPU seconds since the computation started")
      .def_readonly("remaining_seconds", &ShootingProgress::remaining_seconds,
                    "estimated CPU seconds still needed (mean cost per iteration x the iterations the last "
                    "contraction rate needs; an estimate, not a bound)");

  py::class_<ContinuationProgress>(m, "ContinuationProgress",
                                   "What continue_orbits' progress(report) receives after each accepted point, "
                                   "before on_point (times: CPU seconds of the computing thread; with parts > 1 each "
                                   "part reports its own).")
      .def_readonly("points", &ContinuationProgress::points, "points of the branch so far (the start included)")
      .def_readonly("max_points", &ContinuationProgress::max_points, "the points allowed")
      .def_readonly("parameter", &ContinuationProgress::parameter, "the parameter of the newest point")
      .def_readonly("covered", &ContinuationProgress::covered,
                    "fraction of the way from p0 to the end of the range, in [0, 1]")
      .def_readonly("cpu_seconds", &ContinuationProgress::cpu_seconds, "CPU seconds since the run started")
      .def_readonly("seconds_per_point", &ContinuationProgress::seconds_per_point, "CPU seconds of the newest point")
      .def_readonly("remaining_seconds", &ContinuationProgress::remaining_seconds,
                    "estimated CPU seconds to the end of the range (cpu_seconds (1 - covered) / covered, at most the "
                    "mean per point times the points left; -1 at the start point, where nothing is covered yet; an "
                    "estimate, not a bound)");
}
