"""Systems and relations of one's own, from Python.

Hybrid systems (docs/python_hybrid.md): HybridSystem, HybridStepper and find_periodic_orbit on a
user's own rhs, guards and transitions, checked against closed forms: the harmonic oscillator, the
bouncing ball's impact times, the belt stick-slip cycle's event times, period and multipliers,
and the forced damped oscillator's receptance and Floquet multipliers; bad input and failing user
code are reported, never lost. Contacts with a relation of one's own (PointContact.with_row,
docs/contacts.md): a rotational friction hinge's stuck orbit and first slip against the
constrained linear solve by numpy, and on it poincare_sections of a ContactSystem and
find_periodic_orbit's further ShootingOptions keywords."""
import cmath
import math

import numpy as np
import pytest

import stickslip as ss


class Oscillator:
    """x'' = -w^2 x - 2 zeta w x' + F cos(W t): no guards, one mode."""

    def __init__(self, w, zeta=0.0, force=0.0, forcing=1.0):
        self.w, self.zeta, self.force, self.forcing = w, zeta, force, forcing

    def rhs(self, mode, t, x):
        return np.array([x[1], -self.w ** 2 * x[0] - 2 * self.zeta * self.w * x[1]
                         + self.force * math.cos(self.forcing * t)])

    def num_guards(self, mode):
        return 0

    def guards(self, mode, t, x):
        return np.zeros(0)

    def guard_direction(self, mode, i):
        return ss.CrossingDirection.Either

    def transition(self, mode, triggered, t, x):
        return mode


class BouncingBall:
    """y'' = -g; at y = 0 falling, v <- -e v; stops after `bounces` impacts when given."""

    def __init__(self, g=9.81, e=0.8, bounces=None):
        self.g, self.e, self.bounces, self.count = g, e, bounces, 0

    def rhs(self, mode, t, x):
        return np.array([x[1], -self.g])

    def num_guards(self, mode):
        return 1

    def guards(self, mode, t, x):
        return np.array([x[0]])

    def guard_direction(self, mode, i):
        return ss.CrossingDirection.Falling

    def transition(self, mode, triggered, t, x):
        self.count += 1
        reason = "bounce %d" % self.count if self.bounces and self.count >= self.bounces else None
        return mode, np.array([0.0, -self.e * x[1]]), reason


STICK, SLIP = 0, 1


class Belt:
    """A mass on a spring to ground, on a belt moving at v: stuck (x' = v) until k x = mu_s N,
    then slipping back (m x'' = -k x + mu_k N) until x' = v again."""

    def __init__(self, m=1.0, k=4 * math.pi ** 2, fs=1.0, fk=0.6, v=0.05):
        self.m, self.k, self.fs, self.fk, self.v = m, k, fs, fk, v

    def rhs(self, mode, t, x):
        if mode == STICK:
            return np.array([self.v, 0.0])
        return np.array([x[1], (-self.k * x[0] + self.fk) / self.m])

    def num_guards(self, mode):
        return 1

    def guards(self, mode, t, x):
        if mode == STICK:
            return np.array([self.fs - self.k * x[0]])  # the friction a stuck mass needs reaches mu_s N
        return np.array([x[1] - self.v])  # the relative velocity returns to zero

    def guard_direction(self, mode, i):
        return ss.CrossingDirection.Falling if mode == STICK else ss.CrossingDirection.Rising

    def transition(self, mode, triggered, t, x):
        if mode == STICK:
            return SLIP
        return STICK, np.array([x[0], self.v])

    def cycle(self):
        """The closed-form belt cycle: stick limit x_s, slip time, stick time, the stick start x_a."""
        w = math.sqrt(self.k / self.m)
        xs, xk = self.fs / self.k, self.fk / self.k
        d = xs - xk
        slip = (math.pi + 2 * math.atan2(self.v / w, d)) / w
        return xs, slip, 2 * d / self.v, 2 * xk - xs


def tight(integrator="dopri5", **kw):
    kw.setdefault("rtol", 1e-11)
    kw.setdefault("atol", 1e-13)
    return ss.RunOptions(integrator, **kw)


