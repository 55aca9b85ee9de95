#pragma once
// Den Hartog's steady orbit of a harmonically forced oscillator with Coulomb friction and
// continuous sliding (two stops per period, no stick): the closed form shared by the contact and
// ode tests.
//
// Reference: J. P. Den Hartog, "Forced vibrations with combined Coulomb and viscous friction",
// Trans. ASME APM-53-9 (1931) 107-115; derived independently from the piecewise-linear ODE below.

#include <cmath>

namespace contact_test {

inline constexpr double kDenHartogPi = 3.14159265358979323846;

// m x'' + k x = F0 cos(w t) - mu_k N sgn(x'). Symmetric orbit x(t + T/2) = -x(t) with one
// positive half-period [t1, t1 + pi/w] where x' >= 0, x(t1) = -X, x'(t1) = 0, x(t1 + pi/w) = X.
// With tau = t - t1, theta = w t1, beta = w/wn, P = F0/(k (1 - beta^2)), a = mu_k N / k:
//   x(tau) = C cos(wn tau) + D sin(wn tau) + P cos(w tau + theta) - a
// x'(0) = 0 gives D = P beta sin(theta); x(0) = -X gives C = -X - P cos(theta) + a. The two end
// conditions x(pi/w) = X, x'(pi/w) = 0 reduce (with c = cos(pi/beta), s = sin(pi/beta),
// (1+c)^2 + s^2 = 2(1+c)) to
//   sin(theta) = (a / P) U,   X = -P cos(theta),   U = s / (beta (1 + c)) = tan(pi/(2 beta))/beta,
// i.e. X^2 = P^2 - a^2 U^2: Den Hartog's X/(F0/k) = sqrt(1/(1-beta^2)^2 - (mu_k N/F0)^2 U^2).
// The displacement peak (x = X) lags the force peak by phi = theta + pi (mod 2 pi).
struct DenHartogOrbit {
  double m, k, F0, w, a, muS_N;
  double wn, beta, P, X, theta, C, D, t1, T;
  bool valid = false;

  DenHartogOrbit(double mass, double stiffness, double force, double omega, double mu_k_N,
                 double mu_s_N)
      : m(mass), k(stiffness), F0(force), w(omega), a(mu_k_N / stiffness), muS_N(mu_s_N) {
    wn = std::sqrt(k / m);
    beta = w / wn;
    P = F0 / (k * (1 - beta * beta));
    const double U = std::tan(kDenHartogPi / (2 * beta)) / beta;
    const double sin_theta = a * U / P;
    if (std::abs(sin_theta) >= 1) return;
    const double cos_theta = (P > 0 ? -1.0 : 1.0) * std::sqrt(1 - sin_theta * sin_theta);
    theta = std::atan2(sin_theta, cos_theta);
    X = -P * cos_theta;
    C = -X - P * cos_theta + a;
    D = P * beta * sin_theta;
    T = 2 * kDenHartogPi / w;
    t1 = std::fmod(theta / w + 2 * T, T);  // w tau + theta = w t
    valid = check();
  }
  double x_half(double tau) const {
    return C * std::cos(wn * tau) + D * std::sin(wn * tau) + P * std::cos(w * tau + theta) - a;
  }
  double v_half(double tau) const {
    return wn * (-C * std::sin(wn * tau) + D * std::cos(wn * tau)) -
           P * w * std::sin(w * tau + theta);
  }
  // Position and velocity at time t (any t), by the half-period symmetry.
  void state(double t, double& x, double& v) const {
    double tau = std::fmod(t - t1, T);
    if (tau < 0) tau += T;
    const double sign = tau < T / 2 ? 1.0 : -1.0;
    if (tau >= T / 2) tau -= T / 2;
    x = sign * x_half(tau);
    v = sign * v_half(tau);
  }
  double phase_lag() const {
    return std::fmod(theta + kDenHartogPi + 4 * kDenHartogPi, 2 * kDenHartogPi);
  }

  // The orbit is the physical one only if x' > 0 inside the half period (no extra stop) and the
  // body cannot stick at the reversal: |k X - F(t1 + T/2)| > mu_s N.
  bool check() const {
    const int n = 4000;
    for (int i = 1; i < n; ++i)
      if (!(v_half(kDenHartogPi / w * i / n) > 0)) return false;
    const double f_required_at_peak = k * X - F0 * std::cos(w * (t1 + T / 2));
    return X > 0 && std::abs(f_required_at_peak) > muS_N;
  }
};

}  // namespace contact_test
