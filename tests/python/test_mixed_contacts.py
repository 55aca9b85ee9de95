"""Mixed scenes (MixedContactSystem), the paper's damper as a body (point_damper_body) and the
exact orbit integrator (integrator=OrbitIntegrator.Exponential) in the Python module
(docs/contacts.md, "Mixed scenes" and "The paper's damper as a body").

References that do not come from the code under test: the single-kind BodyContactSystem (a mixed
scene holding only body contacts must repeat its run switch for switch), the energy balance,
FrictionDampedSystem (an independent implementation of the paper's damper: its own state layout,
contact coordinate and inertial normal solve) and the Dormand-Prince shooting of the same orbit."""
import math

import numpy as np
import pytest

import blade_scene as blade
import stickslip as ss
from test_bodies import Platforms, Wedge
from test_contact_system import den_hartog_scene


def shaken_wedge():
    """The wedge between the platforms, the left platform's tip shaken vertically (as
    test_bodies' stick-slip run), and a grounded slider at the left platform's middle."""
    p, w = Platforms(4, damping=0.01), Wedge()
    wedge = w.build(p, ss.CoulombLaw(0.25, 0.2))
    W = 0.6 * float(p.basis.omega()[0])
    load = ss.PointLoad.harmonic(p.left, 0.125, ss.LoadDirection.GlobalY, 30.0, W)
    slider = ss.PointContact.grounded(ss.StructurePoint(p.left, 0.0625), ss.PlaneDirection.global_y(),
                                      ss.CoulombLaw(0.35, 0.3), 50.0)
    return p, w, wedge, load, slider, 2 * math.pi / W


def tight(interval):
    return ss.RunOptions("dopri5", rtol=1e-10, atol=1e-14, output_interval=interval)


def test_mixed_scene_without_the_slider_repeats_the_body_contact_system():
    p, w, wedge, load, _, T = shaken_wedge()
    single = ss.BodyContactSystem(p.frame, p.basis, [wedge.body], wedge.contacts, [load])
    mixed = ss.MixedContactSystem(p.frame, p.basis, [wedge.body], list(wedge.contacts), [load])
    assert mixed.num_contacts() == 2 and mixed.state_size() == single.state_size()
    assert all(isinstance(c, ss.BodyContact) for c in mixed.contacts())
    runs = [ss.simulate(s, 2 * T, tight(T / 50), x0=w.static_state(s, p)) for s in (single, mixed)]
    for r in runs:
        assert r.ok, r.message
    a, b = single.events(), mixed.events()
    assert len(a) >= 8  # stick-slip and lift-off: the faces switch repeatedly (12 switches)
    # The same equations, solved by the same code paths on the same contacts: the same switches at
    # the same times (to the event location's 1e-12 s bracket; 1e-10 s leaves a factor 100).
    assert [(e.contact, e.from_state, e.to_state) for e in a] == [(e.contact, e.from_state, e.to_state) for e in b]
    assert max(abs(e.t - f.t) for e, f in zip(a, b)) <= 1e-10
    np.testing.assert_allclose(runs[1].x, runs[0].x, rtol=0, atol=1e-9 * np.max(np.abs(runs[0].x)))


def test_mixed_scene_with_the_slider_closes_its_energy_balance():
    p, w, wedge, load, slider, T = shaken_wedge()
    mixed = ss.MixedContactSystem(p.frame, p.basis, [wedge.body], list(wedge.contacts) + [slider], [load])
    assert mixed.num_contacts() == 3
    assert isinstance(mixed.contacts()[2], ss.PointContact)
    x0 = w.static_state(mixed, p)
    run = ss.simulate(mixed, T, tight(T / 50), x0=x0, evaluate_from=0.0)
    assert run.ok, run.message
    assert any(e.contact == 2 and e.to_state != ss.ContactState.Stick for e in mixed.events())  # the slider slips
    assert np.all(run.forces["N"][:, 2] == pytest.approx(50.0, rel=1e-15))  # its held normal
    b = mixed.energy_balance(run.x, run.E0)
    assert b.friction_dissipation > 0
    # rtol 1e-10: the audit integrals carry the integration error, ~1e-9 of the work (as the
    # wedge alone in test_bodies).
    assert b.relative_residual() <= 1e-7


