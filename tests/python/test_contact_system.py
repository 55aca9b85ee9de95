"""Tests of ContactSystem in the Python module (docs/howto/python_contacts.md, "Contacts at structure points").

References that do not come from the code under test: Den Hartog's closed-form continuous-sliding
orbit of a forced oscillator with Coulomb friction (ported below), the energy balance, and the
library's error messages."""
import math

import numpy as np
import pytest

import stickslip as ss

STEEL = ss.SectionProperties(E=2.06e11, rho=7800, A=6e-5, I=2e-11)
LENGTH = 0.2


def cantilever(elements=10):
    """A clamped vertical cantilever along Y of `elements` elements, length 0.2 m."""
    frame = ss.FrameModel()
    root = frame.add_node(0.0, 0.0)
    tip = frame.add_node(0.0, LENGTH)
    member = frame.add_member(root, tip, STEEL, elements)
    frame.clamp(root)
    return frame, member


class DenHartogOrbit:
    """Den Hartog's steady orbit of m x'' + k x = F0 cos(w t) - mu_k N sgn(x') with continuous
    sliding (two stops per period, no stick). J. P. Den Hartog, "Forced vibrations with combined
    Coulomb and viscous friction", Trans. ASME APM-53-9 (1931) 107-115.

    The orbit is symmetric, x(t + T/2) = -x(t), with one half-period [t1, t1 + pi/w] where
    x' >= 0, x(t1) = -X, x'(t1) = 0. With tau = t - t1, theta = w t1, beta = w/wn,
    P = F0/(k (1 - beta^2)), a = mu_k N / k:
        x(tau) = C cos(wn tau) + D sin(wn tau) + P cos(w tau + theta) - a,
    D = P beta sin(theta), C = -X - P cos(theta) + a; the end conditions x(pi/w) = X,
    x'(pi/w) = 0 give sin(theta) = (a/P) U, X = -P cos(theta), U = tan(pi/(2 beta))/beta."""

    def __init__(self, m, k, F0, w, mu_k_N, mu_s_N):
        self.k, self.F0, self.w, self.a, self.mu_s_N = k, F0, w, mu_k_N / k, mu_s_N
        self.wn = math.sqrt(k / m)
        self.beta = w / self.wn
        self.P = F0 / (k * (1 - self.beta**2))
        U = math.tan(math.pi / (2 * self.beta)) / self.beta
        sin_theta = self.a * U / self.P
        assert abs(sin_theta) < 1, "no continuous-sliding orbit"
        cos_theta = (-1.0 if self.P > 0 else 1.0) * math.sqrt(1 - sin_theta**2)
        self.theta = math.atan2(sin_theta, cos_theta)
        self.X = -self.P * cos_theta
        self.C = -self.X - self.P * cos_theta + self.a
        self.D = self.P * self.beta * sin_theta
        self.T = 2 * math.pi / w
        self.t1 = math.fmod(self.theta / w + 2 * self.T, self.T)

    def x_half(self, tau):
        return (self.C * np.cos(self.wn * tau) + self.D * np.sin(self.wn * tau)
                + self.P * np.cos(self.w * tau + self.theta) - self.a)

    def v_half(self, tau):
        return (self.wn * (-self.C * np.sin(self.wn * tau) + self.D * np.cos(self.wn * tau))
                - self.P * self.w * np.sin(self.w * tau + self.theta))

    def state(self, t):
        """(x, v) at times t (array), by the half-period symmetry."""
        tau = np.mod(np.asarray(t, float) - self.t1, self.T)
        sign = np.where(tau < self.T / 2, 1.0, -1.0)
        tau = np.where(tau < self.T / 2, tau, tau - self.T / 2)
        return sign * self.x_half(tau), sign * self.v_half(tau)

    def physical(self):
        """x' > 0 inside the half period (no extra stop) and no stick at the reversal."""
        tau = math.pi / self.w * np.arange(1, 4000) / 4000
        f_required = self.k * self.X - self.F0 * math.cos(self.w * (self.t1 + self.T / 2))
        return bool(np.all(self.v_half(tau) > 0)) and self.X > 0 and abs(f_required) > self.mu_s_N


def den_hartog_scene(F0=20.0):
    """One retained mode of the cantilever with a grounded Coulomb slider at the tip and the tip
    force F0 cos(w t) [N]: with x = phi q the tip is the oscillator m = 1/phi^2, k = omega^2/phi^2."""
    frame, member = cantilever()
    basis = ss.compute_modes(frame, num_modes=1)
    wn = float(basis.omega()[0])
    w, mu, N = 0.6 * wn, 0.3, 15.0
    slider = ss.PointContact.grounded(ss.StructurePoint(member, LENGTH), ss.PlaneDirection.global_x(),
                                      ss.CoulombLaw(mu, mu), N)
    # F0 cos(w t) = F0 sin(w t + pi/2), applied at the tip along X (the load's own row).
    load = ss.PointLoad.harmonic(member, LENGTH, ss.LoadDirection.GlobalX, F0, w, math.pi / 2)
    system = ss.ContactSystem(frame, basis, [slider], [load])
    phi = float(system.contact_row(0)[0])
    m = 1 / phi**2
    orbit = DenHartogOrbit(m, wn**2 * m, F0, w, mu * N, mu * N)
    assert orbit.physical()
    return system, phi, orbit