@pytest.mark.parametrize("integrator,options,tol", [
    # dopri5 at rtol 1e-11 over 6.5 periods: global error ~1e-9 of the unit amplitude.
    ("dopri5", {}, 1e-8),
    # rk4 at h = 1e-3: local error (w h)^5 / 120 per step, 5000 steps: ~1e-9; its dense output
    # (cubic Hermite) is O(h^4) ~ 1e-8 between steps.
    ("rk4", {"fixed_step": 1e-3}, 1e-7),
    # rosenbrock23 at rtol 1e-9: a second-order method, whose global error under per-step control
    # scales as rtol^(2/3) = 1e-6 times a constant of order ten.
    ("rosenbrock23", {"rtol": 1e-9, "atol": 1e-11}, 3e-5),
])
def test_oscillator_samples_are_the_closed_form_cosine(integrator, options, tol):
    w = 2 * math.pi * 1.3
    run = ss.HybridStepper(ss.HybridSystem(Oscillator(w)),
                           tight(integrator, output_interval=0.01, **options)).integrate(0, 0.0, np.array([1.0, 0.0]), 5.0)
    assert run.ok, run.message
    assert run.t == 5.0 and run.mode == 0 and not run.events
    t = run.sample_times
    assert len(t) == 501 and t[0] == 0.0 and abs(t[-1] - 5.0) < 1e-12
    np.testing.assert_allclose(run.samples[:, 0], np.cos(w * t), rtol=0, atol=tol)
    np.testing.assert_allclose(run.samples[:, 1], -w * np.sin(w * t), rtol=0, atol=tol * w)
    assert run.stats.rhs_evaluations > 0 and run.stats.accepted_steps > 0


def test_bouncing_ball_impacts_at_the_closed_form_times_and_stops_when_asked():
    g, e, h = 9.81, 0.8, 1.0
    ball = BouncingBall(g, e)
    run = ss.HybridStepper(ss.HybridSystem(ball), tight()).integrate(0, 0.0, np.array([h, 0.0]), 3.0)
    assert run.ok, run.message
    # Free flight is a quadratic, which Dormand-Prince integrates exactly: the impact times are the
    # closed form's to the event-time tolerance (1e-12) plus round-off accumulated over the bounces.
    v1 = math.sqrt(2 * g * h)
    times = [v1 / g]
    for k in range(1, len(run.events)):
        times.append(times[-1] + 2 * e ** k * v1 / g)
    assert len(run.events) >= 5 and times[-1] < 3.0
    np.testing.assert_allclose([ev.t for ev in run.events], times, rtol=0, atol=1e-9)
    assert all(ev.from_mode == 0 and ev.to_mode == 0 and list(ev.triggered) == [0] for ev in run.events)
    assert ball.count == len(run.events) == run.stats.events

    stop = BouncingBall(g, e, bounces=3)
    run = ss.HybridStepper(ss.HybridSystem(stop), tight()).integrate(0, 0.0, np.array([h, 0.0]), 3.0)
    assert run.status == ss.Status.StoppedBySystem and not run.ok
    assert "bounce 3" in run.message
    assert abs(run.t - times[2]) < 1e-9
    # The reset state is the one handed back: the rebound velocity e^3 v1.
    assert abs(run.x[1] - e ** 3 * v1) < 1e-8


