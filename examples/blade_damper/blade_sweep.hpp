#pragma once
/// \file blade_sweep.hpp
/// \brief The preload sweep of the blade example as work items of the library's sweep runner
/// (stickslip/sweep.hpp): one row of sweep.csv per preload, and sweep.csv / the head of
/// sweep.json from the rows, so that blade_damper (threads) and blade_sweep_mpi (MPI ranks)
/// write the same files.

#include "blade_regime.hpp"
#include "blade_run.hpp"
#include "blade_scene.hpp"

#include <stickslip/sweep.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace blade {

/// A number as the example writes it (%.10g).
inline std::string fmt(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}
/// A JSON number (null when not finite, e.g. E of a run that stopped before its window).
inline std::string jnum(double v) { return std::isfinite(v) ? fmt(v) : "null"; }

/// The example's run settings: DOPRI rtol 1e-7, atol 1e-10, events located to 1e-12 s.
inline RunSettings default_settings() {
  RunSettings s;
  s.run.stepper.rtol = 1e-7;
  s.run.stepper.atol = 1e-10;
  s.run.stepper.event_time_tolerance = 1e-12;
  return s;
}

/// `s` for a run of this duration: the last second recorded, E over the paper's window
/// [19, 19.5] s (or [T - 1, T - 0.5] for shorter runs).
inline RunSettings settings_for_duration(RunSettings s, double duration) {
  s.duration = duration;
  s.record_window = std::min(1.0, duration);
  s.energy_t1 = 19.0;
  s.energy_t2 = 19.5;
  s.fit_energy_window();
  return s;
}

/// `text` as a number (all of it: "2x" is not 2); throws std::invalid_argument naming `what`
/// (e.g. the option) otherwise.
inline double parse_number(const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    throw std::invalid_argument(what + " expects a number, got '" + text + "'");
  return v;
}

/// `text` as an integer in [lo, hi] (all of it); throws std::invalid_argument naming `what` and
/// saying `why` the range is what it is otherwise.
inline long long parse_integer(const std::string& text, const std::string& what, long long lo, long long hi,
                               const std::string& why) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || v < lo || v > hi)
    throw std::invalid_argument(what + " expects an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                "]" + (why.empty() ? "" : " (" + why + ")") + ", got '" + text + "'");
  return v;
}

/// "a,b,c" as numbers; throws std::invalid_argument naming `what` and the bad item.
inline std::vector<double> parse_list(const std::string& s, const std::string& what = "the list a,b,...") {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    v.push_back(parse_number(item, what + " (item " + std::to_string(v.size() + 1) + ")"));
  if (v.empty()) throw std::invalid_argument(what + " expects numbers a,b,..., got '" + s + "'");
  return v;
}

/// The largest sweep (--sweep's count): each preload is a run of the sweep's duration.
constexpr long long kMaxSweepCount = 100000;

/// The value after option argv[i] (advancing i to it); throws std::invalid_argument when it is missing.
inline std::string next_argument(int argc, char** argv, int& i) {
  if (i + 1 >= argc) throw std::invalid_argument(std::string("missing value after ") + argv[i]);
  return argv[++i];
}

/// --sweep's "lo:hi:count" into lo, hi, count. Throws std::invalid_argument naming --sweep
/// unless lo and hi are finite numbers with 0 < lo < hi and count an integer in
/// [2, kMaxSweepCount].
inline void parse_sweep_range(const std::string& s, double& lo, double& hi, int& count) {
  const std::string expects = "--sweep expects lo:hi:count with finite 0 < lo < hi and 2 <= count <= " +
                              std::to_string(kMaxSweepCount) + ", got '" + s + "'";
  const std::size_t a = s.find(':'), b = a == std::string::npos ? a : s.find(':', a + 1);
  if (b == std::string::npos) throw std::invalid_argument(expects);
  try {
    lo = parse_number(s.substr(0, a), "--sweep");
    hi = parse_number(s.substr(a + 1, b - a - 1), "--sweep");
    count = static_cast<int>(
        parse_integer(s.substr(b + 1), "--sweep", 2, kMaxSweepCount, "each preload is a run"));
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(expects);
  }
  if (!(lo > 0) || !(hi > lo) || !std::isfinite(hi)) throw std::invalid_argument(expects);
}

/// count preloads from lo to hi, log-spaced (or linearly).
inline std::vector<double> sweep_preloads(double lo, double hi, int count, bool log_spaced) {
  std::vector<double> preloads(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const double s = double(k) / double(count - 1);
    preloads[static_cast<std::size_t>(k)] = log_spaced ? lo * std::pow(hi / lo, s) : lo + (hi - lo) * s;
  }
  return preloads;
}

/// Key column of sweep.csv (written for failed items too).
inline const char* kSweepKeyHeader = "preload_N";
/// The other columns of sweep.csv (then `error`, stickslip::write_sweep_csv).
inline const char* kSweepHeader =
    "energy_density_m2,regime,stick_fraction_1,stick_fraction_2,transitions_per_period_1,"
    "transitions_per_period_2,tip_max_m,status,cpu_seconds,rhs_evaluations,events";

/// The row of one run after its preload (kSweepHeader's columns).
inline std::string sweep_row(const RunRecord& r) {
  std::ostringstream o;
  o << fmt(r.energy_density) << ',' << r.overall_regime << ',' << fmt(r.regime[0].stick_fraction) << ','
    << fmt(r.regime[1].stick_fraction) << ',' << fmt(r.regime[0].transitions_per_period) << ','
    << fmt(r.regime[1].transitions_per_period) << ',' << fmt(r.tip_max) << ',' << stickslip::to_string(r.status)
    << ',' << fmt(r.cpu_seconds) << ',' << r.stats.rhs_evaluations << ',' << r.total_events;
  return o.str();
}

