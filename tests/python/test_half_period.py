"""SymmetricBranches with a half-period shift and a symmetry centre, and continue_orbits'
wrap_section, from Python (docs/python_branches.md, docs/python.md).

References that do not come from the code under test:
- a linear 2-blade disk forced at engine order 1: blade 1 is forced F cos(W t + pi), i.e. half a
  period after blade 0, so the shift by one blade S (travelling_wave_shift: S S = I for N = 2)
  maps a solution x(t) onto S x(t + T/2). Its orbit is shot over the full period
  (find_periodic_orbit, which knows nothing of the symmetry), and the half-period map is checked
  against that orbit's own multipliers (M = H^2) and against the closed form H = S_PP Phi(T/2),
  Phi the modal flow of q'' + 2 zeta w q' + w^2 q = 0 from numpy's eigen decomposition;
- the symmetry centre against c + S (x - c) computed with numpy;
- wrap_section against the closed-form receptance of the cantilever of test_continuation.py, and
  against the same branch started within the first period."""
import math
import types

import numpy as np
import pytest

import stickslip as ss
from test_continuation import UNIT, receptance, scene, state_at
from test_disk import BLADE, make_disk

ZETA, F = 0.02, 20.0


def disk_scene():
    """The linear 2-blade disk at engine order 1, W 3 % below the first 1-nodal-diameter mode:
    (system, S, T, nm, the travelling-wave orbit, the full-period orbit)."""
    n, eo = 2, 1
    disk = make_disk(n)
    modes = ss.compute_cyclic_modes(disk, 2)
    basis = ss.annulus_basis(disk, modes)
    basis = basis.with_modal_damping(np.full(basis.size(), ZETA))
    W = 0.97 * modes.families[1].omega[0]
    T = 2 * math.pi / W
    loads = ss.engine_order_loads(disk, 1, BLADE, ss.LoadDirection.GlobalX, F, W, eo)
    system = ss.ContactSystem(disk.frame(), basis, [], loads)
    shift = ss.travelling_wave_shift(disk, basis, system, eo)
    assert shift.symmetry.shifts_per_period == 2  # tau = T / 2: the shift by one blade is half a period
    tw = ss.travelling_wave(system, shift, [], 0.0, system.initial_state(), T)
    assert tw.ok, tw.message
    full = ss.find_periodic_orbit(system, T, t0=0.0, x0=tw.x0, mode=[])
    assert full.ok, full.message
    return system, basis, np.asarray(shift.state), T, basis.size(), tw, full


def point_of(orbit, p=1.0):
    return types.SimpleNamespace(parameter=p, orbit=orbit)


def same_system(system, p):
    return system


