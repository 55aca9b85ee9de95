"""The paper's damper as a body with the choices of its ModelOptions (point_damper_body(frame,
body, damper, options); docs/contacts.md, "The paper's damper as a body") in the Python module.

Reference that does not come from the code under test: FrictionDampedSystem, an independent
implementation of the damper (its own state layout, contact coordinate and normal force), run on
the same blade scene; and the library's error messages."""
import pytest

import blade_scene as blade
import stickslip as ss


def mirrored(s):
    """The body's tangent is -u (t = (n_y, -n_x), n = -w): its slip direction is the damper's mirrored."""
    return {ss.ContactState.SlipPositive: ss.ContactState.SlipNegative,
            ss.ContactState.SlipNegative: ss.ContactState.SlipPositive}.get(s, s)


def test_constant_normal_load_runs_as_the_friction_damped_system():
    options = ss.ModelOptions()
    options.normal_load = ss.NormalLoad.Constant
    scene = blade.make_blade_scene(blade.BladeParameters(preload=2.7, model=options))
    fds = scene.system
    parts = [ss.point_damper_body(scene.frame, i, d, options) for i, d in enumerate(fds.dampers())]
    for d, pt in zip(fds.dampers(), parts):
        assert pt.contact.normal_behaviour == ss.ContactNormal.Held
        assert pt.contact.held_normal_force == d.preload
    bodies = ss.BodyContactSystem(scene.frame, scene.basis, [pt.body for pt in parts],
                                  [pt.contact for pt in parts], fds.loads())
    run = ss.RunOptions("dopri5", rtol=1e-11, atol=1e-15, output_interval=2e-4)
    ra, rb = ss.simulate(fds, 0.03, run), ss.simulate(bodies, 0.03, run)
    assert ra.ok and rb.ok, (ra.message, rb.message)
    ea, eb = fds.events(), bodies.events()
    assert len(ea) >= 4  # both dampers stick and slip
    assert [(e.damper, mirrored(e.from_state), mirrored(e.to_state)) for e in ea] == \
        [(e.contact, e.from_state, e.to_state) for e in eb]
    # Both integrate the same equations at rtol 1e-11 (the C++ comparison's measured 1.1e-12 s;
    # 1e-10 s leaves a factor 100).
    assert max(abs(a.t - b.t) for a, b in zip(ea, eb)) <= 1e-10


def test_choices_map_and_are_settable():
    scene = blade.make_blade_scene(blade.BladeParameters(preload=2.7))
    d = scene.system.dampers()[0]
    options = ss.ModelOptions()
    options.end_policy = ss.EndPolicy.Extrapolate
    c = ss.point_damper_body(scene.frame, 0, d, options).contact
    assert (c.start_end, c.finish_end) == (ss.MemberEnd.Extend, ss.MemberEnd.Extend)
    assert c.at_lift_off == ss.Separation.Stop  # the damper's default: a lift-off stops the run
    assert c.normal_behaviour == ss.ContactNormal.Unilateral
    options.moving_contact = False
    assert ss.point_damper_body(scene.frame, 0, d, options).contact.contact_point == ss.ContactPoint.Fixed
    c.at_lift_off = ss.Separation.Separate
    c.start_end = ss.MemberEnd.Stop
    assert (c.at_lift_off, c.start_end) == (ss.Separation.Separate, ss.MemberEnd.Stop)


def test_choices_without_a_body_form_are_refused_naming_them():
    scene = blade.make_blade_scene(blade.BladeParameters(preload=2.7))
    d = scene.system.dampers()[0]
    options = ss.ModelOptions()
    options.end_policy = ss.EndPolicy.Clamp
    with pytest.raises(ValueError, match="Clamp"):
        ss.point_damper_body(scene.frame, 0, d, options)
    options = ss.ModelOptions()
    options.watch_lift_off = False
    with pytest.raises(ValueError, match="watch_lift_off"):
        ss.point_damper_body(scene.frame, 0, d, options)
    c = ss.point_damper_body(scene.frame, 0, d).contact
    c.normal_behaviour = ss.ContactNormal.Held  # held_normal_force 0
    with pytest.raises(ValueError, match="held_normal_force"):
        ss.BodyContactSystem(scene.frame, scene.basis, [ss.point_damper_body(scene.frame, 0, d).body], [c])
