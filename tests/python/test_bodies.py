"""Rigid bodies, body contacts and the wedge damper in the Python module (docs/howto/python_contacts.md, "Rigid
bodies and the wedge damper").

References that do not come from the code under test: the wedge's statics by hand (the balance
of the preload P with the two face normal forces, and of their moments), the platforms' static
deflection from the modal basis (omega^2 q = Phi^T F), the energy balance, and the library's
error messages."""
import math

import numpy as np
import pytest

import stickslip as ss

PLATFORM = ss.SectionProperties(E=2.06e11, rho=7800, A=1e-4, I=1e-8)


class Platforms:
    """Two horizontal cantilever platforms of length 0.125 m, clamped at x = -0.25 and x = +0.25,
    their tips (the platform points) at x = -0.125 and x = +0.125."""

    def __init__(self, modes, damping=0.0):
        self.frame = ss.FrameModel()
        root_l, root_r = self.frame.add_node(-0.25, 0.0), self.frame.add_node(0.25, 0.0)
        self.tip_l, self.tip_r = self.frame.add_node(-0.125, 0.0), self.frame.add_node(0.125, 0.0)
        self.left = self.frame.add_member(root_l, self.tip_l, PLATFORM, 4)
        self.right = self.frame.add_member(root_r, self.tip_r, PLATFORM, 4)
        self.frame.clamp(root_l)
        self.frame.clamp(root_r)
        self.basis = ss.compute_modes(self.frame, num_modes=modes)
        if damping > 0:
            self.basis = self.basis.with_modal_damping(np.full(modes, damping))

    def row(self, node, d):
        """The structure part of a tip's displacement along d: its nodal rows (hand)."""
        return d[0] * self.basis.nodal(node, ss.Dof.X) + d[1] * self.basis.nodal(node, ss.Dof.Y)


class Wedge:
    """Face angles 30 and 45 degrees, one contact point per face at (-a, h) and (b, h); b (by hand)
    makes the frictionless normal forces' moments about the centre of mass cancel."""
    mass, inertia, P = 0.05, 2e-5, 100.0
    al, ar, a, h = math.pi / 6, math.pi / 4, 0.01, 0.004

    def __init__(self):
        # Statics by hand: N_l sin a_l = N_r sin a_r, N_l cos a_l + N_r cos a_r = P.
        self.Nl = self.P * math.sin(self.ar) / math.sin(self.al + self.ar)
        self.Nr = self.P * math.sin(self.al) / math.sin(self.al + self.ar)
        self.b = ((self.Nl * (self.a * math.cos(self.al) - self.h * math.sin(self.al))
                   + self.Nr * self.h * math.sin(self.ar)) / (self.Nr * math.cos(self.ar)))
        # Contact normals, platform -> damper: minus the faces' outward normals.
        self.nl = np.array([math.sin(self.al), -math.cos(self.al)])
        self.nr = np.array([-math.sin(self.ar), -math.cos(self.ar)])

    def build(self, p, law):
        left = ss.WedgeFace([ss.StructurePoint(p.left, 0.125)], np.array([-self.a, self.h]), self.al)
        right = ss.WedgeFace([ss.StructurePoint(p.right, 0.125)], np.array([self.b, self.h]), self.ar)
        return ss.wedge_damper(0, self.mass, self.inertia, self.P, left, right, law)

    def static_state(self, system, p):
        """Platforms deflected by the hand forces -N_k n_k, the damper translated so that both
        gaps are zero (n_k . (x, y) = n_k . u_k, theta = 0), at rest."""
        n = p.basis.size()
        x = system.initial_state()
        F = -self.Nl * p.row(p.tip_l, self.nl) - self.Nr * p.row(p.tip_r, self.nr)
        x[:n] = F / p.basis.omega() ** 2
        A = np.array([self.nl, self.nr])
        rhs = np.array([p.row(p.tip_l, self.nl) @ x[:n], p.row(p.tip_r, self.nr) @ x[:n]])
        x[n:n + 2] = np.linalg.solve(A, rhs)
        return x


def test_wedge_static_normal_forces_follow_the_hand_statics():
    p, w = Platforms(6), Wedge()
    wedge = w.build(p, ss.CoulombLaw(0.5, 0.5))
    assert len(wedge.contacts) == 2
    # The builder's normals are the faces' (turned from the radial +Y by the angles).
    np.testing.assert_allclose([wedge.contacts[0].normal.x, wedge.contacts[0].normal.y], w.nl, atol=1e-15)
    np.testing.assert_allclose([wedge.contacts[1].normal.x, wedge.contacts[1].normal.y], w.nr, atol=1e-15)
    system = ss.BodyContactSystem(p.frame, p.basis, [wedge.body], wedge.contacts)
    assert system.num_bodies() == 1 and system.num_coordinates() == 6 + 3 and system.body_offset(0) == 6
    e = system.evaluate(system.requested_mode(), 0.0, w.static_state(system, p))
    assert e["finite"]
    np.testing.assert_allclose(e["gap"], 0.0, atol=1e-15)
    # Rounding in a solve of condition ~1e4 (modal and body entries): 1e-9 of the load. The
    # mirror: N_r = P sin a_l / sin(a_l + a_r).
    assert e["N"][0] == pytest.approx(w.P * math.sin(w.ar) / math.sin(w.al + w.ar), abs=1e-9 * w.P)
    assert e["N"][1] == pytest.approx(w.P * math.sin(w.al) / math.sin(w.al + w.ar), abs=1e-9 * w.P)
    np.testing.assert_allclose(e["f"], 0.0, atol=1e-9 * w.P)  # the moments balance without friction
    assert np.max(np.abs(e["qdd"][-3:])) <= 1e-7 * w.P / w.mass  # the damper at rest