def test_belt_events_and_autonomous_orbit_are_the_closed_form_cycle():
    belt = Belt()
    xs, slip, stick, xa = belt.cycle()
    system = ss.HybridSystem(belt)
    run = ss.HybridStepper(system, tight()).integrate(STICK, 0.0, np.array([0.0, belt.v]), 4.0)
    assert run.ok, run.message
    expected, t, k = [], xs / belt.v, 0
    while t < 4.0:
        expected.append(t)
        t += slip if k % 2 == 0 else stick
        k += 1
    # Event times: the slip phase is harmonic (dopri5 at rtol 1e-11: ~1e-10 s per phase), the
    # stick phase linear (exact); 1e-8 s leaves a margin for the accumulation over six phases.
    np.testing.assert_allclose([ev.t for ev in run.events], expected, rtol=0, atol=1e-8)
    assert [(ev.from_mode, ev.to_mode) for ev in run.events][:2] == [(STICK, SLIP), (SLIP, STICK)]

    # The limit cycle by autonomous shooting from a stuck state on it, with a period guess 10 %
    # off: the period is the closed form's; the stick phase resets the velocity, so the only
    # non-trivial multiplier is 0 (a point map), the trivial one 1.
    x0 = np.array([0.5 * (xa + xs), belt.v])
    orbit = ss.find_periodic_orbit(system, 0.9 * (slip + stick), x0, mode=STICK, autonomous=True)
    assert orbit.ok, orbit.message
    assert abs(orbit.period - (slip + stick)) < 1e-8 * (slip + stick)
    assert orbit.mode == STICK and len(orbit.events) == 2
    assert abs(orbit.trivial - 1) < 1e-6
    assert orbit.stable and orbit.max_modulus < 1e-6
    # The largest |x|: the mass breaks away at x_s moving at v and turns at x_k + A, where the slip
    # phase's amplitude is A = sqrt((x_s - x_k)^2 + (v / w)^2). The orbit samples 256 points per
    # period: the sampled peak is within 1 - cos(2 pi / 256) of A (3e-4 of it).
    w = math.sqrt(belt.k / belt.m)
    xk = belt.fk / belt.k
    peak = xk + math.hypot(xs - xk, belt.v / w)
    assert abs(orbit.amplitudes[0] - peak) < 3e-4 * peak


def test_forced_orbit_is_the_receptance_and_its_multipliers_the_damped_exponentials():
    w, zeta, force, forcing = 2 * math.pi, 0.05, 3.0, 2 * math.pi * 1.2
    system = ss.HybridSystem(Oscillator(w, zeta, force, forcing))
    period = 2 * math.pi / forcing
    for monodromy in ("variational", "finite_difference"):
        orbit = ss.find_periodic_orbit(system, period, np.zeros(2), monodromy=monodromy)
        assert orbit.ok, orbit.message
        # x(t) = Re(X e^{i W t}), X = F / (w^2 - W^2 + 2 i zeta w W): at t0 = 0, x = Re X, x' = -W Im X.
        X = force / (w ** 2 - forcing ** 2 + 2j * zeta * w * forcing)
        np.testing.assert_allclose(orbit.x0, [X.real, -forcing * X.imag], rtol=1e-8, atol=1e-12)
        # amplitudes: the largest |x| over 256 samples a period, within 1 - cos(pi / 256) of |X|.
        assert abs(orbit.amplitudes[0] - abs(X)) < 1e-4 * abs(X)
        # M = exp(A T): eigenvalues exp(lambda T), lambda = -zeta w +- i w sqrt(1 - zeta^2); the
        # finite-difference monodromy is accurate to ~fd_step, the variational one to rtol.
        lam = complex(-zeta * w, w * math.sqrt(1 - zeta ** 2))
        mu = sorted([cmath.exp(lam * period), cmath.exp(lam.conjugate() * period)], key=lambda z: z.imag)
        got = sorted(orbit.multipliers, key=lambda z: z.imag)
        np.testing.assert_allclose(got, mu, rtol=0, atol=1e-6)
        assert orbit.stable and orbit.instability == ss.Instability.Stable


