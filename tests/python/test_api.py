"""The Python API against the C++ one (docs/python.md, "Python and C++"): every public class,
function, method, property and enum value has a docstring of its own; C++ functions are Python
methods (not properties); the composition layer's accessors reached from Python agree with
independent computations (closed forms, the model's own point shapes)."""
import inspect
import math
import re

import numpy as np
import pytest

import stickslip as ss

# pybind11 writes each overload's signature ("name(arg: type, ...) -> type") into __doc__ by
# itself; a docstring is what remains once those lines are removed.
SIGNATURE = re.compile(r"^\s*(\d+\.\s+)?[A-Za-z_][A-Za-z_0-9]*\(.*\)(\s*->\s*.+)?\s*$")


def own_text(doc):
    """The parts of a pybind11 docstring that are not signatures: one string per overload."""
    lines = (doc or "").splitlines()
    if lines and lines[0].strip() == "Overloaded function.":
        parts, current = [], []
        for line in lines[1:]:
            if re.match(r"^\d+\.\s+\S+\(", line):
                if current or parts:
                    parts.append(current)
                current = []
            elif line.strip():
                current.append(line)
        parts.append(current)
        return [" ".join(p).strip() for p in parts]
    return [" ".join(line for line in lines if line.strip() and not SIGNATURE.match(line)).strip()]


def enum_member_docs(cls):
    """{member name: its docstring} from the "Members:" section pybind11 writes for an enum."""
    doc = cls.__doc__ or ""
    head, _, members = doc.partition("Members:")
    out = {}
    for line in members.splitlines():
        name, sep, text = line.strip().partition(" : ")
        if name:
            out[name] = text.strip() if sep else ""
    return head.strip(), out


def is_enum(cls):
    return hasattr(cls, "__members__")


def undocumented(obj, where, missing):
    """Appends to `missing` every public part of a class (recursively) without a docstring."""
    if is_enum(obj):
        head, members = enum_member_docs(obj)
        if not head:
            missing.append(where)
        for name in obj.__members__:
            if not members.get(name):
                missing.append(where + "." + name)
        return
    if not (obj.__doc__ or "").strip():
        missing.append(where)
    for name, value in vars(obj).items():
        if name.startswith("_") and name not in ("__init__", "__call__", "__len__"):
            continue
        path = where + "." + name
        if inspect.isclass(value):
            undocumented(value, path, missing)
        elif isinstance(value, property):
            if not "".join(own_text(value.__doc__)):
                missing.append(path)
        else:
            function = getattr(obj, name)
            if not callable(function):
                continue
            if not all(own_text(function.__doc__)):
                missing.append(path)


def missing_docstrings(module):
    """The public names of `module` (recursively: classes' members, enum values) without a
    docstring (also used by scripts/python_api_reference.py)."""
    missing = []
    for name in dir(module):
        if name.startswith("_"):
            continue
        obj = getattr(module, name)
        if inspect.isclass(obj):
            undocumented(obj, name, missing)
        elif callable(obj):
            if not all(own_text(obj.__doc__)):
                missing.append(name)
    return missing


def test_every_public_class_function_property_and_enum_value_has_a_docstring():
    missing = missing_docstrings(ss)
    assert not missing, "without a docstring: " + ", ".join(missing)


def test_the_walk_finds_an_undocumented_member():
    # The check itself: pybind11's own signature is not a docstring.
    class Holder:
        """documented"""

        @property
        def bare(self):
            return 0

    found = []
    undocumented(Holder, "Holder", found)
    assert found == ["Holder.bare"]
    assert own_text("f(self: X, a: int) -> float\n") == [""]
    assert own_text("Overloaded function.\n\n1. f(a: int) -> int\n\nOne.\n\n2. f(a: str) -> int\n") == ["One.", ""]


# C++ functions that are Python methods, with the kind C++ gives them (the docs call them so).
CPP_FUNCTIONS = {
    "ModalBasis": ["omega", "frequencies_hz", "phi", "size", "num_free", "num_rigid_body_modes", "damping_ratios",
                   "damping_coefficients", "nodal", "expand", "nodal_displacements", "truncated"],
    "FrameModel": ["num_members", "num_nodes", "num_elements", "is_constrained", "node_position"],
    "FrictionDampedSystem": ["num_modes", "num_dampers", "state_size", "q_offset", "qd_offset", "x_offset",
                             "xd_offset", "contact_offset", "flight_offset", "num_separable", "flight_slot",
                             "energy_offset", "audit_size", "options", "dampers", "loads", "omega_squared",
                             "linear_rates", "stop_reason", "stop_damper", "load_fault", "events", "impacts"],
    "ContactSystem": ["num_modes", "num_contacts", "state_size", "audit_offset", "contacts", "loads", "options",
                      "linear_rates", "contact_row", "events"],
    "BodyContactSystem": ["num_modes", "num_bodies", "num_coordinates", "num_contacts", "state_size",
                          "audit_offset", "body_offset", "contacts", "bodies", "loads", "options", "linear_rates",
                          "contact_row", "events"],
    "CoulombLaw": ["mu_s", "mu_k", "static_coefficient", "kinetic_coefficient"],
    "EnergyBalance": ["relative_residual"],
    "PointDamper": ["effective_mass", "effective_stiffness"],
}


@pytest.mark.parametrize("cls", sorted(CPP_FUNCTIONS))
def test_cpp_functions_are_python_methods(cls):
    klass = getattr(ss, cls)
    kinds = {name: type(vars(klass).get(name)).__name__ for name in CPP_FUNCTIONS[cls]}
    assert all(not isinstance(vars(klass).get(name), property) and callable(getattr(klass, name, None))
               for name in CPP_FUNCTIONS[cls]), kinds


