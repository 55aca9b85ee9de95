"""continue_orbits (pseudo-arclength continuation of forced periodic orbits, docs/python.md)
against the closed-form forced response of a damped linear scene, and the behaviour of its
Python callables (exceptions propagate, a wrong return is a TypeError)."""
import math

import numpy as np
import pytest

import stickslip as ss

ZETA = 0.02  # modal damping ratio of every mode
UNIT = 100.0  # the continuation parameter is p = W / UNIT [rad/s]: p and the states are O(0.01-1)


def scene(modes=2):
    """A clamped cantilever on `modes` damped modes, harmonic load at 0.1 m (no damper):
    w = 260.8, 1634.5 rad/s."""
    f = ss.FrameModel()
    root, tip = f.add_node(0, 0), f.add_node(0, 0.2)
    m = f.add_member(root, tip, ss.SectionProperties(2.06e11, 7800, 6e-5, 2e-11), 10)
    f.clamp(root)
    basis = ss.compute_modes(f, num_modes=modes).with_modal_damping(np.full(modes, ZETA))

    def at(F, W):
        return ss.FrictionDampedSystem(f, basis, [], [ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, F, W)])

    return at, basis, at(1.0, 1.0).point_shape(m, 0.1, ss.LoadDirection.GlobalX)


def receptance(psi, basis, F, W):
    """Closed form: q_j'' + 2 zeta w_j q_j' + w_j^2 q_j = psi_j F sin(W t) has the orbit
    q_j = Im(a_j e^{iWt}), a_j = psi_j F / (w_j^2 - W^2 + 2i zeta w_j W): the state (q, q') at
    t0 = 0 and the amplitudes (|a_j|, W |a_j|)."""
    w = basis.omega()
    a = psi * F / (w ** 2 - W ** 2 + 2j * ZETA * w * W)
    return np.concatenate([np.imag(a), np.imag(1j * W * a)]), np.concatenate([np.abs(a), W * np.abs(a)])


@pytest.mark.parametrize("chord_iterations", [0, 4])
def test_frequency_branch_is_the_closed_form_receptance(chord_iterations):
    # Through the first resonance (w_1 = 260.8 rad/s, p = 2.608). Tolerances: each orbit solves
    # |x(T) - x(0)| <= 1e-9 (absolute: |x| < 1) with runs at rtol 1e-9; the error of x0 is that
    # residual over 1 - |mu| (mu = exp(-zeta w_1 T) ~ 0.88: x8) plus the run's global error
    # ~rtol |x|: <= 2e-8 against |x0| ~ 0.02-0.1, measured <= 3e-8 relative: 1e-6. The amplitudes
    # are max |x_i| over the steps and 256 samples per period: a sampled sine is short of its peak
    # by <= 1 - cos(pi / 256) = 7.5e-5 of it: 1e-4 relative. The multipliers (variational
    # monodromy at rtol 1e-9) are exp(lambda_j T), lambda_j = -zeta w_j +- i w_j sqrt(1 - zeta^2):
    # 1e-6. The same with chord iterations (plain runs with the last point's Jacobian first):
    # the points are confirmed by the same Newton test, so the same bounds hold.
    at, basis, psi = scene()
    seen = []
    branch = ss.continue_orbits(at(1.0, 230.0), lambda system, p: at(1.0, p * UNIT), 2.3, 2.9,
                                lambda p: 2 * math.pi / (p * UNIT), rtol=1e-9, atol=1e-14,
                                initial_step=0.05, max_step=0.1, on_point=seen.append,
                                chord_iterations=chord_iterations)
    assert branch.status == ss.ContinuationStatus.Completed and branch.completed, branch.message
    p = branch.parameters
    assert p[0] == 2.3 and np.all(np.diff(p) > 0) and p[-1] > 2.75  # no fold: p grows to near p_end
    assert len(p) >= 6 and p[p < 2.608].size and p[p > 2.608].size  # both sides of the resonance
    assert [pt.parameter for pt in seen] == list(p)  # on_point saw every point, in order
    w = basis.omega()
    lam = -ZETA * w + 1j * w * math.sqrt(1 - ZETA ** 2)
    for pt in branch.points:
        W = pt.parameter * UNIT
        T = 2 * math.pi / W
        x0, amp = receptance(psi, basis, 1.0, W)
        o = pt.orbit
        assert o.ok and o.period == pytest.approx(T, rel=1e-15)
        assert np.abs(o.x0[:x0.size] - x0).max() < 1e-6 * np.abs(x0).max(), pt.parameter
        assert np.abs(o.amplitudes - amp).max() < 1e-4 * amp.max(), pt.parameter
        mu = np.sort(np.abs(np.concatenate([np.exp(lam * T), np.exp(np.conj(lam) * T)])))
        assert np.abs(np.sort(np.abs(o.multipliers)) - mu).max() < 1e-6
        assert o.stable and not pt.stability_changed and o.events == []
        assert o.stick_fractions == [] and o.switches == []  # no damper


