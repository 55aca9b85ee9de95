"""Threads, interrupts and bounded requests (docs/python.md, "Threads and interrupts"): calls on
one FrictionDampedSystem from several threads give the serial result, calls on separate systems
run at once, Ctrl-C stops a long call, and requests beyond a stated limit are refused naming it."""
import _thread
import math
import signal
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import blade_scene as blade
import stickslip as ss


def cantilever_system(load, kind="damped"):
    """A cantilever with load(member): a FrictionDampedSystem without dampers, or (kind
    "contacts") a ContactSystem with a grounded slider at mid-span."""
    f = ss.FrameModel()
    root, tip = f.add_node(0, 0), f.add_node(0, 0.2)
    m = f.add_member(root, tip, ss.SectionProperties(2.06e11, 7800, 6e-5, 2e-11), 10)
    f.clamp(root)
    basis = ss.compute_modes(f, num_modes=3)
    if kind == "contacts":
        slider = ss.PointContact.grounded(ss.StructurePoint(m, 0.1), ss.PlaneDirection.global_x(),
                                          ss.CoulombLaw(0.35, 0.3), 1.0)
        return ss.ContactSystem(f, basis, [slider], [load(m)]), m
    return ss.FrictionDampedSystem(f, basis, [], [load(m)]), m


def run_signature(run):
    """What two runs of one scene from one start must share bit for bit."""
    return (run.status, run.t, run.x.tobytes(), run.states.tobytes(), run.sample_modes.tobytes(),
            run.stats.accepted_steps, run.stats.rhs_evaluations, len(run.transitions),
            run.energy.friction_dissipation)


def test_threads_on_one_system_give_the_serial_result_one_call_at_a_time():
    # A stick-slip blade run exercises every mutable cache of the system (the coupled solve's
    # workspace and factorisation, the event log). Runs of one scene from one start are
    # deterministic, so every threaded run must equal the serial one exactly.
    system = blade.make_blade_scene(blade.BladeParameters(preload=2.7)).system
    opts = blade.run_options(sample_interval=1e-3)
    reference = run_signature(ss.simulate(system, 0.06, opts))
    assert reference[0] == ss.Status.Success and reference[7] > 0  # stick-slip: transitions
    with ThreadPoolExecutor(4) as pool:
        runs = list(pool.map(lambda _: run_signature(ss.simulate(system, 0.06, opts)), range(8)))
    assert all(r == reference for r in runs)


@pytest.mark.parametrize("kind", ["damped", "contacts"])
def test_calls_on_one_system_do_not_overlap(kind):
    # Calls on one system (a FrictionDampedSystem or a ContactSystem) do not overlap: a Python
    # load (called inside each run with the GIL re-acquired, and every 50th call sleeping 0.1 ms
    # with it released, so that a run going on at the same time would get in) sees each run's
    # calls as one unbroken block.
    calls, local, start = [], threading.local(), threading.Barrier(3)

    def load(m):
        def f(t):
            calls.append(local.run)
            if len(calls) % 50 == 0:
                time.sleep(1e-4)
            return 20.0 * math.sin(200.0 * t)
        pl = ss.PointLoad(m, 0.1)
        pl.time_function = f
        return pl

    def run(k):
        local.run = k
        start.wait()
        return ss.simulate(shared, 0.03, ss.RunOptions(output_interval=1e-3))

    shared, _ = cantilever_system(load, kind)
    with ThreadPoolExecutor(3) as pool:
        assert all(r.ok for r in pool.map(run, range(3)))
    blocks = [k for i, k in enumerate(calls) if i == 0 or calls[i - 1] != k]
    assert sorted(blocks) == [0, 1, 2]


def test_threads_on_separate_systems_run_at_the_same_time():
    # Each run's Python load waits at a barrier of two on its first call: both runs must be
    # inside simulate at once to pass it (a lock shared by all systems would leave one of them
    # waiting for the other's run, and the barrier would break after its timeout).
    barrier = threading.Barrier(2, timeout=10)

    def load(m):
        seen = []
        def f(t):
            if not seen:
                seen.append(t)
                barrier.wait()
            return 20.0 * math.sin(200.0 * t)
        pl = ss.PointLoad(m, 0.1)
        pl.time_function = f
        return pl

    systems = [cantilever_system(load)[0] for _ in range(2)]
    with ThreadPoolExecutor(2) as pool:
        runs = list(pool.map(lambda s: ss.simulate(s, 0.005, ss.RunOptions(output_interval=1e-3)), systems))
    assert all(r.ok for r in runs)
    np.testing.assert_array_equal(runs[0].states, runs[1].states)  # the same scene and start


