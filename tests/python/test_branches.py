"""Bifurcations and branch switching from Python (docs/python_branches.md): locate_bifurcations and
Branch.bifurcations, PeriodDoubling, SymmetricBranches.

References that do not come from the code under test:
- constructed points whose multipliers are given, where the crossing parameter is the linear
  interpolation of |mu| - 1 (or of det(M - I) on a block) worked out by hand (the numbers of the
  C++ tests tests/steady_state/bifurcation_test.cpp and pitchfork_test.cpp);
- a clamped-clamped beam with a grounded Coulomb slider and a harmonic force at its midpoint,
  symmetric under the mirror x -> L - x. With two retained modes (the first symmetric, the second
  antisymmetric: zero at the midpoint), the slider and the load act on mode 1 alone: mode 1
  without viscous damping is Den Hartog's oscillator (its closed-form continuous-sliding orbit is
  DenHartogOrbit of test_contact_system.py), and mode 2 is a free damped oscillator whose
  multipliers are exp(lambda T), lambda = -zeta w2 +- i w2 sqrt(1 - zeta^2): the antisymmetric
  (V-) multipliers of every symmetric orbit. A free linear mode has no periodic orbit but rest,
  so no asymmetric orbit exists: a start along it fails.

The Python module has no smooth nonlinear system (a Duffing or the C++ tests' two-mass cubic
oscillator): a located flip and a located pitchfork against their closed forms are tested in C++
(tests/steady_state), not here."""
import math
import types

import numpy as np
import pytest

import stickslip as ss
from test_contact_system import DenHartogOrbit

STEEL = ss.SectionProperties(E=2.06e11, rho=7800, A=6e-5, I=2e-11)
LENGTH = 0.4
ZETA2 = 0.02  # modal damping ratio of the antisymmetric mode (mode 1: none, as Den Hartog's)


def fake_point(p, multipliers):
    """A point with only what locate_bifurcations reads: .parameter and .orbit.multipliers."""
    return types.SimpleNamespace(parameter=p, orbit=types.SimpleNamespace(multipliers=np.asarray(multipliers, complex)))


def pair(mu_a, mu_b, complex_pair=False):
    """The multipliers of the C++ test's 2 x 2 monodromies: (mu_a, mu_b), or mu_a e^{+-i}."""
    return [mu_a * np.exp(1j), mu_a * np.exp(-1j)] if complex_pair else [mu_a, mu_b]


def test_crossings_are_classified_by_the_multiplier_and_the_branch_turn():
    def one(points):
        found = ss.locate_bifurcations([fake_point(p, mu) for p, mu in points])
        assert len(found) == 1
        return found[0]

    # +1 with p increasing throughout: pitchfork where |mu| - 1 = -0.1 -> +0.1 interpolates to
    # 0, p = 1.5 (1e-12: the interpolation's round-off).
    b = one([(0, pair(0.8, 0.5)), (1, pair(0.9, 0.5)), (2, pair(1.1, 0.5)), (3, pair(1.2, 0.5))])
    assert b.kind == ss.BifurcationKind.Pitchfork and b.before == 1 and b.destabilising
    assert b.parameter == pytest.approx(1.5, abs=1e-12)
    # The same multipliers on a branch that turns (p 0, 1, 1.2, 1.1): a fold.
    b = one([(0, pair(0.8, 0.5)), (1, pair(0.9, 0.5)), (1.2, pair(1.1, 0.5)), (1.1, pair(1.2, 0.5))])
    assert b.kind == ss.BifurcationKind.Fold
    # Through -1 (|mu| - 1: -0.1 -> 0.3, zero at 0.25), and back in.
    b = one([(0, pair(-0.9, 0.5)), (1, pair(-1.3, 0.5))])
    assert b.kind == ss.BifurcationKind.PeriodDoubling and b.parameter == pytest.approx(0.25, abs=1e-12)
    b = one([(0, pair(-1.3, 0.5)), (1, pair(-0.9, 0.5))])
    assert b.kind == ss.BifurcationKind.PeriodDoubling and not b.destabilising
    # A complex pair through the circle (0.95 -> 1.05): Neimark-Sacker at 0.5.
    b = one([(0, pair(0.95, 0, True)), (1, pair(1.05, 0, True))])
    assert b.kind == ss.BifurcationKind.NeimarkSacker and b.parameter == pytest.approx(0.5, abs=1e-12)
    assert "neimark_sacker" in repr(b)
    # A pair colliding outside the circle into two real multipliers: no crossing.
    assert ss.locate_bifurcations([fake_point(0, pair(1.5, 0, True)), fake_point(1, pair(1.6, 1.4))]) == []
    with pytest.raises(ValueError, match="locate_bifurcations: tolerance"):
        ss.locate_bifurcations([], tolerance=-1.0)
    with pytest.raises(TypeError, match=r"points\[0\]\.parameter must be a float"):
        ss.locate_bifurcations([fake_point("p", [0.5])])