def test_amplitude_branch_at_a_fixed_period_scales_linearly():
    # A float period: continuation in the load amplitude F at W = 250 rad/s; the orbit is
    # F times the closed form at F = 1 (tolerance as above: 1e-6 of the state).
    at, basis, psi = scene()
    W = 250.0
    branch = ss.continue_orbits(at(1.0, W), lambda system, F: at(F, W), 1.0, 3.0, 2 * math.pi / W,
                                rtol=1e-9, atol=1e-14, initial_step=0.2, max_step=0.5)
    assert branch.completed, branch.message
    assert len(branch.points) >= 3 and branch.parameters[-1] > 2.5
    for pt in branch.points:
        x0, _ = receptance(psi, basis, pt.parameter, W)
        assert np.abs(pt.orbit.x0[:x0.size] - x0).max() < 1e-6 * np.abs(x0).max(), pt.parameter
    # Downwards (p_end < p0) the branch goes the other way.
    down = ss.continue_orbits(at(3.0, W), lambda system, F: at(F, W), 3.0, 2.0, 2 * math.pi / W,
                              rtol=1e-9, atol=1e-14, initial_step=0.2, max_step=0.5)
    assert down.completed and np.all(np.diff(down.parameters) < 0)


def test_stop_when_ends_the_branch_where_the_rule_says_and_the_corrector_distance_reaches_cpp():
    # stop_when(last, next): the branch through the resonance stopped at the first point past
    # p = 2.5 (the rule sees `next` before it is added); every kept point is the receptance's.
    at, basis, psi = scene()
    asked = []

    def past(last, nxt):
        asked.append((last.parameter, nxt.parameter))
        return nxt.parameter > 2.5

    branch = ss.continue_orbits(at(1.0, 230.0), lambda system, p: at(1.0, p * UNIT), 2.3, 2.9,
                                lambda p: 2 * math.pi / (p * UNIT), rtol=1e-9, atol=1e-14,
                                initial_step=0.05, max_step=0.1, stop_when=past)
    assert branch.status == ss.ContinuationStatus.Stopped, branch.message
    p = branch.parameters
    assert p[-1] <= 2.5 and asked and asked[-1][1] > 2.5 and asked[-1][0] == p[-1]
    for pt in branch.points:
        x0, _ = receptance(psi, basis, 1.0, pt.parameter * UNIT)
        assert np.abs(pt.orbit.x0[:x0.size] - x0).max() < 1e-6 * np.abs(x0).max()
    # A smooth linear branch: every corrected point lies near its prediction, so a distance
    # bound of 2 steps changes nothing; a negative one is refused by the C++ options.
    bounded = ss.continue_orbits(at(1.0, 230.0), lambda system, p: at(1.0, p * UNIT), 2.3, 2.9,
                                 lambda p: 2 * math.pi / (p * UNIT), rtol=1e-9, atol=1e-14,
                                 initial_step=0.05, max_step=0.1, max_corrector_distance=2.0)
    assert bounded.completed, bounded.message
    with pytest.raises(ValueError, match="max_corrector_distance"):
        ss.continue_orbits(at(1.0, 230.0), lambda system, p: at(1.0, p * UNIT), 2.3, 2.9,
                           lambda p: 2 * math.pi / (p * UNIT), max_corrector_distance=-1.0)
    with pytest.raises(ValueError, match="stop_when"):
        ss.continue_orbits(at(1.0, 230.0), lambda system, p: at(1.0, p * UNIT), 2.3, 2.9,
                           lambda p: 2 * math.pi / (p * UNIT), stop_when=3)
    with pytest.raises(ValueError, match="parts = 1"):
        ss.continue_orbits(at(1.0, 230.0), lambda system, p: at(1.0, p * UNIT), 2.3, 2.9,
                           lambda p: 2 * math.pi / (p * UNIT), stop_when=past, parts=2)


