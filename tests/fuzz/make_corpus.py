#!/usr/bin/python3
"""Writes the hand-made regression corpus of the fuzz harnesses: tests/fuzz/corpus/<harness>/<name>.

Each input is written field by field in the encoding of tests/fuzz/fuzz_input.hpp and in the field
order of the harness (see the "Layout" comment at the top of each tests/fuzz/<harness>_fuzz.cpp
and of fuzz_frames.hpp). Values are written exactly (raw IEEE doubles / int64), so the files are
reproducible: run `/usr/bin/python3 tests/fuzz/make_corpus.py` from the repository root after
changing a layout, and commit the result. Inputs found by fuzzing (scripts/fuzz.sh) are copied
into the corpus folders as they are, named after what they reproduce.
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def R(x):
    """A double, exactly (tag 32: 8 raw bytes follow)."""
    return bytes([32]) + struct.pack('<d', float(x))


def I(n):
    """An integer, exactly (tag 16: 8 raw bytes of int64 follow)."""
    return bytes([16]) + struct.pack('<q', n)


def C(k):
    """A choice(n) / flag() byte equal to k (k < n)."""
    return bytes([k])


INF = float('inf')
NAN = float('nan')
LONG_MAX = 2**63 - 1

# --- frames (fuzz_frames.hpp) -------------------------------------------------------------------
STEEL = dict(E=2.06e11, rho=7800.0, A=6e-5, I=2e-11)


def frame(topology=0, E=STEEL['E'], rho=STEEL['rho'], A=STEEL['A'], I_=STEEL['I'], L=0.2, theta=0.0,
          elements=4, tiny=None, lumped=False, masses=(), spring=None):
    """topology 0 cantilever, 1 free-free beam, 2 T-frame, 3 free-free T-frame, 4 pinned beam; masses: list of
    (at_tip, m); spring: k on the tip's Y or None."""
    b = C(topology) + R(E) + R(rho) + R(A) + R(I_) + R(L) + R(theta) + I(elements)
    b += C(1) + R(tiny) if tiny is not None else C(0)
    b += C(1 if lumped else 0) + C(len(masses))
    for at_tip, m in masses:
        b += C(1 if at_tip else 0) + R(m)
    b += C(1) + R(spring) if spring is not None else C(0)
    return b


# --- contact_fuzz.cpp ---------------------------------------------------------------------------
def contact_probe(state, v, N, f, watch=False):
    return C(state) + R(v) + R(N) + R(f) + C(1 if watch else 0)


def impact_probe(e, landing_speed, W_nn, W_nt, W_tt, v_n, v_t, W_tn=None):
    """Kind 5 of contact_fuzz.cpp: an impact; W_tn given makes W asymmetric."""
    b = C(5) + R(e) + R(landing_speed) + R(W_nn) + R(W_nt) + R(W_tt)
    b += C(1) + R(W_tn) if W_tn is not None else C(0)
    return b + R(v_n) + R(v_t)


def contact_coulomb(mu_s, mu_k, tol, probes):
    return C(0) + R(mu_s) + R(mu_k) + R(tol) + b''.join(probes)


def contact_regularised(mu, v_eps, linear, tol, probes):
    return C(2) + R(mu) + R(v_eps) + C(1 if linear else 0) + R(tol) + b''.join(probes)


# --- stepper_fuzz.cpp ---------------------------------------------------------------------------
def stepper(m=1.0, k=1.0, F0=0.0, omega=1.0, v_belt=0.0, N=1.0, mu_s=0.4, mu_k=0.3, method=1,
            bisection=False, fixed_step=1e-3, rtol=1e-6, atol=1e-9, output_interval=0.0, min_step=1e-14,
            max_steps=20000, zeno_max_events=1000, zeno_window=1e-6, t0=0.0, span=10.0, x0=0.0, v0=0.0,
            mode=0):
    """method 0 RK4, 1 DormandPrince54, 2 Rosenbrock23; mode 0 stick, 1 slip+, 2 slip-."""
    return (R(m) + R(k) + R(F0) + R(omega) + R(v_belt) + R(N) + R(mu_s) + R(mu_k) + C(method) +
            C(1 if bisection else 0) + R(fixed_step) + R(rtol) + R(atol) + R(output_interval) + R(min_step) +
            I(max_steps) + I(zeno_max_events) + R(zeno_window) + R(t0) + R(span) + R(x0) + R(v0) + C(mode))


