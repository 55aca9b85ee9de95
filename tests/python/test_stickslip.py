"""Tests of the Python module stickslip (label python; docs/python.md).

References that do not come from the code under test: the C++ example's own output files for
the same scene, a closed-form forced response, the energy balance, sample counts of the contact
states, RK4's convergence order, and the library's error messages."""
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import blade_scene as blade
import stickslip as ss

# The example prints with %.10g: a value v is written with a rounding error of at most
# 5e-10 |v| (half a unit of the tenth significant digit); 1e-9 |v| leaves a factor 2 for the
# decimal-binary conversion. Anything beyond that is a different computation.
PRINTED = 1e-9


def close_to_printed(python, printed):
    python, printed = np.asarray(python, float), np.asarray(printed, float)
    assert python.shape == printed.shape
    np.testing.assert_array_less(np.abs(python - printed), PRINTED * np.abs(printed) + 1e-300)


def read_csv(path):
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    return {k: np.array([r[k] for r in rows]) for k in rows[0]}


@pytest.fixture(scope="module")
def example_run(tmp_path_factory):
    """The C++ example at a stick-slip preload (the most sensitive regime: ~1000 switches)."""
    exe = os.environ.get("STICKSLIP_BLADE_DAMPER")
    if not exe or not os.path.exists(exe):
        pytest.skip("the blade_damper example is not built (STICKSLIP_BUILD_EXAMPLES=OFF)")
    out = tmp_path_factory.mktemp("blade")
    subprocess.run([exe, "--preload", "2.7", "--duration", "2", "--out", str(out)], check=True,
                   stdout=subprocess.DEVNULL)
    scene = blade.make_blade_scene(blade.BladeParameters(preload=2.7))
    run, summary = blade.run(scene, 2.0)
    return out, scene, run, summary


def test_blade_scene_equals_the_cpp_example(example_run):
    out, scene, run, summary = example_run
    sys = scene.system
    h = read_csv(out / "history_N0_2.7.csv")
    assert len(h["t"]) == len(run.force_t) == 10001  # the last second at 0.1 ms, both ends
    close_to_printed(run.force_t, h["t"].astype(float))
    last = run.sample_t >= 1.0 - 1e-12
    close_to_printed(run.probes[last, 0], h["tip"].astype(float))
    for i in range(2):
        for name in ("N", "f", "V", "y", "X"):
            close_to_printed(run.forces[name][:, i], h[f"{name}{i + 1}"].astype(float))
        close_to_printed(run.states[last, sys.x_offset() + i], h[f"x{i + 1}"].astype(float))
        np.testing.assert_array_equal(run.sample_modes[last, i], h[f"state{i + 1}"].astype(int))
    tip = read_csv(out / "tip_N0_2.7.csv")
    index = np.searchsorted(run.sample_t, tip["t"].astype(float) - 1e-9)
    close_to_printed(run.sample_t[index], tip["t"].astype(float))
    close_to_printed(run.probes[index, 0], tip["tip"].astype(float))
    events = read_csv(out / "events_N0_2.7.csv")
    mine = [e for e in sys.events() if e.t >= 1.0]
    assert len(mine) == len(events["t"]) > 100
    close_to_printed([e.t for e in mine], events["t"].astype(float))
    np.testing.assert_array_equal([e.damper for e in mine], events["damper"].astype(int))
    with open(out / "summary_N0_2.7.json") as fh:
        s = json.load(fh)
    assert s["status"] == "success" and run.ok
    assert s["regime"] == summary["regime"] == "stick-slip"
    close_to_printed(summary["energy_density"], s["energy_density_m2"])
    close_to_printed(summary["stick_fraction"], [d["stick_fraction"] for d in s["dampers"]])
    assert s["stats"]["events"] == run.stats.events
    assert s["stats"]["rhs_evaluations"] == run.stats.rhs_evaluations
    close_to_printed(run.energy.residual, s["energy_audit_residual_J"])