def beam():
    """The clamped-clamped beam along X (20 elements: the midpoint is a node), two modes."""
    frame = ss.FrameModel()
    a = frame.add_node(0.0, 0.0)
    b = frame.add_node(LENGTH, 0.0)
    member = frame.add_member(a, b, STEEL, 20)
    frame.clamp(a)
    frame.clamp(b)
    basis = ss.compute_modes(frame, num_modes=2).with_modal_damping(np.array([0.0, ZETA2]))
    return frame, member, basis


def mirror_parity(frame, member, basis):
    """+1 / -1 per mode: its transverse shape at L - x against at x (x = L / 4)."""
    def row(x):  # the modes' Y displacement at x: a slider's contact row there
        slider = ss.PointContact.grounded(ss.StructurePoint(member, x), ss.PlaneDirection.global_y(),
                                          ss.CoulombLaw(0.3, 0.3), 1.0)
        return np.asarray(ss.ContactSystem(frame, basis, [slider]).contact_row(0))

    left, right = row(LENGTH / 4), row(3 * LENGTH / 4)
    assert np.allclose(np.abs(left), np.abs(right), rtol=1e-9)  # each mode symmetric or antisymmetric
    return np.sign(right / left)


def beam_scene(F0=20.0):
    """The beam with the midpoint slider and the midpoint force F0 cos(w t) [N] along Y, w = 0.6
    w1; the mirror S (diag(s, s) on (q, q'), the audit integrals unchanged) and Den Hartog's orbit
    of mode 1 (x = phi q1 at the midpoint: m = 1 / phi^2, k = w1^2 / phi^2)."""
    frame, member, basis = beam()
    w1 = float(basis.omega()[0])
    w, mu, N = 0.6 * w1, 0.3, 15.0
    slider = ss.PointContact.grounded(ss.StructurePoint(member, LENGTH / 2), ss.PlaneDirection.global_y(),
                                      ss.CoulombLaw(mu, mu), N)
    load = ss.PointLoad.harmonic(member, LENGTH / 2, ss.LoadDirection.GlobalY, F0, w, math.pi / 2)
    system = ss.ContactSystem(frame, basis, [slider], [load])
    s = mirror_parity(frame, member, basis)
    S = np.diag(np.concatenate([s, s, np.ones(system.state_size() - 4)]))
    row = np.asarray(system.contact_row(0))
    phi = float(row[0])
    orbit = DenHartogOrbit(1 / phi**2, w1**2 / phi**2, F0, w, mu * N, mu * N)
    return system, S, row, phi, orbit


def symmetric_branch():
    system, S, row, phi, orbit = beam_scene()
    t0 = orbit.t1 + 0.2 * orbit.T  # inside the upward slide at every amplitude of the branch
    xe, ve = orbit.state(t0)
    x = system.initial_state()
    x[0], x[2] = xe / phi, ve / phi
    # p = F0 / 20 N from 1 to 1.2 at the fixed period 2 pi / w; t0 kept (section_margin 0) so that
    # the flip location below reaches its multiplier test.
    at = lambda s, p: beam_scene(20.0 * p)[0]
    branch = ss.continue_orbits(system, at, 1.0, 1.2, orbit.T, t0=t0, x0=x, mode=[ss.ContactState.SlipPositive],
                                initial_step=0.05, max_step=0.1, section_margin=0.0)
    return system, S, row, phi, orbit, t0, at, branch