# --- frame_modes_fuzz.cpp -----------------------------------------------------------------------
def frame_modes(fr, num_modes=4, solver=0, alpha=0.0, beta=0.0):
    """solver 0 Auto, 1 Dense, 2 Sparse."""
    return fr + I(num_modes) + C(solver) + R(alpha) + R(beta)


# --- member_shapes_fuzz.cpp ---------------------------------------------------------------------
def member_shapes(fr, num_modes=4, member=0, policy=0, eps=()):
    """policy 0 Throw, 1 Clamp, 2 Extrapolate."""
    return fr + I(num_modes) + C(member) + C(policy) + b''.join(R(e) for e in eps)


# --- model_fuzz.cpp -----------------------------------------------------------------------------
def coulomb_law(mu_s=0.35, mu_k=0.3):
    return C(0) + R(mu_s) + R(mu_k)


def damper(member=1, X0=0.01, m=0.05, k=1e4, N0=30.0, law=None, share=0.5, side_minus=False, state=0,
           inertial=True):
    return (C(member) + R(X0) + R(m) + R(k) + R(N0) + (law or coulomb_law()) + R(share) +
            C(1 if side_minus else 0) + C(state) + C(1 if inertial else 0))


def load(member=0, at=0.05, direction=0, amplitude=20.0, omega=200.0, phase=0.0):
    return C(member) + R(at) + C(direction) + R(amplitude) + R(omega) + R(phase)


def model(fr, num_modes=2, alpha=0.0, beta=0.0, dampers=(), loads=(), constant_normal=False, moving=True,
          convective=True, watch_lift_off=True, audit=True, end_policy=0, integrator=1, fixed_step=1e-5,
          rtol=1e-6, atol=1e-9, max_steps=2000, unchecked=False, t_end=2e-3, state_size=0, mode_size=0):
    """integrator 0 RK4, 1 DormandPrince54, 2 Rosenbrock23; state_size / mode_size 0 right,
    6 one short, 7 one long."""
    b = fr + I(num_modes) + R(alpha) + R(beta) + C(len(dampers)) + b''.join(dampers)
    b += C(len(loads)) + b''.join(loads)
    b += b''.join(C(1 if x else 0) for x in (constant_normal, moving, convective, watch_lift_off, audit))
    b += C(end_policy) + C(integrator) + R(fixed_step) + R(rtol) + R(atol) + I(max_steps)
    b += C(1 if unchecked else 0) + R(t_end) + C(state_size) + C(mode_size)
    return b


T_FRAME = frame(topology=2, L=0.2, elements=4)


# --- steady_state_fuzz.cpp ----------------------------------------------------------------------
def steady_state(m=2.0, k=50.0, F0=10.0, omega=5.0, v_belt=0.0, N=4.0, mu_s=0.25, mu_k=0.25, mode=1, x0=0.1,
                 v0=0.0, t0=0.0, order=0, rtol=1e-10, atol=1e-12, max_steps=5000, tolerance=1e-9, max_iterations=6,
                 monodromy=0, control=True, fd_step=1e-6, action=0, transient=4, max_period=2, half=0.05,
                 initial_step=0.05, max_points=3, chord=0, section_margin=0.0):
    """mode 0 stick, 1 slip+, 2 slip-; order c: T = (1 + c) 2 pi / omega; monodromy 0 variational, 1 finite
    differences; action 0 shooting, 1 Poincare sections, 2 continuation in omega."""
    b = (R(m) + R(k) + R(F0) + R(omega) + R(v_belt) + R(N) + R(mu_s) + R(mu_k) + C(mode) + R(x0) + R(v0) + R(t0) +
         C(order) + R(rtol) + R(atol) + I(max_steps) + R(tolerance) + I(max_iterations) + C(monodromy) +
         C(1 if control else 0) + R(fd_step) + C(action))
    if action == 1:
        b += I(transient) + I(max_period)
    elif action == 2:
        b += R(half) + R(initial_step) + I(max_points) + I(chord) + R(section_margin)
    return b