def test_python_sweep_rows_equal_the_cpp_sweep(tmp_path):
    """examples/python/sweep.py's rows against blade_sweep_mpi's (serial backend) at the same
    preloads: E, the regime and its inputs, the tip maximum and the work counters."""
    exe = os.environ.get("STICKSLIP_BLADE_SWEEP")
    if not exe or not os.path.exists(exe):
        pytest.skip("blade_sweep_mpi is not built (STICKSLIP_MPI or STICKSLIP_BUILD_EXAMPLES OFF)")
    import sweep
    preloads = [1.5, 2.7, 26.0]  # left platform, stick-slip, stick
    subprocess.run([exe, "--backend", "serial", "--sweep-preloads", ",".join(map(str, preloads)), "--duration",
                    "0.6", "--out", str(tmp_path)], check=True, stdout=subprocess.DEVNULL)
    cpp = read_csv(tmp_path / "sweep.csv")
    for k, p in enumerate(preloads):
        row = sweep.sweep_point(p, 0.6)
        assert row["regime"] == cpp["regime"][k]
        for name in ("stick_fraction_1", "stick_fraction_2", "tip_max_m"):
            close_to_printed(row[name], float(cpp[name][k]))
        # E over [0, 0.1] s: also for 1.5 N, which leaves the platform after t2.
        close_to_printed(row["energy_density_m2"], float(cpp["energy_density_m2"][k]))
        assert row["status"] == {"success": "Success", "stopped_by_system": "StoppedBySystem"}[cpp["status"][k]]
        assert row["rhs_evaluations"] == int(cpp["rhs_evaluations"][k])
        assert row["events"] == int(cpp["events"][k])


def test_sweep_script_writes_its_rows_and_plot(tmp_path):
    script = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python", "sweep.py")
    subprocess.run([sys.executable, script, "--lo", "2", "--hi", "20", "--count", "2", "--duration", "0.2",
                    "--threads", "2", "--out", str(tmp_path)], check=True, stdout=subprocess.DEVNULL,
                   env=dict(os.environ))
    rows = read_csv(tmp_path / "sweep_python.csv")
    close_to_printed(rows["preload_N"].astype(float), [2.0, 20.0])
    assert (tmp_path / "sweep_python.png").stat().st_size > 10000


def cantilever(loads_at=0.1, modes=3):
    f = ss.FrameModel()
    root, tip = f.add_node(0, 0), f.add_node(0, 0.2)
    m = f.add_member(root, tip, ss.SectionProperties(2.06e11, 7800, 6e-5, 2e-11), 10)
    f.clamp(root)
    basis = ss.compute_modes(f, num_modes=modes)
    return f, m, basis


@pytest.mark.parametrize("integrator,kw,tol", [
    # Global errors relative to the largest |q|. rk4 at h = 2e-6 s: mode 3's phase error
    # (h w_3)^4 w_3 T / 120 ~ 3e-8 times its small share of q (measured 2e-13): 1e-8.
    ("rk4", {"fixed_step": 2e-6}, 1e-8),
    # The fifth-order methods at rtol 1e-9 (local) over ~80 periods of mode 3 (measured 4e-12
    # and 3e-12): 1e-8.
    ("dopri5", {"rtol": 1e-9, "atol": 1e-15}, 1e-8),
    ("exponential", {"rtol": 1e-9, "atol": 1e-15}, 1e-8),
    # Rosenbrock23's third-order error estimate lets the global error grow to ~50 rtol
    # (measured 5e-8): 1e-6.
    ("rosenbrock23", {"rtol": 1e-9, "atol": 1e-15}, 1e-6),
])
def test_every_integrator_matches_the_closed_form_forced_response(integrator, kw, tol):
    # No damper: q_j'' + w_j^2 q_j = psi_j F sin(W t) from rest has
    # q_j = psi_j F / (w_j^2 - W^2) (sin W t - (W / w_j) sin w_j t).
    f, m, basis = cantilever()
    F, W = 1.0, 200.0
    system = ss.FrictionDampedSystem(f, basis, [], [ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, F, W)])
    psi = system.point_shape(m, 0.1, ss.LoadDirection.GlobalX)
    w = basis.omega()
    run = ss.simulate(system, 0.1, ss.RunOptions(integrator, output_interval=1e-3, **kw))
    assert run.ok, run.message
    t = run.sample_t[:, None]
    q = psi * F / (w ** 2 - W ** 2) * (np.sin(W * t) - (W / w) * np.sin(w * t))
    err = np.abs(run.states[:, :len(basis)] - q).max() / np.abs(q).max()
    assert err < tol, f"{integrator}: relative error {err:.2e}"
    # The energy audit closes: E(t) - E0 = W_ext (no dissipation). The audit integrates W_ext
    # with the state's tolerances (measured residual <= 6e-10 W_ext): 1e-7 W_ext.
    assert abs(run.energy.residual) <= 1e-7 * abs(run.energy.external_work)


