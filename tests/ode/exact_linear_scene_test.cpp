// ExactLinearStepper on an exactly linear scene: three degrees of freedom (a rigid-body mode, an
// undamped mode forced at its own frequency, a damped mode), constant and harmonic loads,
// against the closed-form modal solution written here per mode (not from the code under test).

#include <stickslip/ode/exact_linear_stepper.hpp>

#include <gtest/gtest.h>

#include "ode/exact_test_systems.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

namespace ode_exact_linear_scene_test {  // named: the exact-stepper tests share one unity TU
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// q'' + 2 zeta w q' + w^2 q = p0 + sum_k (pc_k cos(W_k t) + ps_k sin(W_k t)), q(0) = q0,
// q'(0) = v0. Particular solutions: constant p0 / w^2 (w > 0) or p0 t^2 / 2 (w = 0); harmonic
// Re[P e^{iWt}], P = (pc - i ps) / (w^2 - W^2 + 2i zeta w W), off resonance; at resonance
// (zeta = 0, W = w) t (pc sin(wt) - ps cos(wt)) / (2w). Homogeneous part fitted to (q0, v0):
// e^{-zeta w t} (A cos(wd t) + B sin(wd t)), wd = w sqrt(1 - zeta^2), or A + B t for w = 0.
struct Sdof {
  double w, zeta, p0;
  std::vector<double> W, pc, ps;

  void particular(double t, double& q, double& v) const {
    q = v = 0;
    if (w > 0) {
      q += p0 / (w * w);
    } else {
      q += 0.5 * p0 * t * t;
      v += p0 * t;
    }
    for (std::size_t k = 0; k < W.size(); ++k) {
      if (zeta == 0 && W[k] == w) {
        const double s = std::sin(w * t), c = std::cos(w * t);
        q += t * (pc[k] * s - ps[k] * c) / (2 * w);
        v += (pc[k] * s - ps[k] * c) / (2 * w) + 0.5 * t * (pc[k] * c + ps[k] * s);
      } else {
        const std::complex<double> P =
            std::complex<double>(pc[k], -ps[k]) /
            std::complex<double>(w * w - W[k] * W[k], 2 * zeta * w * W[k]);
        const std::complex<double> e = std::exp(std::complex<double>(0, W[k] * t));
        q += (P * e).real();
        v += (std::complex<double>(0, W[k]) * P * e).real();
      }
    }
  }
  void state(double q0, double v0, double t, double& q, double& v) const {
    double qp0, vp0;
    particular(0, qp0, vp0);
    const double a = q0 - qp0, b0 = v0 - vp0;
    double qh, vh;
    if (w == 0) {
      qh = a + b0 * t;
      vh = b0;
    } else {
      const double wd = w * std::sqrt(1 - zeta * zeta), s = zeta * w;
      const double B = (b0 + s * a) / wd;
      const double e = std::exp(-s * t), c = std::cos(wd * t), sn = std::sin(wd * t);
      qh = e * (a * c + B * sn);
      vh = e * (-s * (a * c + B * sn) + wd * (-a * sn + B * c));
    }
    particular(t, q, v);
    q += qh;
    v += vh;
  }
};

// u'' + C u' + K u = Q p(t), K = Q diag(w^2) Q^T, C = Q diag(2 zeta w) Q^T; state (u, u', E) with
// the quadrature E' = u_0^2, given to the stepper as a quadratic form (LinearPart::quadrature_forms)
// when `forms` is set.
class LinearScene : public ode_exact_test::Unguarded<Eigen::Matrix<double, 7, 1>> {
 public:
  using Scalar = double;
  using State = Eigen::Matrix<double, 7, 1>;
  using Mode = int;