def test_bad_systems_options_and_user_errors_are_reported():
    class NoGuards:
        def rhs(self, mode, t, x):
            return x

    with pytest.raises(ValueError, match="no method num_guards"):
        ss.HybridSystem(NoGuards())
    with pytest.raises(ValueError, match="options.integrator must be rk4, dopri5 or rosenbrock23"):
        ss.HybridStepper(ss.HybridSystem(Oscillator(1.0)), ss.RunOptions("exponential"))
    with pytest.raises(ValueError, match="rtol"):
        ss.HybridStepper(ss.HybridSystem(Oscillator(1.0)), ss.RunOptions("dopri5", rtol=-1.0))
    stepper = ss.HybridStepper(ss.HybridSystem(Oscillator(1.0)))
    with pytest.raises(ValueError, match="t_end"):
        stepper.integrate(0, 1.0, np.array([1.0, 0.0]), 0.5)
    with pytest.raises(ValueError, match="x0 must be finite"):
        stepper.integrate(0, 0.0, np.array([math.nan, 0.0]), 1.0)

    class WrongSize(Oscillator):
        def rhs(self, mode, t, x):
            return np.zeros(3)

    with pytest.raises(ValueError, match="rhs returned 3 values where 2 are needed"):
        ss.HybridStepper(ss.HybridSystem(WrongSize(1.0))).integrate(0, 0.0, np.array([1.0, 0.0]), 1.0)

    class Raises(Oscillator):
        def rhs(self, mode, t, x):
            if t > 0.5:
                raise ZeroDivisionError("the user's model failed at t = %g" % t)
            return super().rhs(mode, t, x)

    with pytest.raises(ZeroDivisionError, match="the user's model failed"):
        ss.HybridStepper(ss.HybridSystem(Raises(1.0))).integrate(0, 0.0, np.array([1.0, 0.0]), 1.0)

    class BlowsUp(Oscillator):
        def rhs(self, mode, t, x):
            return np.array([x[1], math.nan if t > 0.25 else 0.0])

    run = ss.HybridStepper(ss.HybridSystem(BlowsUp(1.0))).integrate(0, 0.0, np.array([1.0, 0.0]), 1.0)
    assert run.status == ss.Status.NonFiniteState and not run.ok
    # The run ends where the last finite step ended, at the NaN's onset.
    assert 0.2 < run.t <= 0.25 + 1e-9 and "non" in run.message.lower()

    class FloatMode(BouncingBall):
        def transition(self, mode, triggered, t, x):
            return 1.5

    with pytest.raises(ValueError, match="the mode must be an int"):
        ss.HybridStepper(ss.HybridSystem(FloatMode())).integrate(0, 0.0, np.array([1.0, 0.0]), 1.0)
    with pytest.raises(ValueError, match="monodromy"):
        ss.find_periodic_orbit(ss.HybridSystem(Oscillator(1.0)), 1.0, np.zeros(2), monodromy="exact")
    with pytest.raises(ValueError, match="t0 must be 0"):
        ss.find_periodic_orbit(ss.HybridSystem(Oscillator(1.0)), 1.0, np.zeros(2), t0=1.0, autonomous=True)


def hinge_scene(limit):
    """A clamped cantilever (20 elements, 4 modes, 1 % modal damping) forced at its tip along X,
    with a rotational friction hinge to ground at mid-span: a relation of one's own, w = the
    rotation's modal row (PointContact.with_row), with a Coulomb limit mu_s N = limit [N m]."""
    f = ss.FrameModel()
    root, tip = f.add_node(0, 0), f.add_node(0, 0.2)
    beam = f.add_member(root, tip, ss.SectionProperties(2.06e11, 7800, 6e-5, 2e-11), 20)
    f.clamp(root)
    basis = ss.compute_modes(f, num_modes=4).with_modal_damping(np.full(4, 0.01))
    mid = f.member_nodes(beam)[10]
    hinge = ss.PointContact.with_row(lambda frame, b: b.nodal(mid, ss.Dof.Rz), ss.CoulombLaw(1.0, 0.8), limit)
    load = ss.PointLoad.harmonic(beam, 0.2, ss.LoadDirection.GlobalX, 2.0, 300.0)
    return ss.ContactSystem(f, basis, [hinge], [load]), basis, basis.nodal(mid, ss.Dof.Rz), basis.nodal(tip, ss.Dof.X)


