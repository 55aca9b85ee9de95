#pragma once
// An independent reference for the forced Duffing oscillator
//   x'' + c x' + k x + k3 x^3 = F cos(w t)
// by Fourier collocation (harmonic balance in the time domain): the periodic orbit's samples at
// N equally spaced times solve D^2 x + c D x + k x + k3 x^3 = F cos(w t_j), D the Fourier
// differentiation matrix (spectral: exact on trigonometric polynomials of degree < N / 2). No
// time stepping, no shooting: it shares nothing with the library's orbits.

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>

namespace steady_state_test {

struct DuffingParameters {
  double c = 0, k = 1, k3 = 1, F = 1, w = 1;
};

// The Fourier differentiation matrix on N equally spaced points of a period P (Trefethen,
// Spectral Methods in MATLAB, ch. 3): D_ij = (2 pi / P) (-1)^(i-j) / 2 cot((i - j) pi / N) for
// even N, csc for odd N.
inline Eigen::MatrixXd fourier_derivative(int N, double P) {
  const double pi = 3.14159265358979323846;
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(N, N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      if (i == j) continue;
      const double a = (i - j) * pi / N, sign = ((i - j) % 2 == 0) ? 1.0 : -1.0;
      D(i, j) = 0.5 * sign * (N % 2 == 0 ? std::cos(a) / std::sin(a) : 1.0 / std::sin(a));
    }
  return D * (2 * pi / P);
}

// The period-T orbit's samples x(j T / N), j = 0 .. N - 1, by Newton on the collocation equations
// from `x` (a guess, overwritten). Returns the final max residual.
inline double duffing_collocation(const DuffingParameters& p, int N, Eigen::VectorXd& x) {
  const double pi = 3.14159265358979323846, T = 2 * pi / p.w;
  const Eigen::MatrixXd D = fourier_derivative(N, T), D2 = D * D;
  Eigen::VectorXd force(N);
  for (int j = 0; j < N; ++j) force[j] = p.F * std::cos(p.w * j * T / N);
  double res = 0;
  for (int it = 0; it < 60; ++it) {
    const Eigen::VectorXd R =
        D2 * x + p.c * (D * x) + p.k * x + p.k3 * x.array().cube().matrix() - force;
    res = R.cwiseAbs().maxCoeff();
    if (res < 1e-12) break;
    Eigen::MatrixXd J = D2 + p.c * D;
    J.diagonal().array() += p.k + 3 * p.k3 * x.array().square();
    x -= J.partialPivLu().solve(R);
  }
  return res;
}

// Mean and the cos/sin coefficients of harmonics 1 .. H of a trigonometric polynomial from its N
// samples over the period (exact for H < N / 2).
struct Fourier {
  double mean = 0;
  Eigen::VectorXd a, b;  // x(t) = mean + sum a_h cos(h w t) + b_h sin(h w t)
  double at(double phase) const {  // x at w t = phase
    double v = mean;
    for (Eigen::Index h = 0; h < a.size(); ++h)
      v += a[h] * std::cos(static_cast<double>(h + 1) * phase) + b[h] * std::sin(static_cast<double>(h + 1) * phase);
    return v;
  }
};
inline Fourier fourier(const Eigen::VectorXd& x, int H) {
  const double pi = 3.14159265358979323846;
  const Eigen::Index n = x.size();
  const double N = static_cast<double>(n);
  Fourier f;
  f.mean = x.mean();
  f.a.setZero(H);
  f.b.setZero(H);
  for (int h = 1; h <= H; ++h)
    for (Eigen::Index j = 0; j < n; ++j) {
      const double phase = 2 * pi * h * static_cast<double>(j) / N;
      f.a[h - 1] += 2.0 / N * x[j] * std::cos(phase);
      f.b[h - 1] += 2.0 / N * x[j] * std::sin(phase);
    }
  return f;
}

}  // namespace steady_state_test
