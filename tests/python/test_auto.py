"""Integrator.Auto and choose_integrator (docs/howto/pick_an_integrator.md): the blade's scene has
moving contacts and lightly damped modes, so the rule gives Dormand-Prince, and a run with
RunOptions("auto") names what it ran."""
import blade_scene as blade
import stickslip as ss


def test_auto_is_an_integrator():
    assert ss.RunOptions("auto").integrator == "auto"
    assert ss.Integrator.Auto != ss.Integrator.DormandPrince54
    assert ss.EventState.Checked != ss.EventState.Reintegrate


def test_blade_scene_gets_dormand_prince_with_a_reason():
    scene = blade.make_blade_scene(blade.BladeParameters(preload=2.7))
    name, reason = ss.choose_integrator(scene.system, 0.1, 1e-7)
    assert name == "dopri5"
    assert "not every mode is exactly linear" in reason