def test_a_python_time_function_is_the_harmonic_load():
    # The same F(t) through a Python callable (called with the GIL re-acquired inside the
    # released integration) and through the harmonic load: the same arithmetic, bitwise equal.
    # The integrator is named: "auto" would run the harmonic load's exactly linear scene by the
    # exponential method and the callable's (opaque to it) by Dormand-Prince.
    f, m, basis = cantilever()
    callable_load = ss.PointLoad(m, 0.1)
    callable_load.time_function = lambda t: 2.0 * math.sin(200.0 * t)
    harmonic = ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, 2.0, 200.0)
    runs = [ss.simulate(ss.FrictionDampedSystem(f, basis, [], [load]), 0.02,
                        ss.RunOptions("dopri5", output_interval=1e-3))
            for load in (callable_load, harmonic)]
    assert np.abs(runs[0].states).max() > 0
    np.testing.assert_array_equal(runs[0].states, runs[1].states)


def test_damper_statistics_agree_with_the_sampled_contact_states():
    scene = blade.make_blade_scene(blade.BladeParameters(preload=2.7))
    period = 2 * math.pi / 200.0
    run = ss.simulate(scene.system, 1.0, blade.run_options(), statistics=ss.StatisticsWindow(0.5, 1.0, period))
    assert run.ok
    window = run.sample_t >= 0.5 - 1e-12
    for i, st in enumerate(run.damper_statistics):
        sampled = np.mean(run.sample_modes[window, i] == int(ss.ContactState.Stick))
        # Time stuck (from the steps) vs the fraction of 0.1 ms samples stuck: each stick interval
        # is off by at most one sample interval at either end (2 per switch pair).
        bound = (st.switches + 2) * 1e-4 / 0.5
        assert abs(st.stick_fraction - sampled) <= bound
        assert st.regime == ss.DamperRegime.StickSlip
        assert st.observed_time == pytest.approx(0.5, rel=1e-12)
        transitions_in_window = sum(1 for tr in run.transitions
                                    if 0.5 <= tr.t <= 1.0 and tr.from_mode[i] != tr.to_mode[i])
        assert st.switches == transitions_in_window
    # Energy audit of a stick-slip run: friction dissipates, and the balance closes to a small
    # fraction of the largest term (rtol 1e-7 per step over ~500 switches).
    b = run.energy
    assert b.friction_dissipation > 0
    assert abs(b.residual) < 1e-4 * max(abs(b.external_work), b.friction_dissipation)


def test_at_rest_the_normal_force_is_the_preload_and_friction_vanishes():
    # From rest at t = 0 the load sin(0) = 0 and every velocity vanish, so nothing accelerates:
    # y'' = 0 gives N = N0 - s m y'' = N0 (paper eqs 23-24), and with no spring stretch the stuck
    # damper needs no friction, f = 0 (to the round-off of the coupled solve, 1e-12 N0).
    params = blade.BladeParameters(preload=5.0)
    sys = blade.make_blade_scene(params).system
    ok, mode, x = sys.make_consistent(sys.requested_mode(), 0.0, sys.initial_state())
    assert ok and mode == [ss.ContactState.Stick] * 2
    e = sys.evaluate(mode, 0.0, x)
    np.testing.assert_allclose(e["N"], [5.0, 5.0], rtol=1e-12)
    np.testing.assert_allclose(e["f"], [0.0, 0.0], atol=1e-12 * 5.0)
    np.testing.assert_allclose(e["qdd"], 0.0, atol=1e-12)
    assert sys.mechanical_energy(mode, 0.0, x) == pytest.approx(0.0, abs=1e-15)
    with pytest.raises(ValueError, match="evaluate"):
        sys.evaluate(mode[:1], 0.0, x)


def test_event_log_counts_every_switched_damper():
    scene = blade.make_blade_scene(blade.BladeParameters(preload=2.0))
    run = ss.simulate(scene.system, 0.5, blade.run_options(sample_interval=1e-3))
    switched = sum(sum(a != b for a, b in zip(tr.from_mode, tr.to_mode)) for tr in run.transitions)
    at_start = [e for e in scene.system.events() if e.t == 0.0]
    assert len(scene.system.events()) == switched + len(at_start)
    assert run.stats.events == len(run.transitions)