  explicit LinearScene(bool forms = false) : with_forms(forms) {
    Q = (Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()) *
         Eigen::AngleAxisd(1.1, Vec3(-1, 0.5, 2).normalized()))
            .toRotationMatrix();
    const double w[3] = {0.0, 3.0, 7.0}, zeta[3] = {0.0, 0.0, 0.05};
    const double p0[3] = {0.5, 0.2, -0.3};
    const double pc[2][3] = {{0.1, 0.4, 0.2}, {0.2, 0.0, 0.5}};
    const double ps[2][3] = {{0.0, 0.3, -0.1}, {-0.3, 0.1, 0.0}};
    Vec3 wv, cv;
    for (int i = 0; i < 3; ++i) {
      modes[i] = Sdof{w[i], zeta[i], p0[i], {3.0, 2.0}, {pc[0][i], pc[1][i]}, {ps[0][i], ps[1][i]}};
      wv[i] = w[i] * w[i];
      cv[i] = 2 * zeta[i] * w[i];
      P0[i] = p0[i];
      Pc(i, 0) = pc[0][i];
      Pc(i, 1) = pc[1][i];
      Ps(i, 0) = ps[0][i];
      Ps(i, 1) = ps[1][i];
    }
    K = Q * wv.asDiagonal() * Q.transpose();
    C = Q * cv.asDiagonal() * Q.transpose();
  }

  Vec3 force(double t) const {
    return Q * (P0 + Pc.col(0) * std::cos(3.0 * t) + Ps.col(0) * std::sin(3.0 * t) +
                Pc.col(1) * std::cos(2.0 * t) + Ps.col(1) * std::sin(2.0 * t));
  }
  void rhs(const Mode&, double t, const State& x, State& dxdt) const {
    dxdt.head<3>() = x.segment<3>(3);
    dxdt.segment<3>(3) = force(t) - K * x.head<3>() - C * x.segment<3>(3);
    dxdt[6] = x[0] * x[0];
  }
  bool linear_part(const Mode&, double, const State&, stickslip::LinearPart<double>& lp) const {
    lp.A.setZero(6, 6);
    lp.A.topRightCorner<3, 3>().setIdentity();
    lp.A.bottomLeftCorner<3, 3>() = -K;
    lp.A.bottomRightCorner<3, 3>() = -C;
    lp.b0.setZero(6);
    lp.b0.tail<3>() = Q * P0;
    lp.omega = {3.0, 2.0};
    lp.bc.setZero(6, 2);
    lp.bs.setZero(6, 2);
    lp.bc.bottomRows<3>() = Q * Pc;
    lp.bs.bottomRows<3>() = Q * Ps;
    lp.exact = true;
    lp.version = 1;
    lp.quadrature_forms.clear();
    if (with_forms) {  // E' = z^T Q z, z = (u, u', 1, cos 3t, sin 3t, cos 2t, sin 2t)
      lp.quadrature_forms.assign(1, Eigen::MatrixXd::Zero(11, 11));
      lp.quadrature_forms[0](0, 0) = 1.0;
    }
    return true;
  }

  // Closed form of (u, u') at t from (u, u')(0) via the modal coordinates q = Q^T u.
  Eigen::Matrix<double, 6, 1> exact(const Eigen::Matrix<double, 6, 1>& x0, double t) const {
    const Vec3 q0 = Q.transpose() * x0.head<3>(), v0 = Q.transpose() * x0.tail<3>();
    Vec3 q, v;
    for (int i = 0; i < 3; ++i) modes[i].state(q0[i], v0[i], t, q[i], v[i]);
    Eigen::Matrix<double, 6, 1> out;
    out << Q * q, Q * v;
    return out;
  }

  Mat3 Q, K, C;
  Vec3 P0;
  Eigen::Matrix<double, 3, 2> Pc, Ps;
  Sdof modes[3];
  bool with_forms = false;
};

struct SampleLog : stickslip::NullObserver {
  std::vector<double> t;
  std::vector<LinearScene::State> x;
  bool on_sample(double ts, const LinearScene::State& xs, const int&) {
    t.push_back(ts);
    x.push_back(xs);
    return true;
  }
};

