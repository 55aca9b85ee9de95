// Python bindings of the impact options of a ContactSystem (docs/contacts.md, "Impacts"): the
// landing height of ContactSystemOptions and, on ContactSystem, BodyContactSystem and
// MixedContactSystem, the landing height in use and the count of impacts that fell back to
// frictionless impulses. The classes themselves are bound in stickslip_module.cpp.

#include "call_guard.hpp"

#include <stickslip/stickslip.hpp>

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace {

template <class Py>
void add_impact_members() {
  auto cls = py::reinterpret_borrow<py::class_<Py>>(py::type::of<Py>());
  cls.def("landing_height", [](const Py& s) { return s.landing_height(); },
          "The landing height in use [m]: options().landing_height, or its default for this frame (1e-8 of its "
          "size).")
      .def("frictionless_impacts", [](const Py& s) { return s.frictionless_impacts(); },
           "Impacts at which no stick / slip case satisfied Newton's and Coulomb's laws together, so that the "
           "landing contacts took frictionless impulses (docs/contacts.md, \"Impacts\").");
}

}  // namespace

void bind_impulse(py::module_& /*m*/) {
  using COptions = stickslip::ContactSystemOptions<double>;
  auto options = py::reinterpret_borrow<py::class_<COptions>>(py::type::of<COptions>());
  options.def_readwrite(
      "landing_height", &COptions::landing_height,
      "a landing whose rebound would rise less than this lands plastically (e = 0): an impact at normal "
      "velocity v_n bounces only when (e v_n)^2 / (2 a) > landing_height [m], a the pressing acceleration of the "
      "open contact. Negative (default -1): 1e-8 of the frame's size; 0: only the velocity tolerance");
  add_impact_members<stickslip_python::PyContactSystem>();
  add_impact_members<stickslip_python::PyBodyContactSystem>();
  add_impact_members<stickslip_python::PyMixedContactSystem>();
}
