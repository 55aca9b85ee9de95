"""Bladed disks from Python (docs/disks.md) against references that do not come from the library's
disk code: the cyclic-symmetry frequencies against a dense generalized eigen solve of the whole
annulus in numpy, the travelling-wave orbit of a linear disk against the closed-form modal
receptance, and the mistuning study's amplification of a tuned sample."""

import math

import numpy as np
import pytest

import stickslip as ss

BLADE, PLATFORM, PITCH = 0.2, 0.04, 0.05
# A stocky section: lambda_max / lambda_1 of the annulus stays near 1e5, so the dense eigen solves
# carry ~1e-16 * 1e5 relative error in the low frequencies.
SECTION = ss.SectionProperties(2.0e11, 7800.0, 1e-4, 1e-9)


def sector(frame, placement):
    """The paper's blade + platform at placement.origin: node 0 left wing, 1 right wing, 2 the
    blade tip (platform middle), 3 the clamped root; member 0 platform, member 1 blade."""
    s = ss.SectionProperties(SECTION.E * placement.stiffness_factor, SECTION.rho, SECTION.A, SECTION.I)
    x, y = placement.origin
    left = frame.add_node(x - PLATFORM / 2, y + BLADE)
    right = frame.add_node(x + PLATFORM / 2, y + BLADE)
    platform = frame.add_member(left, right, s, 2)
    middle = frame.member_nodes(platform)[1]
    root = frame.add_node(x, y)
    frame.add_member(root, middle, s, 4)
    frame.clamp(root)
    return left, right


def make_disk(n, mistuning=()):
    return ss.BladedDisk(n, PITCH, sector, ss.SectorCoupling.springs(1e4, 1e4, 10.0), list(mistuning))


def annulus_frequencies(disk):
    """All frequencies of K x = w^2 M x by numpy: Cholesky of M, symmetric eigenvalues."""
    K, M = disk.stiffness(), disk.mass()
    L = np.linalg.cholesky(M)
    Li = np.linalg.inv(L)
    lam = np.linalg.eigvalsh(Li @ K @ Li.T)
    return np.sqrt(np.sort(lam))


def test_cyclic_frequencies_equal_the_full_annulus_eigen_solve():
    for n in (6, 7):
        disk = make_disk(n)
        modes = ss.compute_cyclic_modes(disk, 3)
        assert len(modes.families) == n // 2 + 1
        cyclic = []
        for f in modes.families:
            assert f.pairs == (0 < f.nodal_diameter < n / 2)
            cyclic += list(f.omega) * (2 if f.pairs else 1)
        cyclic = np.sort(cyclic)
        full = annulus_frequencies(disk)
        # The 3 n lowest cyclic modes are the annulus' lowest only up to the first family's third
        # mode; compare those below it. Both dense solves: ~1e-11 relative (above), 1e-8 leaves margin.
        top = min(f.omega[2] for f in modes.families)
        for w in cyclic[cyclic <= top]:
            assert np.min(np.abs(full - w)) <= 1e-8 * w
        assert np.allclose(cyclic[: n], full[: n], rtol=1e-8, atol=0)
        basis = ss.annulus_basis(disk, modes)
        assert np.allclose(basis.omega(), cyclic, rtol=1e-12)


def test_linear_travelling_wave_is_the_closed_form_receptance():
    n, eo, zeta, F = 5, 2, 0.02, 20.0
    disk = make_disk(n)
    modes = ss.compute_cyclic_modes(disk, 2)
    basis = ss.annulus_basis(disk, modes)
    basis = basis.with_modal_damping(np.full(basis.size(), zeta))
    h = ss.engine_order_nodal_diameter(eo, n)
    W = 0.97 * modes.families[h].omega[0]
    T = 2 * math.pi / W
    # The load at the blade tip node (member 1's end): F cos(W t + 2 pi EO k / N) on blade k.
    loads = ss.engine_order_loads(disk, 1, BLADE, ss.LoadDirection.GlobalX, F, W, eo)
    system = ss.ContactSystem(disk.frame(), basis, [], loads)
    shift = ss.travelling_wave_shift(disk, basis, system, eo)
    assert shift.symmetry.shifts_per_period == n  # EO 2 coprime with 5: tau = T / 5
    x0 = system.initial_state()
    orbit = ss.travelling_wave(system, shift, [], 0.0, x0, T)
    assert orbit.ok, orbit.message
    # Closed form, independent of the shooting: q_r(t) = Re(Q_r e^{iWt}),
    # Q_r = phi_r(tips) . Fhat / (w_r^2 - W^2 + 2 i zeta w_r W), Fhat_k = F e^{2 pi i EO k / N}.
    w = basis.omega()
    g = np.zeros(basis.size(), dtype=complex)
    for k in range(n):
        g += basis.nodal(disk.node(k, 2), ss.Dof.X) * F * np.exp(2j * math.pi * eo * k / n)
    Q = g / (w**2 - W**2 + 2j * zeta * w * W)
    nm = basis.size()
    expected = np.concatenate([Q.real, (1j * W * Q).real])
    got = orbit.x0[: 2 * nm]
    # Newton to 1e-9 of max |x| on runs of rtol 1e-10: the orbits agree to ~1e-8 of the state.
    assert np.max(np.abs(got - expected)) <= 1e-7 * np.max(np.abs(expected))
    # Linear and damped: every full-period multiplier has modulus e^{-zeta w_r T} <= 1.
    assert orbit.stable and orbit.max_multiplier < 1.0
    assert orbit.check == ss.FloquetCheck.TravellingWave
    # mode_retries reaches TravellingWaveOptions: no contacts, so no retry changes the orbit, and a
    # negative count is refused by the C++ options check, naming the option.
    again = ss.travelling_wave(system, shift, [], 0.0, x0, T, mode_retries=0)
    assert again.ok and np.array_equal(again.x0, orbit.x0)
    with pytest.raises(ValueError, match="mode_retries"):
        ss.travelling_wave(system, shift, [], 0.0, x0, T, mode_retries=-1)
    # settle_periods reaches it too: converged from the guess, the orbit started there (0 periods);
    # a negative count is refused naming it.
    assert orbit.settled_periods == 0
    with pytest.raises(ValueError, match="settle_periods"):
        ss.travelling_wave(system, shift, [], 0.0, x0, T, settle_periods=-1)
    with pytest.raises(ValueError, match="settle_after"):
        ss.travelling_wave(system, shift, [], 0.0, x0, T, settle_after=0)


