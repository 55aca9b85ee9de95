#pragma once
/// \file resonance_search.hpp
/// \brief The optimal-preload search of `blade_damper --optimise-preload`, free of the blade:
/// the resonant amplitude A(p) = max over omega of a(p, omega) (a = an orbit's amplitude), and the
/// parameter p* = argmin A(p), both by a coarse grid and a golden-section search around its best point.

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

/// The minimum of f on [a, b] without assuming one minimum over the whole range: with grid >= 3,
/// f on `grid` uniform points of [a, b] first, then golden_minimum on the two grid cells around
/// the smallest grid value (a local minimum narrower than a cell may still be missed, but not a
/// second one that the grid sees lower); grid < 3: golden_minimum on [a, b]. tol is absolute.
/// Returns the best point evaluated (grid points included) and the evaluations of both stages.
inline Extremum grid_golden_minimum(const std::function<double(double)>& f, double a, double b, double tol,
                                    int grid) {
  if (grid < 3) return golden_minimum(f, a, b, tol);
  Extremum coarse;
  coarse.value = std::numeric_limits<double>::infinity();
  double lo = a, hi = b;
  for (int k = 0; k < grid; ++k) {
    const double x = a + (b - a) * k / (grid - 1);
    const double v = f(x);
    ++coarse.evaluations;
    if (!std::isfinite(v)) {
      coarse.ok = false;
      coarse.message = "non-finite value at " + std::to_string(x);
      return coarse;
    }
    if (v < coarse.value) {
      coarse.value = v, coarse.x = x;
      lo = a + (b - a) * std::max(k - 1, 0) / (grid - 1);
      hi = a + (b - a) * std::min(k + 1, grid - 1) / (grid - 1);
    }
  }
  Extremum fine = golden_minimum(f, lo, hi, tol);
  fine.evaluations += coarse.evaluations;
  if (fine.ok && coarse.value < fine.value) fine.x = coarse.x, fine.value = coarse.value;
  return fine;
}

/// The optimum of a min-max search.
struct MinMax {
  Extremum parameter;  ///< p* and A(p*) (value = the resonant amplitude, not its negative)
  double omega = 0;    ///< the frequency of the resonant peak at p*
};

/// p* = argmin_{p in [p_lo, p_hi]} max_{omega in bracket(p)} a(p, omega), each by
/// grid_golden_minimum (to p_tol and omega_tol times the bracket's width): `grid` points of
/// [p_lo, p_hi] and `omega_grid` points of each frequency bracket before the golden sections
/// (< 3: a golden section over the whole range, which assumes one extremum there: a response
/// with two peaks can make it climb the lower one). `amplitude(p, omega)` returns a non-finite
/// value when it fails (the search stops); `bracket(p)` the frequency range that holds the
/// resonance at p; `on_peak(p, omega, A)` is called after each resonant peak found.
inline MinMax min_max_amplitude(const std::function<double(double, double)>& amplitude,
                                const std::function<std::pair<double, double>(double)>& bracket,
                                double p_lo, double p_hi, double p_tol, double omega_tol, int grid = 0,
                                const std::function<void(double, double, double)>& on_peak = {},
                                int omega_grid = 0) {
  MinMax out;
  double best_peak = std::numeric_limits<double>::infinity();
  auto resonant = [&](double p) {
    const auto [lo, hi] = bracket(p);
    const Extremum peak =
        grid_golden_minimum([&](double w) { return -amplitude(p, w); }, lo, hi, omega_tol * (hi - lo), omega_grid);
    if (!peak.ok) return std::numeric_limits<double>::quiet_NaN();
    if (on_peak) on_peak(p, peak.x, -peak.value);
    if (-peak.value < best_peak) best_peak = -peak.value, out.omega = peak.x;
    return -peak.value;
  };
  out.parameter = grid_golden_minimum(resonant, p_lo, p_hi, p_tol * (p_hi - p_lo), grid);
  if (!out.parameter.ok) out.parameter.message = "no resonant peak: " + out.parameter.message;
  return out;
}

}  // namespace blade