# --- separation_fuzz.cpp ------------------------------------------------------------------------
def regularised_law(mu=0.3, v_eps=1e-3, linear=False):
    return C(2) + R(mu) + R(v_eps) + C(1 if linear else 0)


def sep_damper(member=1, X0=0.02, m=0.02, k=1e3, N0=0.4, law=None, share=1.0, side_minus=False, state=0,
               constant_normal=False, fixed_point=False, separation=1, restitution=0.5, landing_speed=1e-4,
               start_end=0, finish_end=0, wall_restitution=1.0):
    """Enum bytes (separation_fuzz.cpp's enum_byte): state 0 stick, 1 slip+, 2 slip-, 244 separated, >= 248 out of
    range; separation 0 Stop, 1 Separate, >= 248 out of range; start_end / finish_end 0 Default, 1 Stop,
    2 Extend, 3 Wall, >= 248 out of range."""
    return (C(member) + R(X0) + R(m) + R(k) + R(N0) + (law or coulomb_law()) + R(share) +
            C(1 if side_minus else 0) + C(state) + C(1 if constant_normal else 0) + C(1 if fixed_point else 0) +
            C(separation) + R(restitution) + R(landing_speed) + C(start_end) + C(finish_end) + R(wall_restitution))


def separation(L1=0.2, L2=0.04, elements=4, num_modes=2, dampers=(), loads=(), constant_normal=False, moving=True,
               convective=True, watch_lift_off=True, end_policy=0, integrator=1, fixed_step=1e-6, rtol=1e-8,
               atol=1e-12, max_steps=5000, t_end=5e-3):
    """end_policy 0 Throw, 1 Clamp, 2 Extrapolate, >= 248 out of range; integrator 0 RK4, 1 DormandPrince54, 2 Rosenbrock23,
    3 Exponential."""
    b = R(L1) + R(L2) + I(elements) + I(num_modes) + C(len(dampers)) + b''.join(dampers)
    b += C(len(loads)) + b''.join(loads)
    b += b''.join(C(1 if x else 0) for x in (constant_normal, moving, convective, watch_lift_off))
    b += C(end_policy) + C(integrator) + R(fixed_step) + R(rtol) + R(atol) + I(max_steps) + R(t_end)
    return b