// The scene against the closed form at 401 samples over 20 s, with the grid set by the scene
// (max_step infinite: 1/8 of the period of the fastest mode) and by awkward max_step values.
// Tolerance 1e-12 of each component's largest magnitude: exp(Â delta) (Padé, scaling and
// squaring) and the Taylor series of the samples are accurate to a few units of round-off per
// step, and ~200 grid steps accumulate < 1e-13; an error of the method (a wrong particular
// solution, a resonance handled as off-resonance, a missed damping term) is O(1).
// With `forms` the quadrature is integrated in closed form (Van Loan) on the grid and along the
// samples (one product per sample once the mode has lasted closed_form_after samples): same
// tolerances, and the quadrature is also checked at every sample.
void check_linear_scene(bool forms) {
  LinearScene scene(forms);
  LinearScene::State x0;
  x0 << 0.1, -0.2, 0.3, 0.5, 0.0, -0.4, 0.0;
  // The quadrature E = int u_0^2 dt against 3-point Gauss-Legendre of the closed form on 20000
  // panels (error ~ (h w)^6 / 2e6 relative, < 1e-16); tolerance as for the state. e_at[k]: E at
  // the sample k (50 panels per output interval 0.05).
  double e_ref = 0;
  std::vector<double> e_at{0.0};
  const int panels = 20000;
  const double hp = 20.0 / panels, gl[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)},
               gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (int i = 0; i < panels; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double u0 = scene.exact(x0.head<6>(), hp * (i + 0.5 + 0.5 * gl[j]))[0];
      e_ref += 0.5 * hp * gw[j] * u0 * u0;
    }
    if ((i + 1) % 50 == 0) e_at.push_back(e_ref);
  }
  for (double max_step : {std::numeric_limits<double>::infinity(), 0.037, 0.0913}) {
    stickslip::StepperOptions<double> opt;
    opt.output_interval = 0.05;
    opt.max_step = max_step;
    stickslip::ExactLinearStepper<LinearScene> stepper(scene, opt);
    SampleLog log;
    const auto r = stepper.integrate(0, 0.0, x0, 20.0, log);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(log.t.size(), 401u);
    Eigen::Matrix<double, 6, 1> scale = Eigen::Matrix<double, 6, 1>::Zero(), err = scale;
    for (std::size_t i = 0; i < log.t.size(); ++i) {
      const auto ref = scene.exact(x0.head<6>(), log.t[i]);
      scale = scale.cwiseMax(ref.cwiseAbs());
      err = err.cwiseMax((log.x[i].head<6>() - ref).cwiseAbs());
    }
    EXPECT_LT((err.array() / scale.array()).maxCoeff(), 1e-12)
        << "max_step " << max_step << ", errors " << err.transpose();
    EXPECT_NEAR(r.x[6] / e_ref, 1.0, 1e-12) << "max_step " << max_step;
    double e_err = 0;
    for (std::size_t i = 0; i < log.t.size(); ++i)
      e_err = std::max(e_err, std::abs(log.x[i][6] - e_at[i]) / e_ref);
    EXPECT_LT(e_err, 1e-12) << "max_step " << max_step;
    std::printf("forms %d, max_step %g: state error %.2e, quadrature error %.2e (samples %.2e), "
                "steps %ld, matvecs %ld, exponentials %ld\n",
                forms ? 1 : 0, max_step, (err.array() / scale.array()).maxCoeff(),
                std::abs(r.x[6] / e_ref - 1), e_err, r.stats.accepted_steps,
                stepper.work().matvecs, stepper.work().propagator_exponentials);
    // Once per run (one mode): the grid ladder (2); with forms also the output interval's Van Loan
    // block (1 form; 401 samples) and the grid step's where the run has closed_form_after steps.
    using Stepper = stickslip::ExactLinearStepper<LinearScene>;
    const long expected = !forms ? 2 : 3 + (r.stats.accepted_steps > Stepper::closed_form_after ? 1 : 0);
    EXPECT_EQ(stepper.work().propagator_exponentials, expected);
  }
}

TEST(ExactLinearStepper, LinearSceneMatchesTheClosedFormModalSolution) { check_linear_scene(false); }

TEST(ExactLinearStepper, ClosedFormQuadraturesMatchTheClosedFormModalSolution) {
  check_linear_scene(true);
}

}  // namespace
}  // namespace ode_exact_linear_scene_test