def tight(output_interval):
    return ss.RunOptions("dopri5", rtol=1e-10, atol=1e-14, output_interval=output_interval)


def test_one_mode_with_a_tip_slider_follows_den_hartogs_orbit():
    system, phi, orbit = den_hartog_scene()
    # The contact's row is the tip's X row, the row through which the load enters: a wrong row
    # (another point, direction or scale) would break the agreement below.
    x = system.initial_state()
    x[0] = -orbit.X / phi  # on the orbit at its lower stop x = -X, v = 0 (time t1)
    ok, mode, x = system.make_consistent(system.requested_mode(), orbit.t1, x)
    assert ok and mode == [ss.ContactState.SlipPositive]
    run = ss.simulate(system, orbit.t1 + 4 * orbit.T, tight(orbit.T / 50), t0=orbit.t1, x0=x, mode=mode)
    assert run.ok, run.message
    xe, _ = orbit.state(run.sample_t)
    worst = np.max(np.abs(phi * run.states[:, 0] - xe))
    # rtol 1e-10 and event times located to ~1e-12 s: errors ~1e-9 X; 1e-6 X fails for a friction
    # force off by 1e-5 relative (dX/d(mu N) ~ X / F0 scale).
    assert worst <= 1e-6 * orbit.X
    # Two slip reversals per period and never a stick (mu_s = mu_k, continuous sliding).
    events = system.events()
    assert len(events) == 1 + 7  # the start, then 7 stops inside (t1, t1 + 4T)
    assert all(e.to_state != ss.ContactState.Stick for e in events)
    assert run.energy.relative_residual() <= 1e-7
    assert run.energy.friction_dissipation > 0


def test_stick_slip_run_closes_the_energy_balance():
    frame, member = cantilever()
    basis = ss.compute_modes(frame, num_modes=6).with_modal_damping(np.full(6, 0.02))
    W = 0.7 * float(basis.omega()[0])
    sliders = [
        ss.PointContact.grounded(ss.StructurePoint(member, LENGTH / 2), ss.PlaneDirection.global_x(),
                                 ss.CoulombLaw(0.35, 0.3), 3.0),
        ss.PointContact.grounded(ss.StructurePoint(member, LENGTH), ss.PlaneDirection.at_angle(0.3),
                                 ss.StribeckLaw(0.4, 0.3, 0.01), 2.0),
    ]
    load = ss.PointLoad.harmonic(member, LENGTH, ss.LoadDirection.GlobalX, 5.0, W)
    system = ss.ContactSystem(frame, basis, sliders, [load])
    run = ss.simulate(system, 0.3, ss.RunOptions("dopri5", rtol=1e-10, atol=1e-14), evaluate_from=0.0)
    assert run.ok, run.message
    events = system.events()
    # Stick-slip (normal forces chosen for it): both contacts stick and slip ~15 times each.
    for i in range(2):
        assert sum(1 for e in events if e.contact == i and e.to_state == ss.ContactState.Stick) >= 10
        assert sum(1 for e in events if e.contact == i and e.to_state != ss.ContactState.Stick) >= 10
    b = system.energy_balance(run.x, run.E0)
    assert b.friction_dissipation > 0.1 * b.external_work
    # rtol 1e-10: the audit integrals carry the integration error, ~1e-9 of the work.
    assert b.relative_residual() < 1e-6
    assert run.energy.residual == pytest.approx(b.residual, abs=1e-15 * b.scale)
    assert run.forces["N"].shape == (len(run.force_t), 2)
    assert np.all(run.forces["N"] == [3.0, 2.0])  # the held normal forces