CORPUS = {
    'contact': {
        # mu / v_eps overflows, the derivative was inf * 0 = NaN
        'item11_regularised_derivative_tiny_v_eps': contact_regularised(
            0.3, 1e-310, False, 1.5e-8, [contact_probe(1, 0.01, 1.0, 0.0)]),
        'item11_regularised_derivative_tiny_v_eps_linear': contact_regularised(
            0.3, 1e-310, True, 1.5e-8, [contact_probe(1, 1e-311, 1.0, 0.0)]),
        'decide_rules_coulomb': contact_coulomb(0.4, 0.3, 1e-8, [
            contact_probe(0, 0.0, 1.0, 0.39), contact_probe(0, 0.0, 1.0, -0.41),
            contact_probe(1, -1e-6, 1.0, 0.1), contact_probe(2, 0.0, 0.0, 1.0),
            contact_probe(1, 0.0, -1.0, 0.0, True)]),
        'decide_non_finite_inputs': contact_coulomb(0.4, 0.3, 1e-8, [
            contact_probe(0, NAN, 1.0, 0.0), contact_probe(1, 0.0, INF, 0.0), contact_probe(2, 0.0, 1.0, -INF)]),
        # the Separated state (4): no friction force, one Falling guard (the gap), decide's rules
        'separated_state': contact_coulomb(0.4, 0.3, 1e-8, [
            contact_probe(4, 0.5, 1e-3, 0.1), contact_probe(4, 0.0, 0.0, 0.0, True), contact_probe(4, 0.0, 2.0, 0.7),
            contact_probe(4, NAN, INF, -INF, True)]),
        # impacts (kind 5) with the directions decoupled (W_nt = 0): a bounce that sticks, a bounce
        # that slips, a landing below the landing speed, a plastic impact (e = 0), no approach (v_n > 0), and an
        # elastic impact (e = 1) that loses only the sliding energy
        'impact_decoupled': contact_coulomb(0.4, 0.3, 1e-8, [
            impact_probe(0.5, 1e-4, 20.0, 0.0, 20.0, -1.0, 0.01), impact_probe(0.5, 1e-4, 20.0, 0.0, 20.0, -1.0, 5.0),
            impact_probe(0.5, 1e-4, 20.0, 0.0, 20.0, -5e-5, -0.3), impact_probe(0.0, 0.0, 1.0, 0.0, 3.0, -2.0, -1.0),
            impact_probe(0.5, 1e-4, 1.0, 0.0, 1.0, 0.5, 1.0), impact_probe(1.0, 0.0, 2.0, 0.0, 2.0, -1.0, 0.0)]),
        # impacts with the directions coupled (a damper on a modal member: W = I/m + Psi^T Psi), in
        # stick and in slip, e = 1 (Newton + Coulomb may create energy there, reported), and the refusals:
        # W not positive definite, W asymmetric, a non-finite v, e > 1, a negative landing speed
        'impact_coupled': contact_coulomb(0.4, 0.3, 1e-8, [
            impact_probe(0.5, 1e-4, 20.0, 4.0, 25.0, -1.0, 0.01), impact_probe(0.5, 1e-4, 20.0, -4.0, 25.0, -1.0, 3.0),
            impact_probe(1.0, 0.0, 1.0, 0.9, 1.0, -1.0, -0.2), impact_probe(0.5, 1e-4, 1.0, 2.0, 1.0, -1.0, 0.0),
            impact_probe(0.5, 1e-4, 1.0, 0.5, 1.0, -1.0, 0.0, W_tn=0.4), impact_probe(0.5, 1e-4, 1.0, 0.0, 1.0, NAN, 0.0),
            impact_probe(1.5, 1e-4, 1.0, 0.0, 1.0, -1.0, 0.0), impact_probe(0.5, -1e-4, 1.0, 0.0, 1.0, -1.0, 0.0)]),
        # impacts at extreme sizes (well posed at 1e50 / 1e-50; beyond, only the exception types)
        'impact_extremes': contact_coulomb(1e6, 1e6, 0.0, [
            impact_probe(0.5, 0.0, 1e-50, 0.0, 1e50, -1e50, 1e50), impact_probe(1.0, 0.0, 1e50, 1e-50, 1e-50, -1e-300, 1e-300),
            impact_probe(0.5, 0.0, 1e-300, 0.0, 1e-300, -1e300, 1e300), impact_probe(0.5, 0.0, 0.0, 0.0, 1.0, -1.0, 0.0),
            impact_probe(0.5, INF, 1.0, 0.0, 1.0, -1.0, 0.0)]),
        # a regularised law has no stick state: only NewtonImpact is probed
        'impact_regularised': contact_regularised(0.3, 1e-4, False, 1e-8, [
            impact_probe(0.5, 1e-4, 2.0, 1.0, 2.0, -1.0, 0.5), impact_probe(0.0, 0.0, 2.0, 0.0, 2.0, -1.0, 0.5)]),
        'extreme_forces': contact_coulomb(1e6, 1e6, 0.0, [
            contact_probe(1, 1e150, 1e150, 1e150, True), contact_probe(0, 0.0, 1e150, -1e150, True)]),
    },
    'stepper': {
        # ~1e12 on_sample calls within one step (max_steps = 1)
        'item4_output_interval_1e-15_max_steps_1': stepper(output_interval=1e-15, max_steps=1, span=1e-3),
        # t0 = t_end = 1e300, interval 0.01: t0 + k dt rounds to t0 for ever
        'item4_t0_equals_t_end_1e300_interval': stepper(output_interval=0.01, t0=1e300, span=0.0),
        # RK4 at t0 = 1e17 with h = 1e-6: t + h rounds to t (ulp(1e17) = 16)
        'item4_rk4_t0_1e17_h_1e-6': stepper(method=0, fixed_step=1e-6, t0=1e17, span=1024.0),
        # the Zeno ring buffer sized zeno_max_events + 1 (overflow / 8 GB)
        'item12_zeno_max_events_long_max': stepper(zeno_max_events=LONG_MAX, span=0.01),
        'item12_zeno_max_events_1e9': stepper(zeno_max_events=10**9, span=0.01),
        # a located stick event read as a velocity reversal (leftover v ~ 1e-7
        # above the tolerance sqrt(eps)): belt oscillator with RK4 at h = 0.1 and with DOPRI at
        # rtol 1e-4, a forced oscillator on a slow belt with RK4 at h = 0.1
        'item1_belt_rk4_h0.1_stick_read_as_reversal': stepper(
            k=1.0, v_belt=0.5, N=1.0, mu_s=0.5, mu_k=0.3, method=0, fixed_step=0.1, span=50.0),
        'item1_belt_dopri_rtol1e-4_stick_read_as_reversal': stepper(
            k=1.0, v_belt=0.5, N=1.0, mu_s=0.4, mu_k=0.39, method=1, rtol=1e-4, atol=1e-7, span=50.0),
        'item1_forced_belt_rk4_h0.1_stick_read_as_reversal': stepper(
            k=1.0, F0=1.0, omega=0.5, v_belt=0.1, N=1.0, mu_s=1.0, mu_k=0.2, method=0, fixed_step=0.1, span=50.0),
        # a plain Den Hartog run (harmonic force, ground) and a belt run, both well resolved
        'den_hartog_dopri': stepper(k=1.0, F0=2.0, omega=0.8, N=1.0, mu_s=0.5, mu_k=0.4, method=1, rtol=1e-10,
                                    atol=1e-12, span=30.0),
        'belt_rk4': stepper(k=1.0, v_belt=0.5, N=1.0, mu_s=0.5, mu_k=0.3, method=0, fixed_step=1e-3, span=20.0,
                            mode=0),
        'belt_rosenbrock': stepper(k=1.0, v_belt=0.5, N=1.0, mu_s=0.5, mu_k=0.3, method=2, rtol=1e-6, span=20.0),
    },
    'frame_modes': {
        # clamped cantilever with a 1e-9 m / 1e-6 m first element
        'item8_cantilever_1e-9_element_dense': frame_modes(frame(topology=0, elements=4, tiny=1e-9), solver=1),
        'item8_cantilever_1e-6_element_dense': frame_modes(frame(topology=0, elements=4, tiny=1e-6), solver=1),
        # small frames with rigid-body modes
        # (a pinned beam: one element gives two zero frequencies for one rigid-body mode; three
        # elements give omega_1 1146.55 for the dense 1145.60 rad/s; lumped mass: Phi^T M Phi off by
        # 1e-6); free beams and free T-frames pass and stay as guards
        'item8_pinned_beam_1_element_sparse': frame_modes(frame(topology=4, elements=1), num_modes=2, solver=2),
        'item8_pinned_beam_3_elements_sparse': frame_modes(frame(topology=4, elements=3), num_modes=4, solver=2),
        'item8_pinned_beam_lumped_sparse': frame_modes(frame(topology=4, elements=4, lumped=True), num_modes=3,
                                                        solver=2),
        'item8_free_beam_sparse': frame_modes(frame(topology=1, elements=4), num_modes=4, solver=2),
        'item8_free_t_frame_sparse': frame_modes(frame(topology=3, elements=4), num_modes=5, solver=2),
        # two point masses of 1e308 kg; overflowing E I and rho A; a 1e-160 m member
        'item9_point_masses_1e308': frame_modes(frame(topology=0, masses=[(True, 1e308), (True, 1e308)])),
        'item9_E_I_overflow': frame_modes(frame(topology=0, E=1e300, I_=1e10)),
        'item9_rho_A_overflow': frame_modes(frame(topology=0, rho=1e300, A=1e10)),
        'item9_member_1e-160_m': frame_modes(frame(topology=0, L=1e-160, theta=0.3, elements=1)),
        # Rayleigh alpha = 10 on a frame with rigid-body modes
        'item10_rayleigh_alpha_10_free_beam': frame_modes(frame(topology=1, elements=4), solver=1, alpha=10.0),
        # 2^62 elements
        'item12_elements_2_pow_62': frame_modes(frame(topology=0, elements=2**62)),
        'item12_elements_2_pow_40': frame_modes(frame(topology=0, elements=2**40)),
        # found by random inputs: Spectra's own error ("TridiagEigen: eigen decomposition failed",
        # std::runtime_error) escapes compute_modes on a stiff (I = 6.6e214 m^4) free beam
        'item8_sparse_spectra_error_escapes': frame_modes(
            frame(topology=1, E=102436255436.02655, rho=4975.692378118562, A=0.00043380091554131385,
                  I_=6.627624794152039e+214, L=0.08581918059052415, theta=3.149510948348211, elements=4,
                  tiny=0.001950084687571527, masses=[(False, 0.2938277256427863), (False, 0.3118181124589914)],
                  spring=580132.7534905013), num_modes=6, solver=2),
        'cantilever_closed_form': frame_modes(frame(topology=0, elements=8), solver=0),
        'blade_platform_sparse': frame_modes(frame(topology=2, elements=16), num_modes=4, solver=2),
    },
    'member_shapes': {
        'cantilever_throw': member_shapes(frame(topology=0, elements=6), eps=[0.0, 0.2, 0.1, -1e-300, 0.2000001, NAN]),
        't_frame_platform_clamp': member_shapes(T_FRAME, member=1, policy=1, eps=[-1.0, 1e300, 0.01, 0.02]),
        't_frame_blade_extrapolate': member_shapes(T_FRAME, member=0, policy=2, eps=[-0.1, 0.3, 2.0, 1e300]),
        'graded_cantilever': member_shapes(frame(topology=0, elements=3, tiny=1e-4), eps=[1e-4, 5e-5, 0.19]),
    },
    'model': {
        # a state one entry short / long, a DamperStates of the wrong count
        'item7_state_one_short': model(T_FRAME, dampers=[damper(), damper(X0=0.015)], loads=[load()], state_size=6),
        'item7_state_one_long': model(T_FRAME, dampers=[damper()], loads=[load()], state_size=7),
        'item7_mode_one_short': model(T_FRAME, dampers=[damper(), damper(X0=0.015)], loads=[load()], mode_size=6),
        'item7_mode_one_long': model(T_FRAME, dampers=[damper()], loads=[load()], mode_size=7),
        # Rayleigh alpha = 10 on a frame with a rigid-body mode (free-free T-frame)
        'item10_rayleigh_alpha_10_free_t_frame': model(frame(topology=3, elements=4), num_modes=4, alpha=10.0),
        # point masses of 1e308 kg through the model
        'item9_point_masses_1e308_model': model(frame(topology=2, elements=4, masses=[(True, 1e308), (True, 1e308)]),
                                                dampers=[damper()], loads=[load()]),
        'paper_t_frame_dopri': model(T_FRAME, dampers=[damper(), damper(X0=0.015)], loads=[load(amplitude=200.0)]),
        'paper_t_frame_rk4': model(T_FRAME, dampers=[damper()], loads=[load(amplitude=200.0)], integrator=0,
                                   fixed_step=1e-6),
    },
    'steady_state': {
        # Den Hartog's oscillator in continuous sliding (beta 0.6, friction ratio 0.1) and with stops
        'den_hartog_sliding_shooting': steady_state(omega=3.0, N=4.0),
        'den_hartog_stops_finite_difference': steady_state(omega=2.5, N=20.0, mu_s=0.3, mu_k=0.25, mode=0, x0=0.0,
                                                          monodromy=1, control=False),
        'den_hartog_subharmonic_guess': steady_state(omega=9.0, N=8.0, order=1, x0=0.3, v0=-0.5, max_iterations=3),
        'belt_poincare': steady_state(F0=2.0, omega=1.0, v_belt=0.3, N=10.0, mu_s=0.5, mu_k=0.3, mode=0, action=1),
        'den_hartog_continuation': steady_state(omega=3.0, N=4.0, action=2, half=0.1, initial_step=0.1, max_points=3),
        'den_hartog_continuation_chord_margin': steady_state(omega=6.0, N=10.0, mu_s=0.3, action=2, chord=2,
                                                            section_margin=0.05),
        'extremes_nan_guess_tiny_period': steady_state(omega=1e300, x0=NAN, t0=1e17),
    },
    'separation': {
        # the settings of the L-frame energy-audit case: RegularisedLaw(0.275, 9.9e-3), inertial normal load,
        # convective terms, moving contact, Separate with e = 0.31, finish end Extend, end_policy Clamp,
        # Rosenbrock23 at rtol 9.9e-8 for 3.8 ms, on this harness's L-frame (0.2 m blade, 0.04 m arm) with a
        # chosen damper and load: 7 impacts, relative residual 5.6e-6 (the reported 1.3e-3 needs that case's
        # own frame and loads, which this layout does not hold)
        'l_frame_audit_regularised_separate_rosenbrock': separation(
            dampers=[sep_damper(member=1, X0=0.03, m=0.05, k=1e3, N0=2.0, law=regularised_law(0.275, 9.9e-3),
                                restitution=0.31, finish_end=2)],
            loads=[load(member=0, at=0.15, direction=0, amplitude=150.0, omega=1500.0)], end_policy=1, integrator=2,
            rtol=9.9e-8, atol=1e-12, t_end=3.8e-3),
        # an initial state beyond ContactState's five values (accepted and run to Success as if in stick), and
        # the Separated one (refused by name)
        'initial_state_out_of_range': separation(dampers=[sep_damper(state=250)], loads=[load(member=0)]),
        'initial_state_255': separation(dampers=[sep_damper(state=255)], loads=[load(member=0)]),
        'initial_state_separated': separation(dampers=[sep_damper(state=244)], loads=[load(member=0)]),
        # out-of-range Separation, MemberEnd and EndPolicy values (accepted and run to Success)
        'separation_enum_out_of_range': separation(dampers=[sep_damper(separation=250)], loads=[load(member=0)]),
        'member_end_out_of_range': separation(dampers=[sep_damper(finish_end=252)], loads=[load(member=0)]),
        'end_policy_out_of_range': separation(dampers=[sep_damper()], loads=[load(member=0)], end_policy=249),
        # a damper bouncing on the arm (Coulomb, e = 0.5), and one sliding between two walls
        'bouncing_damper_dopri': separation(
            dampers=[sep_damper(m=0.2, N0=0.4, restitution=0.5, fixed_point=True)],
            loads=[load(member=0, at=0.15, amplitude=200.0, omega=1500.0)], rtol=1e-9),
        'walls_both_ends': separation(
            dampers=[sep_damper(X0=0.02, k=0.0, N0=0.4, separation=0, start_end=3, finish_end=3, wall_restitution=0.6,
                                state=1, law=coulomb_law(0.2, 0.2), constant_normal=True)],
            loads=[load(member=0, at=0.15, amplitude=50.0, omega=1500.0)], rtol=1e-9),
        'two_dampers_exponential': separation(
            dampers=[sep_damper(X0=0.01), sep_damper(X0=0.03, side_minus=True, restitution=0.0)],
            loads=[load(member=0, at=0.1, amplitude=200.0, omega=1500.0)], integrator=3, rtol=1e-8),
    },
}


def main():
    for harness, inputs in CORPUS.items():
        folder = os.path.join(HERE, 'corpus', harness)
        os.makedirs(folder, exist_ok=True)
        for name, data in inputs.items():
            with open(os.path.join(folder, name), 'wb') as f:
                f.write(data)
    print('wrote', sum(len(v) for v in CORPUS.values()), 'inputs')


if __name__ == '__main__':
    main()