class Boom(Exception):
    pass


def test_an_exception_in_a_callable_propagates_and_the_system_stays_usable():
    at, basis, psi = scene(modes=1)
    W = 250.0
    calls = []

    def parameter(system, F):
        calls.append(F)
        if len(calls) == 4:  # after the start (p0, p0 +- h), inside the first corrector
            raise Boom("from parameter")
        return at(F, W)

    system = at(1.0, W)
    with pytest.raises(Boom, match="from parameter"):
        ss.continue_orbits(system, parameter, 1.0, 2.0, 2 * math.pi / W)
    assert len(calls) == 4  # the run stopped at the exception

    def period(p):
        raise Boom("from period")

    with pytest.raises(Boom, match="from period"):
        ss.continue_orbits(system, lambda s, F: at(F, W), 1.0, 2.0, period)

    def on_point(point):
        raise Boom("from on_point")

    with pytest.raises(Boom, match="from on_point"):
        ss.continue_orbits(system, lambda s, F: at(F, W), 1.0, 2.0, 2 * math.pi / W, on_point=on_point)
    # The system (left at the parameter of the failed call) still works.
    orbit = ss.find_periodic_orbit(system, 2 * math.pi / W)
    assert orbit.ok, orbit.message


def test_bad_callables_and_options_are_reported():
    at, basis, psi = scene(modes=1)
    system = at(1.0, 250.0)
    T = 2 * math.pi / 250.0
    with pytest.raises(TypeError, match="must return the FrictionDampedSystem at p, got NoneType"):
        ss.continue_orbits(system, lambda s, p: None, 1.0, 2.0, T)
    with pytest.raises(ValueError, match="parameter must be a callable"):
        ss.continue_orbits(system, 3.0, 1.0, 2.0, T)
    with pytest.raises(ValueError, match="period must be finite and > 0"):
        ss.continue_orbits(system, lambda s, p: s, 1.0, 2.0, -T)
    with pytest.raises(ValueError, match="p_end must differ from p0"):
        ss.continue_orbits(system, lambda s, p: s, 1.0, 1.0, T)
    with pytest.raises(ValueError, match="options.initial_step"):
        ss.continue_orbits(system, lambda s, p: s, 1.0, 2.0, T, initial_step=1.0, max_step=0.1)
    with pytest.raises(ValueError, match="options.chord_iterations"):
        ss.continue_orbits(system, lambda s, p: s, 1.0, 2.0, T, chord_iterations=-1)
    with pytest.raises(ValueError, match="options.section_margin"):
        ss.continue_orbits(system, lambda s, p: s, 1.0, 2.0, T, section_margin=0.5)
    with pytest.raises(ValueError, match="monodromy"):
        ss.continue_orbits(system, lambda s, p: s, 1.0, 2.0, T, monodromy="guess")