def test_mirror_symmetric_beam_branch_its_antisymmetric_multipliers_and_no_asymmetric_orbit():
    system, S, row, phi, orbit, t0, at, branch = symmetric_branch()
    # The scene as described: mode 1 symmetric, mode 2 antisymmetric, which the midpoint slider
    # does not move (its row's mode-2 entry, 5e-12 of mode 1's, is the eigensolver's error).
    assert np.array_equal(np.diag(S)[:2], [1.0, -1.0])
    assert abs(row[1]) <= 1e-10 * abs(row[0])
    assert orbit.physical()
    assert branch.status == ss.ContinuationStatus.Completed, branch.message
    assert len(branch.points) >= 3
    frame, member, basis = beam()
    w2 = float(basis.omega()[1])
    lam = -ZETA2 * w2 + 1j * w2 * math.sqrt(1 - ZETA2**2)
    anti_ref = np.sort_complex(np.exp(np.array([lam, lam.conjugate()]) * orbit.T))
    sb = ss.SymmetricBranches(system, at, orbit.T, S, 1.0, 1.2, section_margin=0.0)
    assert np.array_equal(sb.symmetry, S)
    for pt in branch.points:
        ref = beam_scene(20.0 * pt.parameter)[4]
        xe, _ = ref.state(t0)
        # Mode 1 is Den Hartog's orbit: 1e-6 X as test_contact_system.py's branch (shooting to 1e-9
        # at rtol 1e-10; an orbit at the wrong amplitude is off by ~X dF0 / F0).
        assert abs(phi * pt.orbit.x0[0] - xe) <= 1e-6 * ref.X
        # Symmetric: mode 2 at rest (Newton's tolerance 1e-9 on an O(1e-3) state bounds it).
        assert sb.asymmetry(pt.orbit.x0) <= 1e-9
        sym, anti = sb.multipliers_by_symmetry(pt.orbit.monodromy)
        # V- is mode 2's exp(lambda T) pair: 1e-7, the variational monodromy at rtol 1e-10 over a
        # period with two events (~1e-9) with margin; a wrong block (mode 1's, or mixed) is O(1) off.
        assert np.allclose(np.sort_complex(anti), anti_ref, rtol=0, atol=1e-7)
        # The two blocks together are the orbit's multipliers.
        both = np.sort_complex(np.concatenate([sym, anti]))
        assert np.allclose(both, np.sort_complex(pt.orbit.multipliers), rtol=0, atol=1e-8)
    # No multiplier leaves the unit circle (|exp(lambda T)| = exp(-zeta w2 T) < 1; Den Hartog's
    # continuous sliding is stable): no bifurcation; classify finds no crossing through +1.
    assert branch.bifurcations == [] and ss.locate_bifurcations(branch) == []
    c = sb.classify(branch.points[0], branch.points[1])
    assert not c.ok and "no real multiplier crosses +1" in c.message
    # The mirror image of a symmetric point is the point (S x0 = x0).
    im = sb.image(branch.points[1])
    assert im.orbit.ok, im.orbit.message
    assert im.parameter == branch.points[1].parameter
    assert np.allclose(im.orbit.x0, branch.points[1].orbit.x0, rtol=0, atol=1e-9)
    # asymmetry of a state with mode 2 displaced by 0.3: max |S x - x| = 2 x 0.3.
    x = branch.points[0].orbit.x0.copy()
    x[1] = 0.3
    assert sb.asymmetry(x) == pytest.approx(0.6, abs=1e-9)

    # Points with the real orbits and constructed monodromies (the C++ test's multipliers, on the
    # symmetric combinations of (q1, q1') and the antisymmetric ones of (q2, q2')).
    def fake(p, mu_s1, mu_a1, mu_s2, mu_a2):
        real = branch.points[0].orbit
        T = np.array([[1, 0, 1, 0], [0, 1, 0, 1], [1, 0, -1, 0], [0, 1, 0, -1]], float)  # columns: s1, a1, s2, a2
        M = T @ np.diag([mu_s1, mu_a1, mu_s2, mu_a2]) @ np.linalg.inv(T)
        o = types.SimpleNamespace(t0=real.t0, period=real.period, x0=real.x0, mode=real.mode, monodromy=M)
        return types.SimpleNamespace(parameter=p, orbit=o)

    # The antisymmetric multiplier 0.9 -> 1.1 between p = 1 and 2: det(M - I) on V- is
    # (0.3 - 1)(mu_a1 - 1), zero at p = 1.5; the vector (0, 1, 0, 1) (max norm 1, either sign).
    c = sb.classify(fake(1, 0.5, 0.9, 0.2, 0.3), fake(2, 0.5, 1.1, 0.2, 0.3))
    assert c.ok and c.kind == ss.BifurcationKind.Pitchfork and not c.located, c.message
    assert c.parameter == pytest.approx(1.5, abs=1e-12)
    v = c.eigenvector
    assert abs(abs(v[1]) - 1) <= 1e-12 and abs(v[1] - v[3]) <= 1e-12 and abs(v[0]) + abs(v[2]) <= 1e-12
    # A symmetric multiplier 0.8 -> 1.4 (the antisymmetric ones inside): a fold at 1 + 0.2 / 0.6.
    f = sb.classify(fake(1, 0.5, 0.9, 0.8, 0.3), fake(2, 0.5, 0.95, 1.4, 0.3))
    assert f.ok and f.kind == ss.BifurcationKind.Fold and f.parameter == pytest.approx(1 + 0.2 / 0.6, abs=1e-12)
    # A start along the antisymmetric mode from that (constructed) pitchfork: mode 2 is a free
    # damped oscillator, whose only periodic orbit is rest, so no asymmetric orbit exists there.
    asym = sb.asymmetric_branch(c, 0.05)
    assert asym.status == ss.ContinuationStatus.StartFailed and asym.points == []
    assert asym.message.startswith("the first asymmetric orbit"), asym.message
    with pytest.raises(ValueError, match="offset must not be 0"):
        sb.asymmetric_branch(c, 0.0)
    with pytest.raises(ValueError, match="pitchfork must be an ok symmetry-breaking pitchfork"):
        sb.asymmetric_branch(f, 0.05)

    # PeriodDoubling on the same branch: no multiplier through -1 between two points.
    pd = ss.PeriodDoubling(system, at, orbit.T, 1.0, 1.2, section_margin=0.0)
    flip = pd.locate_flip(branch.points[0], branch.points[1])
    assert not flip.ok and "no multiplier crosses -1" in flip.message
    with pytest.raises(ValueError, match="flip must be located"):
        pd.period_doubled_branch(flip, 0.05)
    with pytest.raises(ValueError, match="PeriodDoubling.locate_flip: tolerance"):
        pd.locate_flip(branch.points[0], branch.points[1], tolerance=0.0)


