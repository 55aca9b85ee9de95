"""A cantilever blade with one friction damper under a harmonic load: the Python quick start
(docs/python.md, "Use"). Run it with the installed package (`pip install .`), from anywhere:

    python3 examples/python/quickstart.py
"""
import numpy as np
import stickslip as ss

frame = ss.FrameModel()                                    # 1. beam elements
root, tip = frame.add_node(0, 0), frame.add_node(0, 0.2)
blade = frame.add_member(root, tip, ss.SectionProperties(E=2.06e11, rho=7800, A=6e-5, I=2e-11), 20)
frame.clamp(root)
basis = ss.compute_modes(frame, num_modes=6)               # 2. mass-normalised modes
dampers = [ss.PointDamper(blade, 0.15, 0.01, 5e3, 5.0, ss.CoulombLaw(0.35, 0.3))]
loads = [ss.PointLoad.harmonic(blade, 0.05, ss.LoadDirection.GlobalX, 20.0, 200.0)]
system = ss.FrictionDampedSystem(frame, basis, dampers, loads)   # 3 + 4 composed

run = ss.simulate(system, 0.5, ss.RunOptions("dopri5", rtol=1e-7, atol=1e-10, output_interval=1e-4),
                  probes=[ss.Probe(blade, 0.2)],           # the tip's X displacement [m]
                  statistics=ss.StatisticsWindow(0.25, 0.5, 2 * np.pi / 200))
print("first natural frequencies [Hz]:", np.round(basis.frequencies_hz()[:3], 1))
print("run:", ss.status_name(run.status), "at t =", run.t, "s;", len(system.events()), "contact switches")
last = run.sample_t >= 0.25
print("tip amplitude over the last 0.25 s: %.3e m" % np.max(np.abs(run.probes[last, 0])))
print("damper stick fraction: %.2f" % run.damper_statistics[0].stick_fraction)
print("energy audit: relative closing error %.1e" % run.energy.relative_residual())
if not run.ok:
    raise SystemExit("the run failed: " + run.message)