def test_bad_contact_inputs_raise_naming_the_parameter():
    frame, member = cantilever(4)
    basis = ss.compute_modes(frame, num_modes=4)
    law = ss.CoulombLaw(0.3, 0.3)

    def grounded(coordinate=0.1, direction=ss.PlaneDirection.global_x(), N=1.0):
        return ss.PointContact.grounded(ss.StructurePoint(member, coordinate), direction, law, N)

    with pytest.raises(ValueError, match=r"PointContact.grounded: N must be finite and > 0"):
        grounded(N=-1.0)
    bad = grounded()
    bad.normal.value = -1.0
    with pytest.raises(ValueError, match="normal.value must be finite and > 0"):
        ss.ContactSystem(frame, basis, [bad])
    bad.normal = ss.HeldNormal(2.0)
    ss.ContactSystem(frame, basis, [bad])  # accepted again
    with pytest.raises(ValueError, match=r"contact 0: side a: coordinate must lie on member 0 \(valid range \[0, 0.2"):
        ss.ContactSystem(frame, basis, [grounded(coordinate=0.3)])
    with pytest.raises(ValueError, match="direction must be a unit vector"):
        ss.ContactSystem(frame, basis, [grounded(direction=ss.PlaneDirection(1.0, 1.0))])
    with pytest.raises(ValueError, match="side b must be another point"):
        ss.ContactSystem(frame, basis, [ss.PointContact.joint(ss.StructurePoint(member, 0.1),
                                                              ss.StructurePoint(member, 0.1),
                                                              ss.PlaneDirection.global_x(), law, 1.0)])
    with pytest.raises(ValueError, match="PointContact.grounded: law must be a CoulombLaw"):
        ss.PointContact.grounded(ss.StructurePoint(member, 0.1), ss.PlaneDirection.global_x(), 0.3, 1.0)
    with pytest.raises(ValueError, match="HeldNormal: time_function must be None or a callable N"):
        ss.HeldNormal(1.0, time_function=3.0)
    system = ss.ContactSystem(frame, basis, [grounded()])
    with pytest.raises(ValueError, match=r"contact_row: i must be in \[0, num_contacts\(\) = 1\)"):
        system.contact_row(1)
    with pytest.raises(ValueError, match="probes must be empty for a ContactSystem"):
        ss.simulate(system, 0.01, probes=[ss.Probe(member, 0.1)])
    with pytest.raises(ValueError, match="simulate: x0 has size 3"):
        ss.simulate(system, 0.01, x0=np.zeros(3))
    with pytest.raises(TypeError):
        ss.ContactSystem(frame, basis, [1.0])


def test_find_periodic_orbit_converges_on_den_hartogs_orbit():
    system, phi, orbit = den_hartog_scene()
    t0 = orbit.t1 + 0.2 * orbit.T  # inside the upward slide, away from the stops
    xe, ve = orbit.state(t0)
    guess = system.initial_state()
    guess[0], guess[1] = 1.05 * xe / phi, 0.95 * ve / phi  # 5 % off the orbit
    found = ss.find_periodic_orbit(system, orbit.T, t0=t0, x0=guess, mode=[ss.ContactState.SlipPositive])
    assert found.ok, found.message
    # Shooting to 1e-9 at rtol 1e-10: the fixed point to ~1e-10 X; 1e-6 X fails for a friction force
    # off by 1e-5 relative (2.7e-6 X).
    assert abs(phi * found.x0[0] - xe) <= 1e-6 * orbit.X
    assert abs(phi * found.x0[1] - ve) <= 1e-6 * orbit.X * orbit.wn
    assert found.switches == [2] and found.stick_fractions == [0.0]


def test_continue_orbits_follows_den_hartogs_orbits_in_the_load_amplitude():
    system, phi, orbit = den_hartog_scene()
    t0 = orbit.t1 + 0.2 * orbit.T  # inside the upward slide at every amplitude of the branch
    xe, ve = orbit.state(t0)
    x = system.initial_state()
    x[0], x[1] = xe / phi, ve / phi
    # p = F0 / 20 N, from 1 to 1.2; the period stays 2 pi / w.
    branch = ss.continue_orbits(system, lambda s, p: den_hartog_scene(20.0 * p)[0], 1.0, 1.2, orbit.T, t0=t0,
                                x0=x, mode=[ss.ContactState.SlipPositive], initial_step=0.05, max_step=0.1)
    assert branch.status == ss.ContinuationStatus.Completed, branch.message
    assert len(branch.points) >= 3 and np.all(np.diff(branch.parameters) > 0)  # the range left after p ~ 1.11
    for pt in branch.points:
        ref = den_hartog_scene(20.0 * pt.parameter)[2]
        xe, ve = ref.state(t0)
        # As find_periodic_orbit's fixed point above (shooting to 1e-9 at rtol 1e-10): 1e-6 X
        # fails for an orbit at the wrong amplitude (dX/dF0 ~ X / F0: 1e-6 X is 2e-5 N).
        assert abs(phi * pt.orbit.x0[0] - xe) <= 1e-6 * ref.X
        assert abs(phi * pt.orbit.x0[1] - ve) <= 1e-6 * ref.X * ref.wn
    with pytest.raises(TypeError, match="parameter\\(system, p\\) must return the ContactSystem at p, got float"):
        ss.continue_orbits(system, lambda s, p: 1.0, 1.0, 1.2, orbit.T, t0=t0, x0=x,
                           mode=[ss.ContactState.SlipPositive])
