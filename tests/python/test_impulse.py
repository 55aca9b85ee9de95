"""Impacts with Coulomb friction on the impulse and the landing rule of the contact systems in the
Python module (docs/contacts_impacts.md).

References that do not come from the code under test: the post-impact velocities of a point mass
hitting ground obliquely by hand (Newton's restitution, Coulomb's law for impulses), and the
geometric series of a bouncing body's impact times."""
import math

import numpy as np
import pytest

import stickslip as ss

PLATFORM = ss.SectionProperties(E=2.06e11, rho=7800, A=1e-4, I=1e-8)


def ground_scene(options, mu=0.3, e=0.5, load=0.0, gap=1e-4):
    """A body (m = 0.2 kg) over ground (normal +y), its contact at the centre of mass, and a
    one-mode cantilever it never touches."""
    frame = ss.FrameModel()
    root, tip = frame.add_node(0.0, 0.0), frame.add_node(0.0, 0.1)
    frame.add_member(root, tip, PLATFORM, 2)
    frame.clamp(root)
    basis = ss.compute_modes(frame, num_modes=1)
    loads = [ss.BodyLoad(ss.PlaneDirection.global_y(), -load)] if load else []
    body = ss.RigidBody(mass=0.2, inertia=1e-4, loads=loads)
    contact = ss.BodyContact.on_ground(ss.BodyPoint(0, np.zeros(2)), ss.PlaneDirection.global_y(),
                                       ss.CoulombLaw(mu, mu), e)
    contact.initial_gap = gap
    contact.initial_state = ss.ContactState.Separated
    return ss.BodyContactSystem(frame, basis, [body], [contact], [], options)


def tight():
    return ss.RunOptions("dopri5", rtol=1e-10, atol=1e-14)


def test_landing_height_option_and_default():
    options = ss.ContactSystemOptions()
    assert options.landing_height < 0  # the frame's default
    assert ground_scene(options).landing_height() == pytest.approx(1e-9, rel=1e-12)  # 1e-8 of 0.1 m
    options.landing_height = 2e-9
    assert ground_scene(options).options().landing_height == 2e-9
    assert ground_scene(options).landing_height() == 2e-9
    options.landing_height = float("nan")
    with pytest.raises(ValueError, match="landing_height"):
        ground_scene(options)


@pytest.mark.parametrize("u", [0.2, 1.5])
def test_oblique_impact_sticks_or_slides_as_the_closed_form(u):
    # Point mass, v = (u, -1), e = 0.5, mu = 0.3: sticks when |u| <= mu (1 + e) |v_n| = 0.45
    # (v_t after 0), else slides to u - 0.45; v_n after e |v_n|. One small solve: round-off.
    system = ground_scene(ss.ContactSystemOptions())
    x0 = system.initial_state()
    v = system.num_coordinates() + system.body_offset(0)
    x0[v], x0[v + 1] = u, -1.0
    run = ss.simulate(system, 1.01e-4, tight(), x0=x0)
    assert run.ok, run.message
    expected = 0.0 if abs(u) <= 0.45 else u - 0.45
    assert run.x[v] == pytest.approx(expected, abs=1e-12)
    assert run.x[v + 1] == pytest.approx(0.5, abs=1e-12)
    assert system.frictionless_impacts() == 0


def test_bouncing_body_comes_to_rest_as_the_geometric_series():
    # Pressed by P = 4 N (a = 20 m/s^2) from 1 mm: t1 = sqrt(2 g0 / a), rebound k flies 2 e^k t1
    # and rises e^2k g0; the landing rule lands the first impact K whose rebound would rise
    # <= landing_height, at t1 (1 + e) / (1 - e) - 2 e^K t1 / (1 - e).
    options = ss.ContactSystemOptions()
    options.landing_height = 2e-9
    e, a, g0 = 0.5, 20.0, 1e-3
    system = ground_scene(options, e=e, load=4.0, gap=g0)
    t1 = math.sqrt(2 * g0 / a)
    K = 1
    while e**(2 * K) * g0 > options.landing_height:
        K += 1
    t_rest = t1 * (1 + e) / (1 - e)
    run = ss.simulate(system, 2 * t_rest, tight())
    assert run.ok, run.message
    events = system.events()
    assert len(events) == K
    assert events[-1].to_state == ss.ContactState.Stick
    assert events[-1].t == pytest.approx(t_rest - 2 * e**K * t1 / (1 - e), abs=1e-9)