def test_bad_arguments_and_callable_results_are_named():
    # Each error names the Python parameter (or callable) and says what it must be and what it
    # got: a TypeError for a wrong type (not pybind11's "Unable to cast" RuntimeError), a
    # ValueError for a wrong value or size (not a later C++ check blaming another option).
    at, basis, psi = scene()
    system = at(1.0, 230.0)
    n = system.state_size()
    P = lambda s, p: at(1.0, p * UNIT)  # noqa: E731
    T = lambda p: 2 * math.pi / (p * UNIT)  # noqa: E731
    run = lambda **kw: ss.continue_orbits(system, P, kw.pop("p0", 2.3), kw.pop("p_end", 2.9),  # noqa: E731
                                          kw.pop("period", T), **kw)
    for period in (None, "abc"):
        with pytest.raises(TypeError, match="continue_orbits: period must be a float or a callable period\\(p\\), got "):
            run(period=period)
    with pytest.raises(TypeError, match="continue_orbits: period\\(p\\) must return a float, got NoneType"):
        run(period=lambda p: None)
    with pytest.raises(ValueError, match="continue_orbits: p0 must be finite \\(got nan\\)"):
        run(p0=math.nan)
    with pytest.raises(ValueError, match="continue_orbits: p_end must be finite \\(got nan\\)"):
        run(p_end=math.nan)
    for parts in (1, 2):
        with pytest.raises(ValueError, match=f"continue_orbits: x0 has size 3, expected state_size\\(\\) = {n}"):
            run(x0=np.zeros(3), parts=parts)
    with pytest.raises(ValueError, match="continue_orbits: mode \\(DamperStates\\) has 1 states"):
        run(mode=[ss.ContactState.Stick])
    with pytest.raises(ValueError, match="continue_orbits: periodic must not be empty \\(None: the default"):
        run(periodic=[])
    with pytest.raises(ValueError, match="continue_orbits: periodic: index out of"):
        run(periodic=[n])
    # start(system, p) -> (mode, t0, x0) of parts > 1.
    what = "continue_orbits: start\\(system, p\\) must return \\(mode, t0, x0\\)"
    for bad, match in [(None, ", got NoneType"), ((1, 2), ", got tuple"),
                       (([], 0.0, np.zeros((2, 4))), " with x0 a 1-D array of floats, got ndarray of shape \\(2, 4\\)"),
                       (([], None, np.zeros(n)), " with t0 a float, got NoneType"),
                       ((3, 0.0, np.zeros(n)), " with mode a list of ContactState, got int")]:
        with pytest.raises(TypeError, match=what + match):
            run(parts=2, start=lambda s, p, bad=bad: bad)
    with pytest.raises(ValueError, match="start\\(system, p\\): mode \\(DamperStates\\) has 1 states"):
        run(parts=2, start=lambda s, p: ([ss.ContactState.Stick], 0.0, np.zeros(n)))
    # start_mode(system, t, x, mode) -> mode.
    what = "continue_orbits: start_mode\\(system, t, x, mode\\)"
    with pytest.raises(TypeError, match=what + " must return a list of ContactState, got NoneType"):
        run(start_mode=lambda s, t, x, mode: None)
    with pytest.raises(ValueError, match=what + ": mode \\(DamperStates\\) has 1 states"):
        run(start_mode=lambda s, t, x, mode: [ss.ContactState.Stick])
    # poincare_sections' start state and periodic set.
    with pytest.raises(ValueError, match=f"poincare_sections: x0 has size 3, expected state_size\\(\\) = {n}"):
        ss.poincare_sections(system, 0.02, x0=np.zeros(3))
    with pytest.raises(ValueError, match="poincare_sections: mode \\(DamperStates\\) has 1 states"):
        ss.poincare_sections(system, 0.02, mode=[ss.ContactState.Stick])
    with pytest.raises(ValueError, match="poincare_sections: periodic must not be empty"):
        ss.poincare_sections(system, 0.02, periodic=[])