def test_half_period_shift_classifies_the_travelling_wave_orbit_by_its_half_period_map():
    system, basis, S, T, nm, tw, full = disk_scene()
    P = 2 * nm  # the default periodic components of a ContactSystem: q, q'
    # The shift by one blade of a 2-blade disk in modal coordinates: +1 on the 0-nodal-diameter
    # modes, -1 on the 1-nodal-diameter ones (a signed identity, so max norms are kept below; 1e-10
    # is the involution test's own tolerance).
    assert np.allclose(np.abs(S[:P, :P]), np.eye(P), rtol=0, atol=1e-10)
    assert np.any(np.diag(S)[:P] < 0)
    pt = point_of(full)
    half = ss.SymmetricBranches(system, same_system, T, S, 0.0, 2.0, half_period_shift=True)
    plain = ss.SymmetricBranches(system, same_system, T, S, 0.0, 2.0)
    assert half.half_period_shift and not plain.half_period_shift
    assert half.symmetry_centre is None
    scale = max(1.0, np.abs(full.x0[:P]).max())
    h = half.half_period_multipliers(pt)
    assert h.ok, h.message
    # x(t0 + T/2) = S x(t0): the full-period orbit solves |x(T) - x(0)| <= 1e-9 max(1, |x|); its
    # error in x0 is that over 1 - |mu| (|mu| = exp(-zeta w T) ~ 0.88: x8) plus the runs' global
    # error ~rtol |x| = 1e-10 |x|: 1e-8 of the state bounds the half-period defect.
    assert h.asymmetry <= 1e-8 * scale, h.asymmetry
    # Without the shift the same orbit is far from symmetric: S x0 - x0 is twice the
    # 1-nodal-diameter modes' state, which the engine-order-1 load drives near resonance.
    assert plain.asymmetry(full.x0) > 1e3 * h.asymmetry
    assert plain.asymmetry(full.x0) >= 0.1 * np.abs(full.x0[:P]).max()
    # The multipliers of the full-period shooting are the squares of H's eigenvalues. Both are
    # variational runs at rtol 1e-10 (half and full period): 1e-8 absolute on multipliers of
    # modulus <= 1.
    mu = np.sort_complex(np.asarray(h.eigenvalues) ** 2)
    assert mu.size == P
    assert np.allclose(mu, np.sort_complex(full.multipliers), rtol=0, atol=1e-8)
    # Closed form: H = S_PP Phi(T/2), Phi(t) = exp(A t) of q'' + 2 zeta w q' + w^2 q = 0 (the
    # linear disk without contacts), exp(A t) = V diag(exp(lambda t)) V^-1 in numpy. The same
    # 1e-8: the eigenvalues of a diagonalisable H move by its error times V's condition number
    # (~1 for these well-separated, lightly damped modes).
    w = basis.omega()
    A = np.block([[np.zeros((nm, nm)), np.eye(nm)], [-np.diag(w**2), -np.diag(2 * ZETA * w)]])
    lam, V = np.linalg.eig(A)
    Phi = (V @ np.diag(np.exp(lam * T / 2)) @ np.linalg.inv(V)).real
    ref = np.sort_complex(np.linalg.eigvals(S[:P, :P] @ Phi))
    assert np.allclose(np.sort_complex(np.asarray(h.eigenvalues)), ref, rtol=0, atol=1e-8)
    # classify: with the shift the orbit counts as symmetric (no crossing between two equal
    # points); without it, it does not.
    c = half.classify(pt, pt)
    assert not c.ok and "half-period map" in c.message, c.message
    c = plain.classify(pt, pt)
    assert not c.ok and "is not symmetric" in c.message, c.message
    # The mirror image with the shift is S x(t0 + T/2) = S S x0 = x0: the same orbit, shot again
    # (its x0 within the Newton tolerance's 1e-8 as above).
    im = half.image(pt)
    assert im.orbit.ok, im.orbit.message
    assert np.abs(im.orbit.x0[:P] - full.x0[:P]).max() <= 1e-8 * scale
    # The split by symmetry needs the half-period map with the shift, and the map needs the shift.
    with pytest.raises(ValueError, match="half_period_multipliers"):
        half.multipliers_by_symmetry(full.monodromy)
    with pytest.raises(ValueError, match="needs half_period_shift=True"):
        plain.half_period_multipliers(pt)
    sym, anti = plain.multipliers_by_symmetry(full.monodromy)  # still there without the shift
    assert sym.size + anti.size == P


def test_symmetry_centre_is_validated_and_maps_x_to_c_plus_s_x_minus_c():
    system, basis, S, T, nm, tw, full = disk_scene()
    P = 2 * nm
    n = system.state_size()
    with pytest.raises(ValueError, match="symmetry_centre"):
        ss.SymmetricBranches(system, same_system, T, S, 0.0, 2.0, symmetry_centre=np.zeros(n - 1))
    bad = np.zeros(n)
    bad[1] = np.nan
    with pytest.raises(ValueError, match="symmetry_centre must be finite"):
        ss.SymmetricBranches(system, same_system, T, S, 0.0, 2.0, symmetry_centre=bad)
    pt = point_of(full)
    x = full.x0
    rng = np.random.default_rng(7)
    v = rng.standard_normal(n) * np.abs(x).max()
    invariant = v + S @ v  # S c = c (S S = I)
    moved = v  # S v != v: its 1-nodal-diameter components flip
    assert np.abs(S @ moved - moved)[:P].max() > 0.1 * np.abs(moved).max()

    def branches(**kw):
        return ss.SymmetricBranches(system, same_system, T, S, 0.0, 2.0, **kw)

    base, base_h = branches(), branches(half_period_shift=True)
    h0 = base_h.half_period_multipliers(pt)
    assert h0.ok, h0.message
    # An S-invariant centre changes nothing: c + S (x - c) = S x + (c - S c) = S x up to the
    # rounding of |c| ~ |x| (1e-15 |x|; 1e-12 leaves margin).
    inv, inv_h = branches(symmetry_centre=invariant), branches(symmetry_centre=invariant, half_period_shift=True)
    assert np.array_equal(inv.symmetry_centre, invariant)
    assert inv.asymmetry(x) == pytest.approx(base.asymmetry(x), abs=1e-12 * np.abs(x).max())
    hi = inv_h.half_period_multipliers(pt)
    assert hi.ok and hi.asymmetry == pytest.approx(h0.asymmetry, abs=1e-12 * np.abs(x).max())
    assert np.array_equal(hi.eigenvalues, h0.eigenvalues)  # H = S dx(T/2)/dx(0) does not see c
    # A centre that S moves: asymmetry(x) = max |c + S (x - c) - x| over P, as numpy computes it
    # (the same operations: rounding only).
    mv, mv_h = branches(symmetry_centre=moved), branches(symmetry_centre=moved, half_period_shift=True)
    expected = np.abs(moved + S @ (x - moved) - x)[:P].max()
    assert mv.asymmetry(x) == pytest.approx(expected, rel=1e-14)
    assert abs(mv.asymmetry(x) - base.asymmetry(x)) > 0.1 * np.abs(moved).max()
    # With the shift: x(t0 + T/2) - (c + S (x0 - c)) = (x(t0 + T/2) - S x0) - (I - S) c, so the
    # defect is max |(I - S) c| over P to within the orbit's own defect h0.asymmetry.
    hm = mv_h.half_period_multipliers(pt)
    assert hm.ok, hm.message
    assert abs(hm.asymmetry - np.abs(moved - S @ moved)[:P].max()) <= h0.asymmetry + 1e-14 * np.abs(moved).max()
    # image() is not checked against c + S (x0 - c) here: this linear disk has one periodic orbit,
    # which the image's shooting reaches from any start.