def test_wedge_stick_slip_run_closes_the_energy_balance():
    p, w = Platforms(4, damping=0.01), Wedge()
    wedge = w.build(p, ss.CoulombLaw(0.25, 0.2))
    W = 0.6 * float(p.basis.omega()[0])
    # The left platform shaken vertically at its tip.
    load = ss.PointLoad.harmonic(p.left, 0.125, ss.LoadDirection.GlobalY, 30.0, W)
    system = ss.BodyContactSystem(p.frame, p.basis, [wedge.body], wedge.contacts, [load])
    T = 2 * math.pi / W
    run = ss.simulate(system, 2 * T, ss.RunOptions("dopri5", rtol=1e-10, atol=1e-14, output_interval=T / 50),
                      x0=w.static_state(system, p), evaluate_from=0.0)
    assert run.ok, run.message
    events = system.events()
    assert len(events) >= 4  # stick-slip: the faces switch repeatedly
    assert any(e.to_state == ss.ContactState.Stick for e in events[2:])  # sticks again after slipping
    assert any(e.from_state == ss.ContactState.Separated for e in events)  # a face lifts off and lands
    assert np.max(np.abs(run.states[:, system.body_offset(0) + 2])) > 1e-6  # the damper turns [rad]
    assert run.states.shape[1] == system.state_size() == 2 * (4 + 3) + 3
    b = system.energy_balance(run.x, run.E0)
    assert b.friction_dissipation > 0
    # rtol 1e-10: the audit integrals carry the integration error, ~1e-9 of the work; stuck
    # projections and impacts are booked exactly.
    assert b.relative_residual() <= 1e-7
    assert run.energy.residual == pytest.approx(b.residual, abs=1e-15 * b.scale)
    assert run.forces["N"].shape == (len(run.force_t), 2)
    assert np.all(run.forces["N"] >= 0)  # unilateral: never tensile


def test_centrifugal_load_is_m_r_omega_squared():
    load = ss.BodyLoad.centrifugal(0.05, 0.3, 1000.0, ss.PlaneDirection.global_y())
    assert load(0.0) == pytest.approx(0.05 * 0.3 * 1000.0**2, rel=1e-15)
    assert (load.direction.x, load.direction.y) == (0.0, 1.0)


def test_bad_body_inputs_raise_naming_the_parameter():
    p = Platforms(4)
    law = ss.CoulombLaw(0.3, 0.3)
    on = ss.BodyContact.on_structure(ss.BodyPoint(0, np.array([0.0, 0.0])), ss.StructurePoint(p.left, 0.125),
                                     ss.PlaneDirection.global_y(), law)
    with pytest.raises(ValueError, match=r"body 0: mass must be finite and > 0"):
        ss.BodyContactSystem(p.frame, p.basis, [ss.RigidBody(mass=-1.0)], [on])
    with pytest.raises(ValueError, match=r"body 0: inertia must be finite and > 0"):
        ss.BodyContactSystem(p.frame, p.basis, [ss.RigidBody(inertia=0.0)], [on])
    with pytest.raises(ValueError, match=r"springs\[0\]: stiffness must be finite and >= 0"):
        spring = ss.BodySpring(np.zeros(2), ss.PlaneDirection.global_x(), -1.0)
        ss.BodyContactSystem(p.frame, p.basis, [ss.RigidBody(springs=[spring])], [on])
    with pytest.raises(ValueError, match=r"contact 0: a.body must name a body of the scene \(1 bodies\)"):
        ss.BodyContactSystem(p.frame, p.basis, [ss.RigidBody()],
                             [ss.BodyContact.on_ground(ss.BodyPoint(3, np.zeros(2)), ss.PlaneDirection.global_y(), law)])
    bouncy = ss.BodyContact.on_ground(ss.BodyPoint(0, np.zeros(2)), ss.PlaneDirection.global_y(), law, 1.5)
    with pytest.raises(ValueError, match=r"restitution must lie in \[0, 1\]"):
        ss.BodyContactSystem(p.frame, p.basis, [ss.RigidBody()], [bouncy])
    with pytest.raises(ValueError, match=r"wedge_damper: left.angle must lie in \(-pi/2, pi/2\)"):
        ss.wedge_damper(0, 0.1, 1e-5, 10.0, ss.WedgeFace([], np.zeros(2), 2.0), ss.WedgeFace([], np.zeros(2), 0.0), law)
    with pytest.raises(ValueError, match=r"wedge_damper: preload must be finite and >= 0"):
        ss.wedge_damper(0, 0.1, 1e-5, -1.0, ss.WedgeFace([], np.zeros(2), 0.1), ss.WedgeFace([], np.zeros(2), 0.1), law)
    with pytest.raises(ValueError, match=r"wedge_damper: law must be a CoulombLaw"):
        ss.wedge_damper(0, 0.1, 1e-5, 1.0, ss.WedgeFace([], np.zeros(2), 0.1), ss.WedgeFace([], np.zeros(2), 0.1), 0.3)
    with pytest.raises(ValueError, match="BodyLoad: time_function must be None or a callable F"):
        ss.BodyLoad(ss.PlaneDirection.global_y(), time_function=3.0)
    system = ss.BodyContactSystem(p.frame, p.basis, [ss.RigidBody()], [on])
    with pytest.raises(ValueError, match=r"BodyContactSystem.body_offset: b must be in \[0, num_bodies\(\) = 1\)"):
        system.body_offset(1)
    with pytest.raises(ValueError, match="simulate: x0 has size 3"):
        ss.simulate(system, 0.01, x0=np.zeros(3))
