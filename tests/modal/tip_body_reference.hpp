#pragma once
// Independent reference: frequencies of a uniform Euler-Bernoulli cantilever (clamped at x = 0)
// carrying a tip body of mass M and rotary inertia J at x = L, from the 2x2 boundary-condition
// determinant of W = C1 cos bx + C2 sin bx + C3 cosh bx + C4 sinh bx (W(0) = W'(0) = 0,
// EI W''(L) = J w^2 W'(L), -EI W'''(L) = M w^2 W(L)). With mu = M/(rho A L), j = J/(rho A L^3)
// and b = beta L the roots give w = b^2 sqrt(EI/(rho A L^4)); mu = j = 0 gives 1 + cos b cosh b = 0.

#include <cmath>
#include <stdexcept>

namespace stickslip_test {

inline double tip_body_determinant(double b, double mu, double j) {
  const double c = std::cos(b), s = std::sin(b), ch = std::cosh(b), sh = std::sinh(b);
  const double j3 = j * b * b * b, mb = mu * b;
  const double r11 = ch + c - j3 * (sh + s), r12 = sh + s - j3 * (ch - c);
  const double r21 = sh - s + mb * (ch - c), r22 = ch + c + mb * (sh - s);
  return r11 * r22 - r12 * r21;
}

/// The k-th (0-based) root b = beta L of the determinant, by scanning and bisection.
inline double tip_body_root(int k, double mu, double j) {
  double lo = 1e-3, f_lo = tip_body_determinant(lo, mu, j);
  int found = -1;
  for (double hi = lo + 1e-3; hi < 40.0; hi += 1e-3) {
    const double f_hi = tip_body_determinant(hi, mu, j);
    if ((f_lo < 0) != (f_hi < 0) && ++found == k) {
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi), f_mid = tip_body_determinant(mid, mu, j);
        if ((f_mid < 0) == (f_lo < 0)) { lo = mid; f_lo = f_mid; } else { hi = mid; }
      }
      return 0.5 * (lo + hi);
    }
    lo = hi;
    f_lo = f_hi;
  }
  throw std::runtime_error("tip_body_root: root not found");
}

}  // namespace stickslip_test