def test_trade_study_measures_rk4s_fourth_order():
    # A stuck scene (preload 26 N: no switch) is smooth, so RK4's error falls 16-fold per halving
    # of the step (log2 ratio 4; 0.3 of slack for the reference's own error and the
    # pre-asymptotic range).
    params = blade.BladeParameters(preload=26.0, modes=4)
    setup = lambda: blade.make_blade_scene(params).system  # noqa: E731
    probe = ss.Probe(1, params.L1, ss.LoadDirection.GlobalX)
    reference = ss.TradeVariant("reference", setup, ss.RunOptions("dopri5", rtol=1e-11, atol=1e-14))
    variants = [ss.TradeVariant(f"rk4 {h}", setup, ss.RunOptions("rk4", fixed_step=h)) for h in (4e-5, 2e-5)]
    study = ss.trade_study(reference, variants, t_end=0.2, output=probe, output_interval=1e-3, repeats=1)
    assert study.reference.ok and study.validation.ok
    coarse, fine = study.rows
    assert coarse.ok and fine.ok
    assert math.log2(coarse.output_error_max / fine.output_error_max) == pytest.approx(4.0, abs=0.3)
    assert study.validation.output_error_max < 0.1 * fine.output_error_max
    text = ss.trade_csv([study.reference] + list(study.rows))
    assert text.splitlines()[0].startswith("name,status,message") and len(text.splitlines()) == 4
    # The same study with the output as a Python callable f(t, x) (the tip from the basis'
    # shape row): the same errors up to the round-off of numpy's dot product (1e-9 relative of
    # errors that are themselves >= 1e-7).
    shape = setup().point_shape(1, params.L1, ss.LoadDirection.GlobalX)
    again = ss.trade_study(reference, variants, t_end=0.2, output=lambda t, x: float(shape @ x[:len(shape)]),
                           output_interval=1e-3, repeats=1)
    for a, b in zip(again.rows, study.rows):
        assert a.output_error_max == pytest.approx(b.output_error_max, rel=1e-9)


def test_trade_study_reports_a_failing_setup_as_a_row():
    params = blade.BladeParameters(preload=26.0, modes=2)
    good = lambda: blade.make_blade_scene(params).system  # noqa: E731

    def bad():
        raise ValueError("setup: no scene")

    probe = ss.Probe(1, params.L1)
    study = ss.trade_study(ss.TradeVariant("ref", good, ss.RunOptions(rtol=1e-9, atol=1e-12)),
                           [ss.TradeVariant("bad", bad)], t_end=0.05, output=probe, repeats=1)
    assert not study.rows[0].started and "setup: no scene" in study.rows[0].message


def test_bad_input_raises_value_error_naming_the_parameter():
    f, m, basis = cantilever()
    law = ss.CoulombLaw(0.35, 0.3)
    with pytest.raises(ValueError, match=r"PointDamper\[0\].*mass must be finite and > 0"):
        ss.FrictionDampedSystem(f, basis, [ss.PointDamper(m, 0.1, -1.0, 1e4, 1.0, law)])
    with pytest.raises(ValueError, match="num_modes must be >= 1"):
        ss.compute_modes(f, num_modes=0)
    with pytest.raises(ValueError, match="integrator must be rk4, dopri5, rosenbrock23, exponential or auto"):
        ss.RunOptions("euler")
    with pytest.raises(ValueError, match="RunOptions: unknown option rtl"):
        ss.RunOptions("dopri5", rtl=1e-6)
    with pytest.raises(ValueError, match="law must be a CoulombLaw"):
        ss.PointDamper(m, 0.1, 1.0, 1e4, 1.0, "coulomb")
    with pytest.raises(ValueError, match="SectionProperties|E must be"):
        f.add_member(0, 1, ss.SectionProperties(-1.0, 7800, 6e-5, 2e-11), 2)
    system = ss.FrictionDampedSystem(f, basis, [])
    with pytest.raises(ValueError, match="fixed_step is above RungeKutta4's stability limit"):
        ss.simulate(system, 0.1, ss.RunOptions("rk4", fixed_step=1e-2))
    with pytest.raises(ValueError, match=f"simulate: x0 has size 3, expected state_size\\(\\) = {system.state_size()}"):
        ss.simulate(system, 0.1, x0=np.zeros(3))
    with pytest.raises(ValueError, match="window.t_end must be > window.t_start"):
        ss.simulate(system, 0.1, statistics=ss.StatisticsWindow(1.0, 0.5, 0.1))


