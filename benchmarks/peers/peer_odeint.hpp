#pragma once
// The problems with Boost.Odeint as a user would write them: runge_kutta_dopri5 with dense
// output, a check of each guard for a sign change after every step, bisection on the dense
// output to locate the earliest crossing, then the mode switch and a restart of the stepper.

#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>

#include <array>

#include "peers/peer_problems.hpp"
#include "peers/peer_run.hpp"

namespace peers {

template <int N>
RunOutcome run_odeint_n(const ChainParameters& p, double tolerance) {
  namespace odeint = boost::numeric::odeint;
  using state_type = std::array<double, 2 * N>;
  using Vec = typename Chain<N>::Vec;
  const Chain<N> chain(p);
  const double T = p.t_end;
  const double event_tolerance = 1e-12;  // s, the library's default event_time_tolerance

  RunOutcome out;
  ContactState mode;
  auto positions = [](const state_type& s) { return Eigen::Map<const Vec>(s.data()); };
  auto velocities = [](const state_type& s) { return Eigen::Map<const Vec>(s.data() + N); };
  auto rhs = [&](const state_type& s, state_type& ds, double t) {
    ++out.rhs_evaluations;
    Vec a;
    chain.acceleration(mode, t, positions(s), velocities(s), a);
    for (int i = 0; i < N; ++i) {
      ds[static_cast<std::size_t>(i)] = s[static_cast<std::size_t>(N + i)];
      ds[static_cast<std::size_t>(N + i)] = a[i];
    }
  };
  auto guards = [&](double t, const state_type& s, double* d) {
    chain.guards(mode, t, positions(s), velocities(s), d);
  };

  state_type x;
  for (int i = 0; i < N; ++i) {
    x[static_cast<std::size_t>(i)] = p.x0[i];
    x[static_cast<std::size_t>(N + i)] = p.v0[i];
  }
  mode = decide_mode(p, p.v0[p.friction_dof] - p.belt_speed,
                     chain.stick_force(0.0, positions(x), velocities(x)));
  auto stepper = odeint::make_dense_output(tolerance, tolerance,
                                           odeint::runge_kutta_dopri5<state_type>());
  stepper.initialize(x, 0.0, 1e-3);
  double before[2], after[2];
  guards(0.0, x, before);
  state_type xe;
  while (stepper.current_time() < T) {
    if (out.steps >= 5'000'000) {
      out.message = "odeint: step budget exhausted";
      return out;
    }
    stepper.do_step(rhs);
    ++out.steps;
    const double t0 = stepper.previous_time(), t1 = stepper.current_time();
    const int ng = chain.num_guards(mode);
    guards(t1, stepper.current_state(), after);
    bool any = false;
    for (int i = 0; i < ng; ++i) any = any || (before[i] > 0.0 && after[i] <= 0.0);
    if (!any) {
      std::copy(after, after + ng, before);
      continue;
    }
    // Bisection on the dense output for the earliest guard that falls to <= 0.
    double lo = t0, hi = t1;
    int fired = 0;
    double d[2];
    while (hi - lo > event_tolerance) {
      const double mid = 0.5 * (lo + hi);
      stepper.calc_state(mid, xe);
      guards(mid, xe, d);
      bool crossed = false;
      for (int i = 0; i < ng; ++i) crossed = crossed || (before[i] > 0.0 && d[i] <= 0.0);
      if (crossed) {
        hi = mid;
      } else {
        lo = mid;
      }
    }
    if (hi >= T) break;  // the event lies beyond the horizon
    stepper.calc_state(hi, xe);
    guards(hi, xe, d);
    for (int i = ng - 1; i >= 0; --i)
      if (before[i] > 0.0 && d[i] <= 0.0) fired = i;
    Vec pos = positions(xe), vel = velocities(xe);
    const ContactState next = chain.switch_mode(mode, fired, hi, pos, vel);
    out.events.push_back({hi, mode, next});
    mode = next;
    for (int i = 0; i < N; ++i) xe[static_cast<std::size_t>(N + i)] = vel[i];
    stepper.initialize(xe, hi, stepper.current_time_step());
    guards(hi, xe, before);
  }
  stepper.calc_state(T, xe);
  out.final_state = Eigen::Map<const Eigen::Matrix<double, 2 * N, 1>>(xe.data());
  out.ok = true;
  return out;
}

/// Boost.Odeint runge_kutta_dopri5 (dense output) at abs = rel tolerance = `tolerance`.
inline RunOutcome run_odeint(const ChainParameters& p, double tolerance) {
  return p.dofs == 1 ? run_odeint_n<1>(p, tolerance) : run_odeint_n<2>(p, tolerance);
}

}  // namespace peers