def cantilever(elements=20):
    frame = ss.FrameModel()
    root, tip = frame.add_node(0, 0), frame.add_node(0, 0.2)
    section = ss.SectionProperties(E=2.06e11, rho=7800, A=6e-5, I=2e-11)
    blade = frame.add_member(root, tip, section, elements)
    frame.clamp(root)
    return frame, root, tip, blade, section


def test_all_modes_one_per_free_dof_and_the_first_is_euler_bernoulli():
    frame, root, tip, blade, s = cantilever()
    basis = ss.compute_modes(frame, num_modes=None)
    # 21 nodes of 3 DOFs, the root's 3 clamped.
    assert basis.size() == len(basis) == basis.num_free() == 3 * frame.num_nodes() - 3 == 60
    assert basis.phi().shape == (60, 60)
    assert np.all(np.diff(basis.omega()) >= 0)
    # Euler-Bernoulli cantilever: omega_1 = (1.87510407)^2 sqrt(EI / (rho A L^4)); 20 cubic
    # elements give it to ~1e-8 relative (their error falls as h^4), 1e-6 leaves margin.
    exact = 1.8751040687 ** 2 * math.sqrt(s.E * s.I / (s.rho * s.A * 0.2 ** 4))
    assert basis.omega()[0] == pytest.approx(exact, rel=1e-6)
    assert basis.frequencies_hz()[0] == pytest.approx(exact / (2 * math.pi), rel=1e-6)
    assert ss.compute_modes(frame).size() == 10  # the default


def test_nodal_rows_are_the_displacements_the_model_interpolates_at_the_node():
    frame, root, tip, blade, _ = cantilever()
    basis = ss.compute_modes(frame, num_modes=6)
    damper = ss.PointDamper(blade, 0.15, 0.01, 5e3, 5.0, ss.CoulombLaw(0.35, 0.3))
    system = ss.FrictionDampedSystem(frame, basis, [damper])
    # The tip's X row of Phi against the member's shape functions evaluated at its end (another
    # computation: the moving-load shapes); both are the same numbers up to round-off.
    np.testing.assert_allclose(basis.nodal(tip, ss.Dof.X),
                               system.point_shape(blade, 0.2, ss.LoadDirection.GlobalX), rtol=1e-12, atol=1e-12)
    assert basis.nodal(tip, ss.Dof.X).shape == (6,)
    np.testing.assert_array_equal(basis.nodal(root, ss.Dof.X), np.zeros(6))  # clamped
    q = np.linspace(1.0, -0.5, 6)
    u = basis.nodal_displacements(q)
    assert u.shape == (3 * frame.num_nodes(),)
    assert u[3 * tip + 0] == pytest.approx(basis.nodal(tip, ss.Dof.X) @ q, rel=1e-12)
    np.testing.assert_allclose(basis.expand(q), basis.phi() @ q, rtol=1e-12, atol=1e-15)
    with pytest.raises(ValueError, match="expand"):
        basis.expand(np.zeros(5))


def test_stuck_natural_modes_of_one_mode_and_one_damper_is_the_closed_form():
    # An L-frame: a clamped column and a horizontal arm at its top; a damper on the arm slides
    # along X, which the column's first bending mode moves (b = the arm's axial shape).
    frame = ss.FrameModel()
    root, top, end = frame.add_node(0, 0), frame.add_node(0, 0.2), frame.add_node(0.1, 0.2)
    section = ss.SectionProperties(E=2.06e11, rho=7800, A=6e-5, I=2e-11)
    frame.add_member(root, top, section, 10)
    arm = frame.add_member(top, end, section, 5)
    frame.clamp(root)
    basis = ss.compute_modes(frame, num_modes=4).truncated(1)
    options = ss.ModelOptions()
    options.normal_load = ss.NormalLoad.Constant  # no a a^T term: M = 1 + s m b^2
    m, k, share = 0.01, 5e3, 0.5
    damper = ss.PointDamper(arm, 0.05, m, k, 5.0, ss.CoulombLaw(0.35, 0.3), share)
    system = ss.FrictionDampedSystem(frame, basis, [damper], [], options)
    b = system.point_shape(arm, 0.05, ss.LoadDirection.Axial)[0]
    assert abs(b) > 1  # the mode moves the damper: the check is not trivial
    w2 = basis.omega()[0] ** 2
    expected = math.sqrt((w2 + share * k * b * b) / (1 + share * m * b * b))  # K v = omega^2 M v, 1 x 1
    stuck = ss.stuck_natural_modes(system)
    assert stuck.omega.shape == (1,) and stuck.shapes.shape == (1, 1)
    assert stuck.omega[0] == pytest.approx(expected, rel=1e-12)
    assert stuck.frequencies_hz()[0] == pytest.approx(expected / (2 * math.pi), rel=1e-12)
    # At another contact coordinate, b changes with it.
    b2 = system.point_shape(arm, 0.08, ss.LoadDirection.Axial)[0]
    expected2 = math.sqrt((w2 + share * k * b2 * b2) / (1 + share * m * b2 * b2))
    assert ss.stuck_natural_modes(system, np.array([0.08])).omega[0] == pytest.approx(expected2, rel=1e-12)
    with pytest.raises(ValueError, match="X"):
        ss.stuck_natural_modes(system, np.zeros(2))
    assert damper.effective_mass() == pytest.approx(share * m) and damper.effective_stiffness() == pytest.approx(share * k)