def test_bad_python_values_and_callable_results_raise_type_error_naming_them():
    # Not pybind11's RuntimeError "Unable to cast Python instance ...": a TypeError naming the
    # option or callable, what it must be and what it got (or, in a trade study, that message in
    # the row, as for any failing variant).
    f, m, basis = cantilever()
    with pytest.raises(TypeError, match="RunOptions: rtol must be a float, got str"):
        ss.RunOptions("dopri5", rtol="tight")
    with pytest.raises(TypeError, match="RunOptions: max_steps must be an int, got float"):
        ss.RunOptions("dopri5", max_steps=1.5)
    load = ss.PointLoad(m, 0.1)
    with pytest.raises(ValueError, match="PointLoad: time_function must be None or a callable F\\(t\\)"):
        load.time_function = 2.0
    load.time_function = lambda t: None
    with pytest.raises(TypeError, match="PointLoad: time_function\\(t\\) must return a float, got NoneType"):
        load.value(0.0)
    with pytest.raises(TypeError, match="PointLoad: time_function\\(t\\) must return a float, got NoneType"):
        ss.simulate(ss.FrictionDampedSystem(f, basis, [], [load]), 0.01)
    load.time_function = None
    assert load.time_function is None and load.value(1.0) == 0.0
    harmonic = ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, 1.0, 200.0)
    good = lambda: ss.FrictionDampedSystem(f, basis, [], [harmonic])  # noqa: E731
    probe = ss.Probe(m, 0.2)
    study = ss.trade_study(ss.TradeVariant("ref", good), [], t_end=0.01, output=lambda t, x: None, repeats=1)
    assert not study.reference.started
    assert "trade_study: output(t, x) must return a float, got NoneType" in study.reference.message
    study = ss.trade_study(ss.TradeVariant("ref", good), [ss.TradeVariant("bad", lambda: None)], t_end=0.01,
                           output=probe, repeats=1)
    assert not study.rows[0].started
    assert "TradeVariant bad: setup() must return a FrictionDampedSystem, got NoneType" in study.rows[0].message


def test_periodic_orbit_of_a_damped_linear_scene_is_the_closed_form():
    # No damper, modal damping zeta: q_j'' + 2 zeta w_j q_j' + w_j^2 q_j = psi_j F sin(W t) has the
    # periodic orbit q_j = Im(psi_j F e^{iWt} / (w_j^2 - W^2 + 2i zeta w_j W)) and Floquet
    # multipliers exp(lambda T), lambda = -zeta w_j +- i w_j sqrt(1 - zeta^2). Shooting starts from
    # rest (far from the orbit) and must find it. Tolerances: Newton stops at 1e-9 of the state's
    # size and the runs are at rtol 1e-10, so the orbit's state is within ~1e-8 of the closed form
    # relative to its largest component; the multipliers come from the variational monodromy at
    # the same tolerances: 1e-6.
    f, m, basis = cantilever()
    zeta, F, W = 0.02, 1.0, 200.0
    basis = basis.with_modal_damping(np.full(len(basis), zeta))
    system = ss.FrictionDampedSystem(f, basis, [], [ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, F, W)])
    psi = system.point_shape(m, 0.1, ss.LoadDirection.GlobalX)
    w = basis.omega()
    T = 2 * math.pi / W
    orbit = ss.find_periodic_orbit(system, T)
    assert orbit.ok, orbit.message
    assert orbit.status == ss.ShootingStatus.Converged
    n = len(basis)
    a = psi * F / (w ** 2 - W ** 2 + 2j * zeta * w * W)
    q0, qd0 = np.imag(a), np.imag(1j * W * a)  # at t0 = 0
    ref = np.concatenate([q0, qd0])
    err = np.abs(orbit.x0[:2 * n] - ref).max() / np.abs(ref).max()
    assert err < 1e-8, f"orbit vs closed form: {err:.2e}"
    lam = -zeta * w + 1j * w * math.sqrt(1 - zeta ** 2)
    expected = np.sort(np.abs(np.concatenate([np.exp(lam * T), np.exp(np.conj(lam) * T)])))
    assert np.abs(np.sort(np.abs(orbit.multipliers)) - expected).max() < 1e-6
    assert orbit.stable and orbit.instability == ss.Instability.Stable
    assert orbit.events == []


