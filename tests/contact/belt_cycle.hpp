#pragma once
// The closed-form stick-slip limit cycle of a mass on a spring dragged by a belt (mu_s > mu_k),
// shared by the contact and ode tests; derivation in tests/contact/coulomb_contact_belt_test.cpp.

#include <cmath>

namespace contact_test {

inline constexpr double kBeltPi = 3.14159265358979323846;

struct BeltCase {
  double mu_s, mu_k, belt_speed;
};

struct BeltCycle {
  double x_k, d, A, t_slip, t_stick;
  BeltCycle(double m, double k, double N, const BeltCase& c) {
    const double w = std::sqrt(k / m);
    x_k = c.mu_k * N / k;
    d = (c.mu_s - c.mu_k) * N / k;
    A = std::sqrt(d * d + std::pow(c.belt_speed / w, 2));
    t_slip = (kBeltPi + 2 * std::atan(c.belt_speed / (w * d))) / w;
    t_stick = 2 * d / c.belt_speed;
  }
};

}  // namespace contact_test
