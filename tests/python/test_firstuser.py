"""Orbit outputs at probes in physical units (OrbitProbe, probe_rows, PeriodicOrbit.outputs) and the
progress reports of find_periodic_orbit and continue_orbits (docs/steady_state.md)."""
import math

import numpy as np
import pytest

import stickslip as ss

ZETA = 0.02


def cantilever(modes=2):
    """A clamped 0.2 m cantilever along Y on `modes` damped modes (no damper)."""
    f = ss.FrameModel()
    root, tip = f.add_node(0, 0), f.add_node(0, 0.2)
    m = f.add_member(root, tip, ss.SectionProperties(2.06e11, 7800, 6e-5, 2e-11), 10)
    f.clamp(root)
    basis = ss.compute_modes(f, num_modes=modes).with_modal_damping(np.full(modes, ZETA))
    return f, m, basis


def test_probe_amplitude_is_the_receptance_times_the_force():
    # Closed form: a tip load F sin(W t) along X gives at a point the displacement
    # Im(H F e^{iWt}), H = sum_j psi_j phi_j / (w_j^2 - W^2 + 2i zeta w_j W), psi and phi from
    # the model's point_shape (not the probes' structure_point_row). The first harmonic is exact
    # on the samples for a pure harmonic; the orbit is right to the Newton tolerance 1e-9 and the
    # runs' rtol 1e-10: 1e-6 of the amplitude.
    f, m, basis = cantilever()
    F, W = 2.0, 1.3 * basis.omega()[0]
    system = ss.FrictionDampedSystem(f, basis, [], [ss.PointLoad.harmonic(m, 0.2, ss.LoadDirection.GlobalX, F, W)])
    probes = [ss.OrbitProbe(ss.StructurePoint(m, 0.1), ss.PlaneDirection.global_x()),
              ss.OrbitProbe(ss.StructurePoint(m, 0.2), ss.PlaneDirection.global_x(), ss.ProbeQuantity.Velocity)]
    rows = ss.probe_rows(f, basis, probes, system)
    assert rows.shape == (2, system.state_size())
    reports = []
    orbit = ss.find_periodic_orbit(system, 2 * math.pi / W, outputs=rows, output_harmonics=2, progress=reports.append)
    assert orbit.ok, orbit.message
    phi = system.point_shape(m, 0.2, ss.LoadDirection.GlobalX)
    w = basis.omega()
    for j, (x, scale) in enumerate([(0.1, 1.0), (0.2, W)]):
        psi = system.point_shape(m, x, ss.LoadDirection.GlobalX)
        amp = scale * abs(np.sum(psi * phi / (w ** 2 - W ** 2 + 2j * ZETA * w * W))) * F
        out = orbit.outputs[j]
        assert out.harmonic(1) == pytest.approx(amp, rel=1e-6)
        assert abs(out.mean) <= 1e-6 * amp
        assert out.harmonic(2) <= 1e-6 * amp
        # extremes over the steps and >= 5 samples a period: within the steps' spacing of the peak
        assert out.amplitude <= amp * (1 + 1e-6) and out.amplitude >= 0.9 * amp
    assert [r.iteration for r in reports] == list(range(len(reports)))
    assert reports[-1].residual <= reports[-1].tolerance and reports[-1].remaining_seconds == 0


def test_continuation_reports_progress_per_point_and_bad_arguments_name_themselves():
    f, m, basis = cantilever()
    W0 = basis.omega()[0]

    def at(W):
        return ss.FrictionDampedSystem(f, basis, [], [ss.PointLoad.harmonic(m, 0.2, ss.LoadDirection.GlobalX, 1.0, W)])

    reports = []
    branch = ss.continue_orbits(at(0.5 * W0), lambda s, p: at(p * W0), 0.5, 0.7, lambda p: 2 * math.pi / (p * W0),
                                progress=reports.append, max_step=0.05)
    assert branch.completed, branch.message
    assert [r.points for r in reports] == list(range(1, len(branch.points) + 1))
    assert [r.parameter for r in reports] == list(branch.parameters)
    assert reports[0].covered == 0 and 0.5 < reports[-1].covered <= 1
    with pytest.raises(ValueError, match="progress"):
        ss.continue_orbits(at(0.5 * W0), lambda s, p: at(p * W0), 0.5, 0.7, 1.0, progress=3)
    with pytest.raises(ValueError, match="probes\\[0\\]"):
        ss.probe_rows(f, basis, [ss.OrbitProbe(ss.StructurePoint(m, 0.5))], at(W0))
