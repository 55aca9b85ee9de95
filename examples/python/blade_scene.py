"""The paper's blade with two under-platform dampers, built with the Python module stickslip.

The same scene as examples/blade_damper/blade_scene.hpp (make_blade_scene): a T-shaped frame,
the blade clamped at its root, the platform centred on the blade tip, the dampers under the
middle of each platform wing; run() reproduces blade_run.hpp's run_scene() records (tip history,
the last second's forces and states, E over [t1, t2], the regime of each damper).
"""
import math
from dataclasses import dataclass, field

import numpy as np

import stickslip as ss


@dataclass
class BladeParameters:
    """Paper section 3 plus the documented open choices (docs/blade_damper.md)."""
    k: float = 1.0e4             # damper spring [N/m]
    spin: float = 50.0           # Omega [rad/s]
    radius: float = 0.46         # r [m]
    E: float = 2.06e11
    rho: float = 7800.0
    A: float = 6e-5
    I: float = 2e-11
    L1: float = 0.2              # blade length [m]
    L2: float = 0.04             # platform length [m]
    mu_s: float = 0.35
    mu_k: float = 0.3
    force: float = 20.0          # F amplitude [N]
    force_omega: float = 200.0   # excitation [rad/s]
    y0: float = 0.05             # excitation point above the root [m]
    preload: float = 12.0        # N0 [N]
    share: float = 0.5           # a damper shared by two blades
    damper_offset: float = 0.01  # dampers at -/+ this distance from the blade axis [m]
    blade_elements: int = 20
    platform_elements: int = 8
    modes: int = 6
    model: ss.ModelOptions = field(default_factory=ss.ModelOptions)

    def damper_mass(self):
        """N0 = share m r Omega^2."""
        return self.preload / (self.share * self.radius * self.spin ** 2)


@dataclass
class BladeScene:
    frame: ss.FrameModel
    basis: ss.ModalBasis
    system: ss.FrictionDampedSystem
    blade_member: int
    platform_member: int
    tip: ss.Probe  # lateral (global X) displacement of the blade tip


def make_blade_scene(p: BladeParameters) -> BladeScene:
    section = ss.SectionProperties(p.E, p.rho, p.A, p.I)
    f = ss.FrameModel()
    root = f.add_node(0.0, 0.0)
    left = f.add_node(-p.L2 / 2, p.L1)
    right = f.add_node(p.L2 / 2, p.L1)
    platform = f.add_member(left, right, section, p.platform_elements)
    tip_node = f.member_nodes(platform)[p.platform_elements // 2]
    blade = f.add_member(root, tip_node, section, p.blade_elements)
    f.clamp(root)
    basis = ss.compute_modes(f, num_modes=p.modes)
    law = ss.CoulombLaw(p.mu_s, p.mu_k)
    m = p.damper_mass()
    dampers = [ss.PointDamper(platform, p.L2 / 2 + s * p.damper_offset, m, p.k, p.preload, law, p.share)
               for s in (-1.0, 1.0)]
    loads = [ss.PointLoad.harmonic(blade, p.y0, ss.LoadDirection.GlobalX, p.force, p.force_omega)]
    system = ss.FrictionDampedSystem(f, basis, dampers, loads, p.model)
    return BladeScene(f, basis, system, blade, platform, ss.Probe(blade, p.L1, ss.LoadDirection.GlobalX))


def run_options(integrator="auto", rtol=1e-7, atol=1e-10, sample_interval=1e-4):
    """The example's defaults (blade_damper: --rtol 1e-7 --atol 1e-10, samples every 0.1 ms)."""
    return ss.RunOptions(integrator, rtol=rtol, atol=atol, event_time_tolerance=1e-12,
                         output_interval=sample_interval)


def energy_window(duration):
    """The paper's E window [19, 19.5] s, or [T - 1, T - 0.5] for runs shorter than 19.5 s."""
    if duration < 19.5:
        return max(0.0, duration - 1.0), max(0.0, duration - 0.5)
    return 19.0, 19.5


def regime(stick_fraction):
    """The example's rule: gross slip below 5 % stuck, stick from 99.9 %, stick-slip between."""
    if math.isnan(stick_fraction):
        return "not reached"
    if stick_fraction < 0.05:
        return "gross slip"
    return "stick" if stick_fraction >= 0.999 else "stick-slip"


def run(scene: BladeScene, duration, options=None, record_window=1.0, record_states=True):
    """One run from rest; returns (ss.Run, summary dict) with E, the tip's max and the regimes.
    The forces are evaluated over the record window (as the C++ example's records); with
    record_states=False only the tip, the contact states and the forces are kept."""
    options = options or run_options()
    window_start = duration - min(record_window, duration)
    r = ss.simulate(scene.system, duration, options, probes=[scene.tip], evaluate_from=window_start,
                    record_states=record_states)
    t, tip = r.sample_t, r.probes[:, 0] if len(r.sample_t) else np.zeros(0)
    t1, t2 = energy_window(duration)
    inside = (t >= t1 - 1e-12) & (t <= t2 + 1e-12)
    E = float("nan")
    if t2 > t1 and r.t >= t2 and inside.sum() > 1:  # as run_scene: E when the run reached t2
        E = float(np.trapz(tip[inside] ** 2, t[inside]) / (t2 - t1))
    last = t >= window_start - 1e-12
    stuck = (r.sample_modes[last] == int(ss.ContactState.Stick)).mean(axis=0) if last.any() \
        else np.full(scene.system.num_dampers(), np.nan)
    regimes = [regime(s) for s in stuck]
    overall = regimes[0] if len(set(regimes)) == 1 else " / ".join(regimes)
    if not r.ok:
        why = scene.system.stop_reason()
        overall = {ss.StopReason.LiftOff: "lift-off", ss.StopReason.LeftMember: "left platform"}.get(why, "run stopped")
    summary = {"energy_density": E, "tip_max": float(np.abs(tip[last]).max()) if last.any() else float("nan"),
               "stick_fraction": [float(s) for s in stuck], "regime": overall}
    return r, summary