def test_periodic_orbit_rejects_a_bad_request_naming_it():
    f, m, basis = cantilever()
    system = ss.FrictionDampedSystem(f, basis, [], [ss.PointLoad.harmonic(m, 0.1, ss.LoadDirection.GlobalX, 1.0, 200.0)])
    with pytest.raises(ValueError, match="monodromy"):
        ss.find_periodic_orbit(system, 0.01, monodromy="guess")
    with pytest.raises(ValueError, match="period"):
        ss.find_periodic_orbit(system, -1.0)
    n = system.state_size()
    with pytest.raises(ValueError, match=f"find_periodic_orbit: x0 has size 3, expected state_size\\(\\) = {n}"):
        ss.find_periodic_orbit(system, 0.01, x0=np.zeros(3))
    damped = ss.FrictionDampedSystem(f, basis, [ss.PointDamper(m, 0.15, 0.01, 5e3, 5.0, ss.CoulombLaw(0.35, 0.3))])
    with pytest.raises(ValueError, match="find_periodic_orbit: mode \\(DamperStates\\) has 0 states, expected num_dampers"):
        ss.find_periodic_orbit(damped, 0.01, mode=[])  # was read past its end (an assertion in Debug builds)
    # [] is not "all components" (C++'s empty set, which takes in the audit integrals): None is the default.
    with pytest.raises(ValueError, match="find_periodic_orbit: periodic must not be empty \\(None: the default"):
        ss.find_periodic_orbit(system, 0.01, periodic=[])
    with pytest.raises(ValueError, match=f"find_periodic_orbit: periodic: index out of \\[0, {n}\\) \\(got {n}\\)"):
        ss.find_periodic_orbit(system, 0.01, periodic=[n])


def test_a_damper_without_preload_that_may_separate_starts_in_flight():
    # Separation.Separate adds the flight coordinates y_d, y_d' after the contact coordinates and
    # the impact-loss term to the audit (docs/model_separation.md); at rest without preload
    # N = 0 is not positive, so make_consistent lets the damper leave instead of refusing the start.
    f, m, basis = cantilever()
    d = ss.PointDamper(m, 0.1, 0.01, 1e3, 0.0, ss.CoulombLaw(0.35, 0.3))
    d.separation = ss.Separation.Separate
    d.restitution = 0.5
    sys = ss.FrictionDampedSystem(f, basis, [d])
    n = sys.num_modes()
    assert sys.num_separable() == 1
    assert sys.flight_offset() == 2 * n + 3  # q, q', x, x', X
    assert sys.energy_offset() == 2 * n + 5 and sys.state_size() == 2 * n + 10
    ok, mode, x = sys.make_consistent(sys.requested_mode(), 0.0, sys.initial_state())
    assert ok and mode == [ss.ContactState.Separated]
    run = ss.simulate(sys, 0.01, ss.RunOptions("dopri5"))
    assert run.energy.impact_loss == 0.0 and abs(run.energy.residual) < 1e-12


def test_member_end_choices_are_bound():
    f, m, basis = cantilever()
    d = ss.PointDamper(m, 0.1, 0.01, 1e3, 1.0, ss.CoulombLaw(0.35, 0.3))
    assert d.start_end == ss.MemberEnd.Default and d.wall_restitution == 1.0
    d.finish_end = ss.MemberEnd.Wall
    d.wall_restitution = 0.5
    sys = ss.FrictionDampedSystem(f, basis, [d])
    assert sys.dampers()[0].finish_end == ss.MemberEnd.Wall
    n = sys.num_modes()
    assert sys.energy_offset() == 2 * n + 3 and sys.state_size() == 2 * n + 8  # a wall adds D_imp
    d.wall_restitution = 1.5
    with pytest.raises(ValueError, match="wall_restitution"):
        ss.FrictionDampedSystem(f, basis, [d])
