// Python bindings of Integrator::Auto's rule (choose_integrator) on a FrictionDampedSystem; the
// enumerator Integrator.Auto itself is bound with the other integrators (stickslip_module.cpp).

#include "call_guard.hpp"

#include <stickslip/stickslip.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <tuple>

namespace py = pybind11;

void bind_auto(py::module_& m) {
  using stickslip_python::PySystem;
  using System = stickslip::FrictionDampedSystem<double>;
  m.def(
      "choose_integrator",
      [](PySystem& system, double t_end, double rtol) {
        const stickslip::IntegratorChoice choice =
            stickslip_python::with_system(system, [&](stickslip_python::SignalCheck&) {
              System& s = system;
              return stickslip::choose_integrator(s, s.requested_mode(), 0.0, s.initial_state(), t_end, rtol);
            });
        return std::make_tuple(std::string(stickslip::to_string(choice.integrator)), choice.reason);
      },
      py::arg("system"), py::arg("t_end"), py::arg("rtol") = 1e-6,
      "(name, reason): the integrator RunOptions(\"auto\") runs on `system` over [0, t_end] at rtol, and why "
      "(C++: choose_integrator; docs/howto/pick_an_integrator.md).");
}