def long_calls():
    """Calls that run for minutes unless stopped; should the interrupt fail, a step or period
    budget ends each after ~15 s (measured: 1.3 us a step of simulate, 15 us of the variational
    orbit run, 0.75 ms a period of poincare_sections), so that the test fails instead of
    hanging."""
    system, m = cantilever_system(lambda m: ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, 1.0, 200.0))
    return {
        "simulate": lambda: ss.simulate(system, 1e6, ss.RunOptions(max_steps=10_000_000, output_interval=1.0)),
        "find_periodic_orbit": lambda: ss.find_periodic_orbit(system, 1e6, max_steps=1_000_000),
        "poincare_sections": lambda: ss.poincare_sections(system, 2 * math.pi / 200.0, transient_periods=20_000),
    }


@pytest.mark.parametrize("name", ["simulate", "find_periodic_orbit", "poincare_sections"])
def test_ctrl_c_stops_a_long_call(name):
    # SIGINT (as Ctrl-C sends it) from a timer thread 0.2 s into the call: the call looks for
    # signals every 20 ms and must raise KeyboardInterrupt well before its budget (~15 s) is
    # spent; 5 s leaves room for a loaded machine. (A call deaf to signals raises it too, once
    # it returns: the time tells them apart.)
    # Python's own SIGINT handler, also where the test runner was started with SIGINT ignored
    # (a background job), which interrupt_main would then leave without effect.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    call = long_calls()[name]
    timer = threading.Timer(0.2, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        timer.cancel()
        timer.join()
        signal.signal(signal.SIGINT, previous)
    assert time.monotonic() - start < 5.0


def test_the_run_budget_bounds_the_steady_state_calls():
    system, m = cantilever_system(lambda m: ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, 1.0, 200.0))
    orbit = ss.find_periodic_orbit(system, 1e6, max_steps=1000)
    assert orbit.status == ss.ShootingStatus.IntegrationFailed and "max_steps" in orbit.message
    sections = ss.poincare_sections(system, 1e3, transient_periods=1, max_steps=1000)
    assert sections.status == ss.PoincareStatus.IntegrationFailed and "max_steps" in sections.message
    for call in (lambda: ss.find_periodic_orbit(system, 0.03, max_steps=0),
                 lambda: ss.poincare_sections(system, 0.03, max_steps=-1),
                 lambda: ss.continue_orbits(system, lambda s, p: s, 1.0, 2.0, 0.03, max_steps=0)):
        with pytest.raises(ValueError, match="max_steps must be > 0"):
            call()


def test_unbounded_requests_are_refused_naming_the_limit():
    system, m = cantilever_system(lambda m: ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, 1.0, 200.0))
    T = 2 * math.pi / 200.0
    # Sections of state_size doubles, kept twice (1 GiB at most): the limit is stated.
    limit = (1 << 30) // (16 * system.state_size())
    with pytest.raises(ValueError, match=f"record_periods must be <= {limit} .*1 GiB"):
        ss.poincare_sections(system, T, record_periods=2**31 - 1)
    with pytest.raises(ValueError, match="max_period must be <= record_periods / 2 = 16"):
        ss.poincare_sections(system, T, max_period=2**30)
    with pytest.raises(ValueError, match="parts must be <= [0-9]+ \\(4 x the hardware threads"):
        ss.continue_orbits(system, lambda s, p: s, 1.0, 2.0, T, parts=5000)


@pytest.mark.parametrize("kind", ["damped", "contacts"])
def test_run_inputs_are_named_before_the_first_evaluation(kind):
    # A non-finite t0 or x0 entry is named as such (it was reported as an inconsistent or
    # lifted-off start, or by the shapes as "eps = nan"); evaluate_from = nan would record nothing.
    system, _ = cantilever_system(lambda m: ss.PointLoad.harmonic(m, 0.2, ss.LoadDirection.GlobalX, 1.0, 100.0), kind)
    opts = ss.RunOptions("dopri5")
    with pytest.raises(ValueError, match="t0"):
        ss.simulate(system, 0.01, opts, t0=math.nan)
    x0 = np.zeros(system.state_size())
    x0[1] = math.inf
    with pytest.raises(ValueError, match=r"x0\[1\]"):
        ss.simulate(system, 0.01, opts, x0=x0)
    with pytest.raises(ValueError, match="evaluate_from"):
        ss.simulate(system, 0.01, opts, evaluate_from=math.nan)