def test_point_damper_body_follows_the_friction_damped_system():
    params = blade.BladeParameters(preload=2.7)
    scene = blade.make_blade_scene(params)
    fds = scene.system
    parts = [ss.point_damper_body(scene.frame, i, d) for i, d in enumerate(fds.dampers())]
    assert all(pt.contact.contact_point == ss.ContactPoint.Moving for pt in parts)
    bodies = ss.BodyContactSystem(scene.frame, scene.basis, [pt.body for pt in parts],
                                  [pt.contact for pt in parts], fds.loads())
    mixed = ss.MixedContactSystem(scene.frame, scene.basis, [pt.body for pt in parts],
                                  [pt.contact for pt in parts], fds.loads())
    duration = 0.05
    runs = [ss.simulate(s, duration, ss.RunOptions("dopri5", rtol=1e-11, atol=1e-15, output_interval=2e-4))
            for s in (fds, bodies, mixed)]
    for r in runs:
        assert r.ok, r.message
    ea = fds.events()
    assert len(ea) >= 10  # stick-slip of both dampers (20 switches over these 0.05 s)

    # The body's tangent is -u (t = (n_y, -n_x), n = -w): its slip direction is the damper's mirrored.
    def mirrored(s):
        return {ss.ContactState.SlipPositive: ss.ContactState.SlipNegative,
                ss.ContactState.SlipNegative: ss.ContactState.SlipPositive}.get(s, s)

    for system in (bodies, mixed):
        eb = system.events()
        assert [(e.damper, mirrored(e.from_state), mirrored(e.to_state)) for e in ea] == \
            [(e.contact, e.from_state, e.to_state) for e in eb]
        # As the C++ comparison (tests/model/contact_damper_test.cpp): both integrate the same
        # equations at rtol 1e-11 with their own arithmetic and states; the event times differ by
        # the integration and location error (measured 7.5e-13 s); 1e-10 s leaves a factor 100.
        assert max(abs(a.t - b.t) for a, b in zip(ea, eb)) <= 1e-10
    # The body scene's audit closes to the integration error (measured 1.3e-13 at rtol 1e-11;
    # 1e-10 leaves the C++ test's margin).
    assert runs[1].energy.relative_residual() <= 1e-10


def test_point_damper_body_rejects_a_wall():
    scene = blade.make_blade_scene(blade.BladeParameters(preload=2.7))
    d = scene.system.dampers()[0]
    d.finish_end = ss.MemberEnd.Wall
    with pytest.raises(ValueError, match="point_damper_body.*finish_end = Wall"):
        ss.point_damper_body(scene.frame, 0, d)
    d = scene.system.dampers()[0]
    d.member = 7
    with pytest.raises(ValueError, match="point_damper_body.*damper.member"):
        ss.point_damper_body(scene.frame, 0, d)


def test_body_contact_point_is_settable_and_checked():
    p = Platforms(2)
    on = ss.BodyContact.on_ground(ss.BodyPoint(0, np.zeros(2)), ss.PlaneDirection.global_y(), ss.CoulombLaw(0.3, 0.3))
    assert on.contact_point == ss.ContactPoint.Fixed
    on.contact_point = ss.ContactPoint.Moving
    with pytest.raises(ValueError, match="contact_point"):  # a moving side b needs b on the structure
        ss.MixedContactSystem(p.frame, p.basis, [ss.RigidBody()], [on])


def test_exponential_orbit_is_the_dormand_prince_orbit():
    system, phi, orbit = den_hartog_scene()
    t0 = orbit.t1 + 0.2 * orbit.T  # inside the upward slide, away from the stops
    xe, ve = orbit.state(t0)
    guess = system.initial_state()
    guess[0], guess[1] = 1.05 * xe / phi, 0.95 * ve / phi
    mode = [ss.ContactState.SlipPositive]
    dp = ss.find_periodic_orbit(system, orbit.T, t0=t0, x0=guess, mode=mode)
    ex = ss.find_periodic_orbit(system, orbit.T, t0=t0, x0=guess, mode=mode,
                                integrator=ss.OrbitIntegrator.Exponential)
    assert dp.ok, dp.message
    assert ex.ok, ex.message
    # Both shoot to 1e-9 (relative) at rtol 1e-10, the exact run's error ~ its event location:
    # the fixed points agree to ~1e-9 of X; 1e-6 X is Den Hartog's own check in
    # test_contact_system, which both must pass.
    assert abs(phi * ex.x0[0] - phi * dp.x0[0]) <= 1e-6 * orbit.X
    assert abs(phi * ex.x0[1] - phi * dp.x0[1]) <= 1e-6 * orbit.X * orbit.wn
    assert abs(phi * ex.x0[0] - xe) <= 1e-6 * orbit.X
    assert ex.switches == dp.switches == [2]
    # The exact runs' monodromy is by central differences, the Dormand-Prince one variational:
    # their multipliers differ by the difference step's error (measured 4.3e-6); 2e-5 of a
    # modulus ~0.42 leaves a factor 4.
    np.testing.assert_allclose(abs(ex.multipliers), abs(dp.multipliers), atol=2e-5)
    # Different runs: the fixed points differ in their last digits (measured 3.8e-11); were the
    # keyword ignored, both calls would be the same computation, bitwise equal.
    assert not np.array_equal(ex.x0, dp.x0)
