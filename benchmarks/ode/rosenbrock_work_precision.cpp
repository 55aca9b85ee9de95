// Where Rosenbrock23 wins: work-precision of Rosenbrock23 (Jacobian by finite differences or by
// the system, re-evaluated every step or reused across accepted steps) against Dormand-Prince 5(4)
// on (a) a stiff linear system (eigenvalues -1 and -1e6, closed form), (b) the regularised
// friction oscillator of tests/contact (tanh law, small v_eps: stiff while |v| < v_eps; reference:
// Dormand-Prince at rtol 1e-12) and (c) a non-stiff harmonic oscillator (closed form).
// Prints a CSV (problem, method, rtol, seconds per run, final-state error, steps, rejected, RHS
// evaluations, Jacobians, LU factorisations) and, per problem, the time of each method at equal
// error relative to the fastest, interpolated log-log on its curve.

#include <stickslip/contact.hpp>
#include <stickslip/ode.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "contact/single_dof_systems.hpp"
#include "ode/ode_bench_systems.hpp"
#include "ode/ode_test_systems.hpp"

namespace {

using Linear = stickslip::test::LinearSystem<2>;
using LinearWithJacobian = stickslip::test::LinearSystemWithJacobian<2>;  // df/dt: differences (0)

using Law = stickslip::RegularisedLaw<double>;
using Friction = contact_test::SingleDofOscillator<Law>;

/// The regularised oscillator m x'' + k x = F(t) + f, f = -mu tanh(v / v_eps) N(t), with its
/// Jacobian and df/dt when UserJacobian (state x, x', W = int F x', D = int -f v).
template <bool UserJacobian>
struct Regularised : Friction {
  using Friction::Friction;
  template <bool U = UserJacobian, std::enable_if_t<U, int> = 0>
  void jacobian(const Mode&, double t, const State& x, Eigen::Matrix4d& j) const {
    const auto& p = parameters();
    const double v = sliding_velocity(x);
    const double n = normal_force(t);
    const double f = -contact().law().coefficient(v) * n;
    const double f_v = -contact().law().coefficient_derivative(v) * n;
    j.setZero();
    j(0, 1) = 1.0;
    j(1, 0) = -p.stiffness / p.mass;
    j(1, 1) = f_v / p.mass;
    j(2, 1) = excitation(t);
    j(3, 1) = -(f_v * v + f);
  }
  template <bool U = UserJacobian, std::enable_if_t<U, int> = 0>
  void time_derivative(const Mode&, double t, const State& x, State& dfdt) const {
    const auto& p = parameters();
    const double v = sliding_velocity(x);
    const double dF = p.force_rate - p.force_amplitude * p.force_frequency *
                                         std::sin(p.force_frequency * t + p.force_phase);
    const double dN = -p.normal_amplitude * p.normal_frequency * std::sin(p.normal_frequency * t);
    const double df = -contact().law().coefficient(v) * dN;
    dfdt << 0.0, (dF + df) / p.mass, dF * x[1], -df * v;
  }
};

struct Point {
  std::string problem, method;
  double rtol, seconds, error;
  stickslip::StepperStats stats;
};

/// One problem: a system factory, initial state, end time and reference final state.
template <class State>
struct Problem {
  std::string name;
  State x0;
  double t_end;
  State reference;
  double atol_over_rtol;
};

template <class Method, class System, class State, class Make>
Point run(const Problem<State>& pb, const std::string& method, double rtol, Make make) {
  System sys = make();
  stickslip::StepperOptions<double> opt;
  opt.rtol = rtol;
  opt.atol = rtol * pb.atol_over_rtol;
  stickslip::HybridStepper<System, Method> stepper(sys, opt);
  const auto mode0 = typename System::Mode{};
  const auto r = stepper.integrate(mode0, 0.0, pb.x0, pb.t_end);
  Point p{pb.name, method, rtol, 0, std::numeric_limits<double>::infinity(), r.stats};
  if (r.ok()) p.error = (r.x - pb.reference).template head<2>().cwiseAbs().maxCoeff();
  p.seconds = stickslip::bench::seconds_per_run([&] {
    const auto rr = stepper.integrate(mode0, 0.0, pb.x0, pb.t_end);
    if (rr.x[0] == 12345.0) std::puts("");
  });
  return p;
}

// Seconds of the curve c at error e, log-log interpolation between neighbours in rtol order;
// NaN outside the range of the curve.
double seconds_at(const std::vector<Point>& c, double e) {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    const double e0 = c[i].error, e1 = c[i + 1].error;
    if (!(std::min(e0, e1) <= e && e <= std::max(e0, e1))) continue;
    const double w = e0 == e1 ? 0.0 : std::log(e / e0) / std::log(e1 / e0);
    const double s = std::exp((1 - w) * std::log(c[i].seconds) + w * std::log(c[i + 1].seconds));
    if (!(s >= best)) best = s;  // the cheapest crossing (curves need not be monotone)
  }
  return best;
}