def test_wrap_section_reduces_a_late_section_into_the_first_period():
    # The cantilever of test_continuation.py through its first resonance (w_1 = 260.8 rad/s) from
    # p0 = 2.4 (W = 240 rad/s), started at t0 = (k + 0.3) T0 with k = 12, and at 0.3 T0.
    at, basis, psi = scene()
    W0 = 2.4 * UNIT
    T0 = 2 * math.pi / W0
    late, early = (12 + 0.3) * T0, 0.3 * T0

    def run(t0, wrap, **kw):
        return ss.continue_orbits(at(1.0, W0), lambda s, p: at(1.0, p * UNIT), 2.4, 2.8,
                                  lambda p: 2 * math.pi / (p * UNIT), t0=t0, rtol=1e-9, atol=1e-14,
                                  initial_step=0.05, max_step=0.1, section_margin=0.0, wrap_section=wrap, **kw)

    ref = run(early, True)
    wrapped = run(late, True)
    assert ref.completed and wrapped.completed, (ref.message, wrapped.message)
    assert len(wrapped.points) >= 5
    for pt in wrapped.points:
        assert 0 <= pt.orbit.t0 < pt.orbit.period
    # The start's t0 reduced by 12 periods: 0.3 T0 up to the rounding of 12.3 T0 (1e-15 of it).
    assert wrapped.points[0].orbit.t0 == pytest.approx(early, abs=1e-13 * late)
    # The same branch as the one started in the first period: the same parameters and orbits up to
    # that rounding carried through Newton (1e-9 of the state, the Newton tolerance).
    assert len(wrapped.points) == len(ref.points)
    assert np.allclose(wrapped.parameters, ref.parameters, rtol=1e-9, atol=0)
    for a, b in zip(wrapped.points, ref.points):
        assert np.allclose(a.orbit.amplitudes, b.orbit.amplitudes, rtol=1e-8, atol=0)
        assert np.abs(a.orbit.x0 - b.orbit.x0).max() <= 1e-8 * np.abs(b.orbit.x0).max()
    # And both are the closed-form receptance at the point's own section t0 (test_continuation.py's
    # 1e-6 of the state and 1e-4 of the amplitude, a sampled sine's shortfall).
    for pt in wrapped.points:
        W = pt.parameter * UNIT
        x0 = state_at(psi, basis, 1.0, W, pt.orbit.t0)
        _, amp = receptance(psi, basis, 1.0, W)
        assert np.abs(pt.orbit.x0[:x0.size] - x0).max() < 1e-6 * np.abs(x0).max(), pt.parameter
        assert np.abs(pt.orbit.amplitudes - amp).max() < 1e-4 * amp.max(), pt.parameter
    # wrap_section=False keeps the late section: every point is at t0 = 12.3 T0 (no events: the
    # section never moves), and its orbit is still the receptance there (the forcing is
    # T-periodic). How far that branch gets is not asserted (at a late t0 it winds into a helix).
    kept = run(late, False, max_points=4)
    assert kept.points, kept.message
    for pt in kept.points:
        assert pt.orbit.t0 == late
        W = pt.parameter * UNIT
        x0 = state_at(psi, basis, 1.0, W, late)
        assert np.abs(pt.orbit.x0[:x0.size] - x0).max() < 1e-6 * np.abs(x0).max(), pt.parameter
