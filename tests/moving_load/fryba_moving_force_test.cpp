// Frýba's classical moving-load benchmark (L. Frýba, Vibration of Solids and Structures under
// Moving Loads, 1972, ch. 1): a simply supported Euler-Bernoulli beam crossed by a constant force
// P at constant speed v. Modal superposition with MemberShapes supplying psi_w(v t) against the
// closed-form series.

#include "stickslip/moving_load/member_shapes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

#include "stickslip/beam.hpp"
#include "stickslip/modal.hpp"

namespace stickslip {
namespace {

// Closed form. With the sine modes phi_j(x) = sqrt(2 / (mu L)) sin(j pi x / L) (mu = rho A),
// omega_j = j^2 omega_1, omega_1 = (pi / L)^2 sqrt(EI / mu), each modal coordinate obeys
//   q_j'' + omega_j^2 q_j = P phi_j(v t) = P sqrt(2 / (mu L)) sin(j Omega t),  Omega = pi v / L,
// q_j(0) = q_j'(0) = 0, solved by q_j = P sqrt(2/(mu L)) [sin(j Omega t) - (j Omega / omega_j)
// sin(omega_j t)] / (omega_j^2 - j^2 Omega^2). With Frýba's speed parameter
//   alpha = Omega / omega_1 = v / v_cr,  v_cr = omega_1 L / pi,
// and 2 P / (mu L omega_1^2) = 2 P L^3 / (pi^4 EI) this is the series (0 <= t <= L / v)
//   w(x, t) = 2 P L^3 / (pi^4 EI) sum_j sin(j pi x / L) / (j^2 (j^2 - alpha^2))
//             [sin(j Omega t) - (alpha / j) sin(j^2 omega_1 t)],
// whose j = alpha term (alpha = 1, j = 1) takes its limit [sin(s) - s cos(s)] / 2, s = omega_1 t.
// Returned in units of the static midspan deflection P L^3 / (48 EI), at x = L / 2.
double series_midspan(double alpha, double omega1_t, int terms) {
  const double pi = M_PI;
  const double Omega_t = alpha * omega1_t;
  double sum = 0.0;
  for (int j = 1; j <= terms; j += 2) {  // even j vanish at midspan
    const double jd = j, sign = ((j / 2) % 2 == 0) ? 1.0 : -1.0;  // sin(j pi / 2)
    const double gap = jd * jd - alpha * alpha;
    if (std::abs(gap) < 1e-12) {
      sum += sign * (std::sin(omega1_t) - omega1_t * std::cos(omega1_t)) / 2.0 / (jd * jd);
    } else {
      sum += sign / (jd * jd * gap) *
             (std::sin(jd * Omega_t) - alpha / jd * std::sin(jd * jd * omega1_t));
    }
  }
  return 48.0 * 2.0 / std::pow(pi, 4) * sum;
}

struct History {
  std::vector<double> fe, exact;  // midspan deflection / static midspan deflection
  double peak_fe = -1e300, peak_exact = -1e300;
};

// FE side: the beam from FrameModel (pin at the left: X, Y fixed; roller at the right: Y fixed),
// 40 elements, its 10 lowest modes (all bending: the first axial mode is ~270 omega_1), and the
// modal equations q'' + Omega^2 q = psi_w(v t) P integrated by classical RK4 with MemberShapes
// evaluating psi_w at every stage (with a cursor, as a simulation would).
History run(double alpha) {
  const double L = 1.0, P = 1.0;
  const SectionProperties<double> sec{2.06e11, 7800.0, 6e-5, 2e-11};
  const double EI = sec.E * sec.I, mu = sec.rho * sec.A;
  FrameModel<double> model;
  const auto left = model.add_node(0.0, 0.0);
  const auto right = model.add_node(L, 0.0);
  const auto beam = model.add_member(left, right, sec, 40);
  model.pin(left);
  model.fix(right, Dof::Y);
  ModalOptions<double> options;
  options.num_modes = 10;
  const auto basis = compute_modes(model.assemble(), options);
  const MemberShapes<double, 10> shapes(model, beam, basis);

  const double omega1 = std::pow(M_PI / L, 2) * std::sqrt(EI / mu);  // analytic omega_1
  const double v = alpha * omega1 * L / M_PI;
  const double T = L / v;  // time on the beam
  const Eigen::Matrix<double, 10, 1> w2 = basis.omega().array().square();
  const double w_static = P * L * L * L / (48 * EI);
  MemberShapes<double, 10>::Values at_mid, s;
  shapes.evaluate(L / 2, at_mid);

  // Step: h omega_max = 0.05 (omega_max ~ 100 omega_1), where RK4's relative phase error per
  // radian, (h omega)^4 / 120, stays ~1e-7 and the highest retained mode is resolved.
  const long steps = static_cast<long>(std::ceil(T * basis.omega().maxCoeff() / 0.05));
  const double h = T / static_cast<double>(steps);
  using V = Eigen::Matrix<double, 10, 1>;
  V q = V::Zero(), qd = V::Zero();
  ElementCursor cursor;
  const auto force = [&](double fraction) {  // fraction = t / T in [0, 1], eps = L * fraction
    shapes.evaluate(L * fraction, s, cursor);
    return V(P * s.psi_w);
  };
  History hist;
  const auto record = [&](long k) {
    const double t = static_cast<double>(k) * h;
    const double fe = at_mid.psi_w.dot(q) / w_static;
    const double exact = series_midspan(alpha, omega1 * t, 201);
    hist.fe.push_back(fe);
    hist.exact.push_back(exact);
    hist.peak_fe = std::max(hist.peak_fe, fe);
    hist.peak_exact = std::max(hist.peak_exact, exact);
  };
  record(0);
  const long record_every = std::max(1L, steps / 2000);
  for (long k = 0; k < steps; ++k) {
    const double n = static_cast<double>(steps);
    const double f0 = static_cast<double>(k) / n, f1 = (static_cast<double>(k) + 0.5) / n,
                 f2 = static_cast<double>(k + 1) / n;
    const V F0 = force(f0), F1 = force(f1), F2 = force(f2);
    const V a1 = F0 - w2.cwiseProduct(q);
    const V q2 = q + 0.5 * h * qd, v2 = qd + 0.5 * h * a1;
    const V a2 = F1 - w2.cwiseProduct(q2);
    const V q3 = q + 0.5 * h * v2, v3 = qd + 0.5 * h * a2;
    const V a3 = F1 - w2.cwiseProduct(q3);
    const V q4 = q + h * v3, v4 = qd + h * a3;
    const V a4 = F2 - w2.cwiseProduct(q4);
    q += h / 6 * (qd + 2 * v2 + 2 * v3 + v4);
    qd += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    if ((k + 1) % record_every == 0 || k + 1 == steps) record(k + 1);
  }
  return hist;
}

// Tolerance 5e-4 of the static midspan deflection (measured: 1.6e-4), on the whole history and
// on the peak dynamic amplification. Budget: truncation to 10 modes drops odd j >= 11 of the
// series, whose static part alone is 96/pi^4 sum_{j>=11, odd} 1/j^4 ~ 1.5e-4 (the dynamic part
// adds less, ~alpha/j of it); the FE frequency error of the retained bending modes with 40
// Hermite elements is below 1e-3 relative even for mode 9, whose midspan share is 1/9^4; RK4
// errors ~1e-6; the series is summed to j = 201 (tail < 1e-7).
constexpr double kTolerance = 5e-4;

class Fryba : public ::testing::TestWithParam<double> {};

TEST_P(Fryba, MidspanHistoryAndPeakAmplificationMatchSeries) {
  const double alpha = GetParam();
  const History hist = run(alpha);
  double max_diff = 0.0;
  for (std::size_t i = 0; i < hist.fe.size(); ++i)
    max_diff = std::max(max_diff, std::abs(hist.fe[i] - hist.exact[i]));
  EXPECT_LT(max_diff, kTolerance) << "alpha = " << alpha;
  EXPECT_NEAR(hist.peak_fe, hist.peak_exact, kTolerance) << "alpha = " << alpha;
  std::cout << "[ Fryba    ] alpha = " << alpha << ": peak dynamic amplification FE "
            << hist.peak_fe << ", series " << hist.peak_exact << ", max history error "
            << max_diff << " (static midspan deflection = 1)" << std::endl;
  // The load leaves the beam with the deflection still growing at alpha = 1; at alpha = 0.1 the
  // response is nearly quasi-static (peak ~1 + alpha). A coarse check that the case is the
  // intended one, independent of the fine comparison above.
  if (alpha < 0.2) {
    EXPECT_NEAR(hist.peak_exact, 1.1, 0.05);
  }
  if (alpha == 1.0) {
    EXPECT_NEAR(hist.exact.back(), hist.peak_exact, 1e-3);
  }
}

INSTANTIATE_TEST_SUITE_P(SpeedParameters, Fryba, ::testing::Values(0.1, 0.5, 1.0));

}  // namespace
}  // namespace stickslip
