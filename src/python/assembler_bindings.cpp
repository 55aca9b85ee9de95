// Python bindings of the body contact's choices that make the paper's damper run through
// ContactSystem as it runs through FrictionDampedSystem (docs/contacts.md, "The paper's damper as
// a body"): ContactNormal, BodyContact's normal_behaviour, held_normal_force, at_lift_off,
// start_end and finish_end, and point_damper_body with the ModelOptions the damper runs under.

#include "call_guard.hpp"

#include <stickslip/stickslip.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_assembler(py::module_& m) {
  using namespace stickslip;
  using BContact = BodyContact<double>;
  py::enum_<ContactNormal>(m, "ContactNormal", "The normal of a BodyContact.")
      .value("Unilateral", ContactNormal::Unilateral,
             "N is solved to hold the gap closed; the contact opens at N = 0 (default)")
      .value("Held", ContactNormal::Held,
             "N = held_normal_force, given; the sides move freely along n and the contact never opens");
  auto contact = py::reinterpret_borrow<py::class_<BContact>>(m.attr("BodyContact"));
  contact
      .def_readwrite("normal_behaviour", &BContact::normal_behaviour,
                     "ContactNormal: Unilateral (default) or Held (N = held_normal_force)")
      .def_readwrite("held_normal_force", &BContact::held_normal_force, "N [N] > 0 of a Held normal")
      .def_readwrite("at_lift_off", &BContact::at_lift_off,
                     "Separation where a unilateral contact's N reaches zero: Separate (default: it opens) or Stop "
                     "(the run stops)")
      .def_readwrite("start_end", &BContact::start_end,
                     "MemberEnd of a moving side b at X = 0: Default or Stop stop the run, Extend continues with "
                     "the end element's shapes (Wall: ValueError)")
      .def_readwrite("finish_end", &BContact::finish_end, "MemberEnd of a moving side b at X = L, as start_end");
  m.def(
      "point_damper_body",
      [](const FrameModel<double>& frame, Eigen::Index body, const PointDamper<double>& damper,
         const ModelOptions<double>& options) { return point_damper_body(frame, body, damper, options); },
      py::arg("frame"), py::arg("body"), py::arg("damper"), py::arg("options"),
      "As point_damper_body(frame, body, damper), with the choices FrictionDampedSystem takes from `options` "
      "(ModelOptions): a constant normal load holds the contact's normal at N0 (ContactNormal.Held), "
      "Separation.Stop stops the run at a lift-off, moving_contact = False fixes the contact point, a Default "
      "member end follows end_policy (Throw: stop, Extrapolate: extend). ValueError naming the parameter: "
      "a Wall end, an extension under EndPolicy.Clamp, convective_terms = False with a moving contact point, "
      "watch_lift_off = False under an inertial normal load, a constant normal load with preload 0.");
}