def stuck_hinge_response(basis, w, phi, amplitude, W):
    """The stuck hinge's steady state by numpy: [K - W^2 + i W C, -w; w^T, 0] [Q; L] = [F; 0],
    q = Im(Q e^{iWt}) and the hinge's moment f = Im(L e^{iWt}); returns (Q, L)."""
    n = basis.size()
    A = np.zeros((n + 1, n + 1), complex)
    A[:n, :n] = np.diag(basis.omega() ** 2 - W ** 2 + 1j * W * basis.damping_coefficients())
    A[:n, n], A[n, :n] = -w, w
    sol = np.linalg.solve(A, np.concatenate([amplitude * phi, [0.0]]))
    return sol[:n], sol[n]


def test_contact_of_ones_own_row_stuck_orbit_and_first_slip_are_the_constrained_closed_form():
    """The stuck hinge's steady state is the linear system constrained by w . q = 0, solved here by
    numpy ([K - W^2 + i W C, -w; w^T, 0] [Q; L] = [F; 0], q = Im(Q e^{iWt}), the hinge's moment
    f = Im(L e^{iWt})); with mu_s N above |L| the orbit never slips, with mu_s N = 0.8 |L| a run
    from that state slips first where |L| |sin(W t + arg L)| reaches mu_s N."""
    W, amplitude = 300.0, 2.0
    system, basis, w, phi = hinge_scene(1.0)
    n = basis.size()
    assert system.num_contacts() == 1 and system.contacts()[0].has_row
    np.testing.assert_array_equal(system.contact_row(0), w)
    Q, L = stuck_hinge_response(basis, w, phi, amplitude, W)
    x_stuck = np.concatenate([Q.imag, W * Q.real, np.zeros(system.state_size() - 2 * n)])

    stuck, *_ = hinge_scene(1.5 * abs(L))
    orbit = ss.find_periodic_orbit(stuck, 2 * math.pi / W, x0=np.zeros(stuck.state_size()))
    assert orbit.ok, orbit.message
    assert not orbit.events and orbit.stick_fractions[0] == 1.0
    # A stuck hinge holds any static moment c within its limit: the stuck orbits are x_stuck plus
    # the static deflection c u, u = K^-1 w (Newton's minimum-norm step picks one). Off that
    # direction, and in the velocities, a linear solve on both sides agrees to the shooting
    # tolerance (1e-9 of max(1, |x0|)).
    u = w / basis.omega() ** 2
    d = orbit.x0[:n] - x_stuck[:n]
    c = d @ u / (u @ u)
    tol = 1e-9
    np.testing.assert_allclose(d - c * u, 0, rtol=0, atol=tol)
    np.testing.assert_allclose(orbit.x0[n:2 * n], x_stuck[n:2 * n], rtol=0, atol=tol)
    # c is the static moment the hinge holds (K c u = w c): stuck all period, |c| + |L| <= mu_s N = 1.5 |L|.
    assert abs(c) <= 0.5 * abs(L)

    slipping, *_ = hinge_scene(0.8 * abs(L))
    run = ss.simulate(slipping, 2 * math.pi / W, ss.RunOptions("dopri5", rtol=1e-10, atol=1e-14), x0=x_stuck)
    assert run.ok, run.message
    events = slipping.events()
    assert events and events[0].from_state == ss.ContactState.Stick
    phase = np.angle(L)
    t = np.linspace(0, 2 * math.pi / W, 200001)
    first = t[np.argmax(abs(L) * np.abs(np.sin(W * t + phase)) >= 0.8 * abs(L))]
    # The closed form's crossing on a grid of 1e-7 s; the event is located to 1e-12 s on the run.
    assert abs(events[0].t - first) < 2e-7