def test_sweep_follows_the_receptance_and_mistuning_of_zero_gives_amplification_one():
    n, eo, zeta, F = 4, 1, 0.02, 10.0
    disk = make_disk(n)
    modes = ss.compute_cyclic_modes(disk, 2)
    basis = ss.annulus_basis(disk, modes).with_modal_damping(np.full(2 * n, zeta))
    w1 = modes.families[1].omega[0]
    omegas = [0.9 * w1, 0.95 * w1, 1.0 * w1]

    def make_system(W):
        return ss.ContactSystem(disk.frame(), basis, [],
                                ss.engine_order_loads(disk, 1, BLADE, ss.LoadDirection.GlobalX, F, W, eo))

    sys0 = make_system(omegas[0])
    points = ss.travelling_wave_sweep(make_system, disk, basis, eo, omegas, [], sys0.initial_state())
    assert [p[0] for p in points] == omegas
    tip = np.array([basis.nodal(disk.node(k, 2), ss.Dof.X) for k in range(n)])
    for W, orbit in points:
        assert orbit.ok, orbit.message
        # The tip amplitude of the closed-form receptance (as above) at W.
        w = basis.omega()
        g = sum(tip[k] * F * np.exp(2j * math.pi * eo * k / n) for k in range(n))
        Q = g / (w**2 - W**2 + 2j * zeta * w * W)
        amplitude = np.abs(tip @ Q).max()
        q = orbit.x0[: basis.size()]
        qd = orbit.x0[basis.size(): 2 * basis.size()]
        # |u| = sqrt(u(0)^2 + (u'(0) / W)^2) of a harmonic u: 1e-7 of the Newton tolerance's scale.
        got = np.hypot(tip @ q, tip @ qd / W).max()
        assert got == pytest.approx(amplitude, rel=1e-6)

    grid = list(np.linspace(0.8 * w1, 1.2 * w1, 41))

    def peak(deltas):
        d = make_disk(n, deltas)
        return ss.engine_order_blade_peak(d, 2, ss.Dof.X, F, eo, 2, ss.Dof.X, grid, zeta, 2 * n)

    tuned = ss.mistuning_study(n, 0.0, 3, 11, peak, threads=2)
    assert tuned.amplification == [1.0, 1.0, 1.0]  # delta = 0: the tuned disk exactly
    assert ss.draw_mistuning(n, 0.05, 7) == ss.draw_mistuning(n, 0.05, 7)
    scattered = ss.mistuning_study(n, 0.05, 4, 11, peak)
    assert all(e == "" for e in scattered.errors())
    # Whitehead's bound (1 + sqrt N) / 2 on the largest blade amplitude of a mistuned disk.
    assert 1.0 < scattered.max_amplification() <= (1 + math.sqrt(n)) / 2
    assert scattered.csv().splitlines()[0].startswith("sample,seed,sigma,peak,blade,amplification")


def test_bad_disk_input_raises_naming_the_parameter():
    with pytest.raises(ValueError, match="num_sectors"):
        make_disk(1)
    with pytest.raises(ValueError, match="pitch"):
        ss.BladedDisk(4, 0.01, sector, ss.SectorCoupling.springs(1e4, 1e4, 10.0))
    disk = make_disk(4)
    with pytest.raises(ValueError, match="law"):
        ss.neighbour_joints(disk, ss.StructurePoint(0, PLATFORM), ss.StructurePoint(0, 0.0),
                            ss.PlaneDirection.global_x(), "coulomb", 10.0)
