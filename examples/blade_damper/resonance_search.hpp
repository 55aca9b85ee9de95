#pragma once
/// \file resonance_search.hpp
/// \brief The optimal-preload search of `blade_damper --optimise-preload`, free of the blade:
/// the resonant amplitude A(p) = max over omega of a(p, omega) (a = an orbit's amplitude), and the
/// parameter p* = argmin A(p), both by golden-section search on unimodal functions.

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>

namespace blade {

/// An extremum found by golden_minimum.
struct Extremum {
  double x = 0;          ///< the abscissa
  double value = 0;      ///< f(x)
  int evaluations = 0;   ///< calls of f
  bool ok = true;        ///< false when f returned a non-finite value (message says where)
  std::string message;   ///< why it failed
};

/// Golden-section search for the minimum of f on [a, b], assumed unimodal, until the bracket is
/// shorter than tol: each step keeps the sub-bracket around the smaller of two interior values
/// (ratio 0.618 per evaluation). Returns the best point evaluated. A non-finite f(x) ends the
/// search (ok = false).
inline Extremum golden_minimum(const std::function<double(double)>& f, double a, double b, double tol) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  Extremum best;
  best.value = std::numeric_limits<double>::infinity();
  auto eval = [&](double x) {
    const double v = f(x);
    ++best.evaluations;
    if (!std::isfinite(v) && best.ok) {
      best.ok = false;
      best.message = "non-finite value at " + std::to_string(x);
    }
    if (v < best.value) best.x = x, best.value = v;
    return v;
  };
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = eval(c), fd = eval(d);
  while (best.ok && b - a > tol) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a);
      fc = eval(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a);
      fd = eval(d);
    }
  }
  return best;
}

/// The optimum of a min-max search.
struct MinMax {
  Extremum parameter;  ///< p* and A(p*) (value = the resonant amplitude, not its negative)
  double omega = 0;    ///< the frequency of the resonant peak at p*
};

/// p* = argmin_{p in [p_lo, p_hi]} max_{omega in bracket(p)} a(p, omega), golden sections in
/// both (to p_tol and omega_tol times the bracket's width). With grid >= 3 the resonant
/// amplitude is first evaluated on `grid` uniform points of [p_lo, p_hi] and the golden section
/// runs on the two cells around the smallest (a guard against a function that is not unimodal
/// over the whole range). `amplitude(p, omega)` returns a non-finite value when it fails (the
/// search stops); `bracket(p)` the frequency range that holds the resonance at p;
/// `on_peak(p, omega, A)` is called after each resonant peak found.
inline MinMax min_max_amplitude(const std::function<double(double, double)>& amplitude,
                                const std::function<std::pair<double, double>(double)>& bracket,
                                double p_lo, double p_hi, double p_tol, double omega_tol, int grid = 0,
                                const std::function<void(double, double, double)>& on_peak = {}) {
  MinMax out;
  double best_peak = std::numeric_limits<double>::infinity();
  auto resonant = [&](double p) {
    const auto [lo, hi] = bracket(p);
    const Extremum peak = golden_minimum([&](double w) { return -amplitude(p, w); }, lo, hi, omega_tol * (hi - lo));
    if (!peak.ok) return std::numeric_limits<double>::quiet_NaN();
    if (on_peak) on_peak(p, peak.x, -peak.value);
    if (-peak.value < best_peak) best_peak = -peak.value, out.omega = peak.x;
    return -peak.value;
  };
  double a = p_lo, b = p_hi;
  Extremum coarse;
  coarse.value = std::numeric_limits<double>::infinity();
  for (int k = 0; grid >= 3 && k < grid; ++k) {
    const double p = p_lo + (p_hi - p_lo) * k / (grid - 1);
    const double v = resonant(p);
    ++coarse.evaluations;
    if (!std::isfinite(v)) {
      out.parameter = coarse;
      out.parameter.ok = false;
      out.parameter.message = "no resonant peak at " + std::to_string(p);
      return out;
    }
    if (v < coarse.value) {
      coarse.value = v, coarse.x = p;
      a = p_lo + (p_hi - p_lo) * std::max(k - 1, 0) / (grid - 1);
      b = p_lo + (p_hi - p_lo) * std::min(k + 1, grid - 1) / (grid - 1);
    }
  }
  out.parameter = golden_minimum(resonant, a, b, p_tol * (p_hi - p_lo));
  out.parameter.evaluations += coarse.evaluations;
  if (out.parameter.ok && coarse.value < out.parameter.value) out.parameter.x = coarse.x, out.parameter.value = coarse.value;
  return out;
}

}  // namespace blade