def test_a_damper_stuck_all_period_has_stick_fraction_one():
    # A preload far above what the load can overcome: the damper never leaves Stick.
    f = ss.FrameModel()
    root, tip = f.add_node(0, 0), f.add_node(0, 0.2)
    m = f.add_member(root, tip, ss.SectionProperties(2.06e11, 7800, 6e-5, 2e-11), 10)
    f.clamp(root)
    basis = ss.compute_modes(f, num_modes=2).with_modal_damping(np.full(2, ZETA))
    damper = ss.PointDamper(m, 0.15, 0.01, 5e3, 50.0, ss.CoulombLaw(0.35, 0.3))
    system = ss.FrictionDampedSystem(f, basis, [damper], [ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, 2.0, 250.0)])
    orbit = ss.find_periodic_orbit(system, 2 * math.pi / 250.0, tolerance=1e-8)
    assert orbit.ok, orbit.message
    assert orbit.stick_fractions == [pytest.approx(1.0, abs=1e-12)] and orbit.switches == [0]


def test_a_branch_in_two_parts_joins_and_is_the_closed_form_receptance():
    # parts=2 (SplitContinuation: part 1 starts at the middle of the range on a copy of the system,
    # on its own thread). The joined branch must be the closed form at every point (same bounds
    # as above), increasing in p without a gap, with part 0 joined into part 1 and every point of
    # both kept. The start guesses: part 0 the given state, part 1 the `start` callable's (here
    # the rest state: one Newton step reaches the orbit of a linear scene).
    at, basis, psi = scene()
    starts = []

    def start(system, p):
        starts.append(p)
        return [], 0.0, system.initial_state()

    branch = ss.continue_orbits(at(1.0, 230.0), lambda system, p: at(1.0, p * UNIT), 2.3, 2.9,
                                lambda p: 2 * math.pi / (p * UNIT), rtol=1e-9, atol=1e-14,
                                initial_step=0.05, max_step=0.1, parts=2, start=start)
    assert branch.completed, branch.message
    assert sorted(starts) == pytest.approx([2.3, 2.6], rel=1e-15)  # one guess per part, at its cut
    assert len(branch.parts) == 2
    first, second = branch.parts
    assert first.joined and first.status == ss.ContinuationStatus.Stopped and first.kept == first.points
    assert second.start_parameter == pytest.approx(2.6, rel=1e-15)
    assert second.status == ss.ContinuationStatus.Completed and second.kept == second.points
    assert first.dropped == [] and second.dropped == []
    p = branch.parameters
    assert len(p) == first.kept + second.kept and np.all(np.diff(p) > 0) and p[-1] > 2.75
    assert p[p < 2.6].size and p[p >= 2.6].size  # points from both parts
    for pt in branch.points:
        x0, amp = receptance(psi, basis, 1.0, pt.parameter * UNIT)
        assert np.abs(pt.orbit.x0[:x0.size] - x0).max() < 1e-6 * np.abs(x0).max(), pt.parameter
    # Bad part counts and start callables are named.
    system = at(1.0, 230.0)
    with pytest.raises(ValueError, match="parts must be >= 1"):
        ss.continue_orbits(system, lambda s, p: at(1.0, p * UNIT), 2.3, 2.9, 0.02, parts=0)
    with pytest.raises(ValueError, match="start must be None or a callable"):
        ss.continue_orbits(system, lambda s, p: at(1.0, p * UNIT), 2.3, 2.9, 0.02, parts=2, start=1.0)
    with pytest.raises(ValueError, match="start\\(system, p\\): x0 has size 1, expected state_size\\(\\) = "):
        ss.continue_orbits(system, lambda s, p: at(1.0, p * UNIT), 2.3, 2.9, 0.02, parts=2,
                           start=lambda s, p: ([], 0.0, np.zeros(1)))