def test_contact_of_ones_own_row_runs_as_the_same_point_contact_and_bad_rows_are_refused():
    system, basis, w, phi = hinge_scene(0.05)
    f = ss.FrameModel()
    # The same relation through with_row and through grounded at the tip: the same run, bit for bit.
    root, tip = f.add_node(0, 0), f.add_node(0, 0.2)
    beam = f.add_member(root, tip, ss.SectionProperties(2.06e11, 7800, 6e-5, 2e-11), 20)
    f.clamp(root)
    b = ss.compute_modes(f, num_modes=4)
    law = ss.CoulombLaw(0.35, 0.3)
    load = [ss.PointLoad.harmonic(beam, 0.2, ss.LoadDirection.GlobalX, 2.0, 300.0)]
    point = ss.PointContact.grounded(ss.StructurePoint(beam, 0.2), ss.PlaneDirection.global_x(), law, 0.5)
    row = ss.PointContact.with_row(lambda frame, basis: basis.nodal(tip, ss.Dof.X), law, 0.5)
    runs = [ss.simulate(ss.ContactSystem(f, b, [c], load), 0.05, ss.RunOptions("dopri5", rtol=1e-8)) for c in (point, row)]
    assert runs[0].ok and runs[1].ok and len(runs[0].transitions) > 2
    assert runs[0].x.tobytes() == runs[1].x.tobytes() and runs[0].t == runs[1].t

    with pytest.raises(ValueError, match="row must return one value per retained mode"):
        ss.ContactSystem(f, b, [ss.PointContact.with_row(lambda frame, basis: np.zeros(3), law, 0.5)], load)
    with pytest.raises(ValueError, match="row must return finite values"):
        ss.ContactSystem(f, b, [ss.PointContact.with_row(lambda frame, basis: np.full(4, math.nan), law, 0.5)], load)
    with pytest.raises(ValueError, match="N"):
        ss.PointContact.with_row(lambda frame, basis: np.zeros(4), law, 0.0)


def test_contact_system_sections_and_orbit_details_reach_the_constrained_closed_form():
    """poincare_sections on a ContactSystem and find_periodic_orbit's further ShootingOptions
    keywords, on the stuck hinge whose steady state numpy solves (as above)."""
    W, amplitude = 300.0, 2.0
    system, basis, w, phi = hinge_scene(1.0)
    n = basis.size()
    Q, L = stuck_hinge_response(basis, w, phi, amplitude, W)
    stuck, *_ = hinge_scene(1.5 * abs(L))
    x_stuck = np.concatenate([Q.imag, W * Q.real, np.zeros(stuck.state_size() - 2 * n)])
    T = 2 * math.pi / W

    # Started on the stuck steady state, a linear response: every section is that state (rtol
    # 1e-10 runs: 1e-8 of its scale), and the verdict is period 1.
    sections = ss.poincare_sections(stuck, T, x0=x_stuck, transient_periods=2, record_periods=8, max_period=4)
    assert sections.periodic and sections.period == 1, sections.status
    scale = np.abs(x_stuck[:2 * n]).max()
    np.testing.assert_allclose(sections.states[:, :2 * n], np.tile(x_stuck[:2 * n], (8, 1)), rtol=0, atol=1e-8 * scale)

    # amplitudes of the chosen components from samples_per_period samples of the orbit: within
    # 1 - cos(pi / samples) of the modal amplitudes |Q_i| (the stuck orbit carries no static moment
    # here: it is started on x_stuck).
    for samples, tol in ((256, 1e-4), (4096, 1e-6)):
        orbit = ss.find_periodic_orbit(stuck, T, x0=x_stuck, samples_per_period=samples, amplitude_components=[0, 1])
        assert orbit.ok, orbit.message
        assert len(orbit.amplitudes) == 2
        np.testing.assert_allclose(orbit.amplitudes, np.abs(Q[:2]), rtol=tol)
    orbit = ss.find_periodic_orbit(stuck, T, x0=x_stuck, monodromy="finite_difference", fd_step=1e-5,
                                   control_sensitivities=False, max_step=T / 20, guard_samples=2,
                                   multiplier_tolerance=1e-3)
    assert orbit.ok and orbit.stable, orbit.message
    for keyword, value in (("fd_step", 0.5), ("max_step", 0.0), ("guard_samples", -1), ("samples_per_period", -1),
                           ("multiplier_tolerance", -1.0), ("amplitude_components", [99])):
        with pytest.raises(ValueError, match=keyword):
            ss.find_periodic_orbit(stuck, T, x0=x_stuck, **{keyword: value})