template <class Sys0, class Sys1, class State, class Make0, class Make1>
void compare(const Problem<State>& pb, const std::vector<double>& rtols,
             const std::vector<double>& dopri_rtols, Make0 make_fd, Make1 make_user) {
  using stickslip::DormandPrince54;
  using stickslip::Rosenbrock23;
  using stickslip::Rosenbrock23Reuse;
  std::vector<std::vector<Point>> curves(5);
  for (double tol : rtols) {
    curves[0].push_back(run<Rosenbrock23, Sys0>(pb, "r23_fd_every", tol, make_fd));
    curves[1].push_back(run<Rosenbrock23, Sys1>(pb, "r23_user_every", tol, make_user));
    curves[2].push_back(run<Rosenbrock23Reuse, Sys0>(pb, "r23_fd_reuse", tol, make_fd));
    curves[3].push_back(run<Rosenbrock23Reuse, Sys1>(pb, "r23_user_reuse", tol, make_user));
  }
  for (double tol : dopri_rtols)
    curves[4].push_back(run<DormandPrince54, Sys0>(pb, "dopri54", tol, make_fd));
  for (const auto& c : curves)
    for (const auto& p : c)
      std::printf("%s,%s,%g,%.4e,%.3e,%ld,%ld,%ld,%ld,%ld\n", p.problem.c_str(), p.method.c_str(),
                  p.rtol, p.seconds, p.error, p.stats.accepted_steps, p.stats.rejected_steps,
                  p.stats.rhs_evaluations, p.stats.jacobian_evaluations, p.stats.factorisations);
  for (double e : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7}) {
    double s[5], fastest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 5; ++i) {
      s[i] = seconds_at(curves[static_cast<std::size_t>(i)], e);
      if (s[i] < fastest) fastest = s[i];
    }
    std::printf("# %s, error %.0e: time / fastest:", pb.name.c_str(), e);
    for (int i = 0; i < 5; ++i)
      std::printf(" %s %.2f", curves[static_cast<std::size_t>(i)][0].method.c_str(),
                  s[i] / fastest);
    std::printf("\n");
  }
}

template <class System>
System make(const Eigen::Matrix2d& a) {
  System s;
  s.a = a;
  return s;
}

contact_test::SingleDofParameters friction_parameters() {
  contact_test::SingleDofParameters p;
  p.mass = 1.0;
  p.stiffness = 10.0;
  p.force_amplitude = 5.0;
  p.force_frequency = 1.5;
  p.normal_force = 8.0;
  p.normal_amplitude = 3.0;
  p.normal_frequency = 3.0;
  p.watch_lift_off = false;  // N >= 5 > 0: no guard, one mode
  return p;
}

}  // namespace

int main() {
  std::printf("problem,method,rtol,seconds,error,steps,rejected,rhs,jacobians,factorisations\n");
  {  // (a) stiff linear system, stiffness ratio 1e6
    Eigen::Matrix2d v;
    v << 1.0, 1.0, 1.0, -1.0;
    const Eigen::Matrix2d a = v * Eigen::Vector2d(-1.0, -1e6).asDiagonal() * v.inverse();
    const Eigen::Vector2d x0(2.0, 0.0);
    const Eigen::Vector2d c = v.inverse() * x0;
    const double t_end = 1.0;
    Problem<Eigen::Vector2d> pb{"stiff_linear", x0, t_end,
                                v * Eigen::Vector2d(c[0] * std::exp(-t_end), 0.0), 1e-3};
    compare<Linear, LinearWithJacobian>(
        pb, {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}, {1e-3, 1e-5, 1e-7, 1e-9},
        [&] { return make<Linear>(a); }, [&] { return make<LinearWithJacobian>(a); });
  }
  {  // (b) regularised friction oscillator, v_eps = 1e-4 m/s (mu N / (m v_eps) ~ 3e4 1/s)
    const Law law(0.4, 1e-4);
    auto make_fd = [&] { return Regularised<false>(friction_parameters(), Friction::Contact(law)); };
    auto make_user = [&] { return Regularised<true>(friction_parameters(), Friction::Contact(law)); };
    const Eigen::Vector4d x0(0.1, 0.0, 0.0, 0.0);
    const double t_end = 10.0;
    Problem<Eigen::Vector4d> ref{"regularised", x0, t_end, x0, 1e-3};
    stickslip::StepperOptions<double> tight;
    tight.rtol = 1e-12;
    tight.atol = 1e-15;
    auto sys = make_fd();
    stickslip::HybridStepper<Regularised<false>, stickslip::DormandPrince54> dp(sys, tight);
    ref.reference = dp.integrate(stickslip::ContactState{}, 0.0, x0, t_end).x;
    compare<Regularised<false>, Regularised<true>>(ref, {1e-3, 1e-4, 1e-5, 1e-6, 1e-7},
                                                   {1e-3, 1e-5, 1e-7, 1e-9}, make_fd, make_user);
  }
  {  // (c) non-stiff harmonic oscillator x'' = -9 x, x(0) = 1: x = cos 3t
    Eigen::Matrix2d a;
    a << 0.0, 1.0, -9.0, 0.0;
    const double t_end = 10.0;
    Problem<Eigen::Vector2d> pb{"nonstiff_oscillator", Eigen::Vector2d(1.0, 0.0), t_end,
                                Eigen::Vector2d(std::cos(3 * t_end), -3 * std::sin(3 * t_end)),
                                1e-3};
    compare<Linear, LinearWithJacobian>(
        pb, {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}, {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9},
        [&] { return make<Linear>(a); }, [&] { return make<LinearWithJacobian>(a); });
  }
  return 0;
}