/// The sweep's work item: the scene of `base` at this preload run with `settings`, as a row.
/// Throws std::invalid_argument naming the preload unless it is finite and > 0 (the damper mass
/// is N0 / (share r Omega^2)).
inline std::string sweep_item(const BladeParameters& base, const RunSettings& settings, double preload) {
  if (!(preload > 0) || !std::isfinite(preload))
    throw std::invalid_argument("preload_N = " + fmt(preload) +
                                ": a preload must be finite and > 0 (the damper mass is N0 / (share r Omega^2))");
  BladeParameters p = base;
  p.preload = preload;
  BladeScene scene = make_blade_scene(p);
  return sweep_row(run_scene(scene, settings));
}

/// Cell `index` (0-based) of a row of kSweepHeader's columns.
inline std::string row_cell(const std::string& row, int index) {
  std::istringstream cells(row);
  std::string cell;
  for (int k = 0; k <= index; ++k) std::getline(cells, cell, ',');
  return cell;
}

/// What the regime map and the representatives need of one sweep row.
struct SweepPoint {
  double preload = 0;
  double energy_density = std::numeric_limits<double>::quiet_NaN();  ///< as written (10 digits)
  std::string regime;           ///< the row's regime text ("error" for a failed item)
  std::optional<Regime> common;  ///< the regime, when it is one of kRegimes
};

/// Sweep points from the rows (their first two cells: E and the regime).
inline std::vector<SweepPoint> sweep_points(const std::vector<double>& preloads,
                                            const std::vector<stickslip::SweepOutcome>& outcomes) {
  std::vector<SweepPoint> points(preloads.size());
  for (std::size_t k = 0; k < preloads.size(); ++k) {
    SweepPoint& p = points[k];
    p.preload = preloads[k];
    if (!outcomes[k].ok) {
      p.regime = "error";
      continue;
    }
    p.energy_density = std::strtod(row_cell(outcomes[k].row, 0).c_str(), nullptr);  // "nan" parses as NaN
    p.regime = row_cell(outcomes[k].row, 1);
    for (Regime r : kRegimes)
      if (p.regime == to_string(r)) p.common = r;
  }
  return points;
}

/// Writes OUT/sweep.csv and the head of sweep.json (duration, optimum, regime map, the regime
/// names and rules) up to the open `"representatives": [`, printing the optimum and the map.
inline void write_sweep_files(const std::string& out, double duration, const std::vector<double>& preloads,
                              const std::vector<stickslip::SweepOutcome>& outcomes, std::ostream& j) {
  {
    std::ofstream csv(out + "/sweep.csv");
    stickslip::write_sweep_csv(csv, kSweepKeyHeader, [&](std::size_t k) { return fmt(preloads[k]); }, kSweepHeader,
                               outcomes);
  }
  const std::vector<SweepPoint> points = sweep_points(preloads, outcomes);
  // The optimum: the least finite E (none when no run has one: every item failed, or no run
  // reached its energy window).
  std::optional<std::size_t> best;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (std::isfinite(points[k].energy_density) &&
        (!best || points[k].energy_density < points[*best].energy_density))
      best = k;
  j << "{\n  \"duration_s\": " << jnum(duration) << ",\n  \"optimum\": ";
  if (best) {
    const SweepPoint& b = points[*best];
    j << "{\"preload_N\": " << jnum(b.preload) << ", \"energy_density_m2\": " << jnum(b.energy_density)
      << ", \"regime\": \"" << b.regime << "\"}";
    std::printf("sweep optimum: N0 = %.2f N, E = %.4e m^2 (%s)\n", b.preload, b.energy_density, b.regime.c_str());
  } else {
    j << "null";
    std::printf("sweep optimum: none (no run has a finite E)\n");
  }
  j << ",\n  \"regime_map\": [";
  std::printf("regime map:\n");
  // Regime map: contiguous preload ranges with the same regime.
  std::size_t start = 0;
  for (std::size_t k = 1; k <= points.size(); ++k) {
    if (k == points.size() || points[k].regime != points[start].regime) {
      j << (start ? ", " : "") << "{\"regime\": \"" << points[start].regime << "\", \"from_N\": "
        << jnum(points[start].preload) << ", \"to_N\": " << jnum(points[k - 1].preload) << "}";
      std::printf("  %6.2f .. %6.2f N: %s\n", points[start].preload, points[k - 1].preload,
                  points[start].regime.c_str());
      start = k;
    }
  }
  j << "],\n  \"regimes\": [";
  for (std::size_t k = 0; k < kRegimes.size(); ++k)
    j << (k ? ", " : "") << "{\"name\": \"" << to_string(kRegimes[k]) << "\", \"folder\": \""
      << regime_folder(kRegimes[k]) << "\"}";
  j << "],\n  \"regime_rule\": \"" << regime_rule_text() << "\",\n  \"representative_rule\": \""
    << representative_rule_text() << "\",\n  \"representatives\": [";
}

/// The sweep's progress line, "\r<what>: k/n preloads done (last N0 = ... N: <regime>)".
inline void print_sweep_progress(const char* what, std::size_t done, std::size_t count, double preload,
                                 const stickslip::SweepOutcome& o) {
  const std::string regime = o.ok ? row_cell(o.row, 1) : "error: " + o.error;
  std::printf("\r%s: %zu/%zu preloads done (last N0 = %.2f N: %s)        ", what, done, count, preload,
              regime.c_str());
  if (done == count) std::printf("\n");
  std::fflush(stdout);
}

}  // namespace blade