def state_at(psi, basis, F, W, t):
    """Closed form of the steady state (q, q') at time t under F sin(W t) (see receptance)."""
    w = basis.omega()
    a = psi * F / (w ** 2 - W ** 2 + 2j * ZETA * w * W) * np.exp(1j * W * t)
    return np.concatenate([np.imag(a), np.imag(1j * W * a)])


def two_tone(F1, W1, F2, W2):
    """The cantilever of scene() with two harmonic loads at 0.1 m."""
    f = ss.FrameModel()
    root, tip = f.add_node(0, 0), f.add_node(0, 0.2)
    m = f.add_member(root, tip, ss.SectionProperties(2.06e11, 7800, 6e-5, 2e-11), 10)
    f.clamp(root)
    basis = ss.compute_modes(f, num_modes=2).with_modal_damping(np.full(2, ZETA))
    loads = [ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, F1, W1),
             ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, F2, W2)]
    return ss.FrictionDampedSystem(f, basis, [], loads)


@pytest.mark.parametrize("k", [1, 3])
def test_poincare_sections_of_a_two_tone_linear_response(k):
    # Loads at W and W / k on the damped cantilever: the steady response repeats every k periods
    # T = 2 pi / W, exactly (superposition of two closed-form receptances). After 200 periods
    # (5.0 s) the free vibration from rest has decayed by exp(-zeta w_1 5.0) = 5e-12, the runs at
    # rtol 1e-10 add ~1e-10 of the state: the sections match the closed form to 1e-7 of their
    # largest component, the recurrence at k is below 1e-7 and at every j < k above 1e-3 (the
    # W / k part of the response, a third of the state, turns by 2 pi j / k between sections).
    at, basis, psi = scene()
    W = 250.0
    T = 2 * math.pi / W
    system = two_tone(1.0, W, 0.5, W / k)
    r = ss.poincare_sections(system, T, transient_periods=200, record_periods=16, max_period=4)
    assert r.status == ss.PoincareStatus.Periodic and r.periodic and r.period == k, r.recurrence
    assert r.message == "" and r.period_time == T and r.t0 == pytest.approx(200 * T, rel=1e-14)
    assert r.states.shape[0] == 16 and len(r.modes) == 16 and r.recurrence.size == 4
    assert r.recurrence[k - 1] < 1e-7 and np.all(r.recurrence[:k - 1] > 1e-3)
    scale = np.abs(r.states[:, :4]).max()
    for n in range(16):
        t = r.t0 + n * T
        x = state_at(psi, basis, 1.0, W, t) + state_at(psi, basis, 0.5, W / k, t)
        assert np.abs(r.states[n, :4] - x).max() < 1e-7 * scale, n


def test_poincare_sections_report_a_quasi_periodic_response_and_bad_input():
    # A second tone at the golden ratio of W never repeats: its phase moves by 2 pi 0.618 j per
    # j periods, never within 0.05 turn of whole for j <= 8, i.e. a recurrence > 1e-3 at every k.
    at, basis, psi = scene()
    W = 250.0
    T = 2 * math.pi / W
    system = two_tone(1.0, W, 0.5, W * (math.sqrt(5) - 1) / 2)
    r = ss.poincare_sections(system, T, transient_periods=50)
    assert r.status == ss.PoincareStatus.NotPeriodic and not r.periodic and r.period == 0
    assert r.recurrence.size == 8 and np.all(r.recurrence > 1e-3)
    with pytest.raises(ValueError, match="poincare_sections: period must be finite and > 0"):
        ss.poincare_sections(system, -T)
    with pytest.raises(ValueError, match="poincare_sections: max_period must be <= record_periods / 2 = 2 "):
        ss.poincare_sections(system, T, record_periods=4, max_period=8)
    with pytest.raises(ValueError, match="options.max_period"):
        ss.poincare_sections(system, T, max_period=0)