def test_bad_input_is_named():
    system, S, row, phi, orbit = beam_scene()
    at = lambda s, p: s
    with pytest.raises(TypeError, match="PeriodDoubling: system must be a FrictionDampedSystem"):
        ss.PeriodDoubling(1.0, at, orbit.T, 0.0, 1.0)
    with pytest.raises(ValueError, match="PeriodDoubling: p_max must be > p_min"):
        ss.PeriodDoubling(system, at, orbit.T, 1.0, 1.0)
    with pytest.raises(ValueError, match="PeriodDoubling: parameter must be a callable"):
        ss.PeriodDoubling(system, None, orbit.T, 0.0, 1.0)
    with pytest.raises(ValueError, match="PeriodDoubling: period"):
        ss.PeriodDoubling(system, at, -1.0, 0.0, 1.0)
    with pytest.raises(ValueError, match="max_step"):
        ss.PeriodDoubling(system, at, orbit.T, 0.0, 1.0, max_step=-1.0)
    bad = S.copy()
    bad[0, 0] = 2.0
    with pytest.raises(ValueError, match="SymmetricBranches: symmetry must be an involution"):
        ss.SymmetricBranches(system, at, orbit.T, bad, 0.0, 1.0)
    with pytest.raises(ValueError, match=r"SymmetricBranches: symmetry must be state_size\(\) x state_size\(\)"):
        ss.SymmetricBranches(system, at, orbit.T, np.eye(4), 0.0, 1.0)
    with pytest.raises(ValueError, match="SymmetricBranches: mode_image must be None or a callable"):
        ss.SymmetricBranches(system, at, orbit.T, S, 0.0, 1.0, mode_image=3)
    with pytest.raises(ValueError, match="symmetry_tolerance"):
        ss.SymmetricBranches(system, at, orbit.T, S, 0.0, 1.0, symmetry_tolerance=0.0)
    sb = ss.SymmetricBranches(system, at, orbit.T, S, 0.0, 1.0)
    point = types.SimpleNamespace(parameter=1.0, orbit=types.SimpleNamespace(
        t0=0.0, period=orbit.T, x0=np.zeros(3), mode=[ss.ContactState.Stick], monodromy=np.eye(4)))
    with pytest.raises(ValueError, match="SymmetricBranches.classify: a.orbit: x0 has size 3"):
        sb.classify(point, point)
    point.orbit.x0 = system.initial_state()
    point.orbit.monodromy = np.eye(3)
    with pytest.raises(ValueError, match=r"SymmetricBranches.image: point.orbit: monodromy must be square over the "
                                         r"periodic components \(4\)"):
        sb.image(point)
    with pytest.raises(ValueError, match="asymmetry: the state size must be the symmetry's"):
        sb.asymmetry(np.zeros(2))
