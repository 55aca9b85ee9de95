#pragma once
/// \file blade_regime.hpp
/// \brief The example's one regime rule (names, thresholds, a run's regime) and the choice of
/// one representative preload per regime from a preload sweep. The thresholds are the library's
/// (stickslip/model/damper_statistics.hpp, classify_regime); the console, CSV/JSON records,
/// folder names, plots (plot.py reads the names from sweep.json) and docs/blade_damper.md all
/// follow it.

#include <stickslip/model/damper_statistics.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace blade {

/// The paper's three regimes (section 3.3), in the order of increasing preload, and the
/// intermittent contact of dampers that leave the platform (--restitution; not a paper regime,
/// not in kRegimes).
enum class Regime { GrossSlip, StickSlip, Stick, IntermittentContact };

/// All regimes, in the order of increasing preload.
inline constexpr std::array<Regime, 3> kRegimes{Regime::GrossSlip, Regime::StickSlip, Regime::Stick};

/// A damper in gross slip is stuck for less than this fraction of the record window.
inline constexpr double kGrossSlipBelow = stickslip::regime_gross_slip_below;
/// A damper sticks when stuck for at least this fraction of the record window.
inline constexpr double kStickFrom = stickslip::regime_stick_from;
/// A damper separated (in flight) for at least this fraction of the window is in intermittent contact.
inline constexpr double kIntermittentFrom = stickslip::regime_intermittent_from;

/// The regime's name everywhere (console, records, plots, docs).
inline const char* to_string(Regime r) {
  switch (r) {
    case Regime::GrossSlip: return "gross slip";
    case Regime::StickSlip: return "stick-slip";
    case Regime::Stick: return "stick";
    case Regime::IntermittentContact: return "intermittent contact";
  }
  return "?";
}

/// The folder of the regime's representative run: "regime_" and the name with '_' for ' ' and '-'
/// ("regime_gross_slip", "regime_stick_slip", "regime_stick").
inline std::string regime_folder(Regime r) {
  std::string s = std::string("regime_") + to_string(r);
  for (char& c : s)
    if (c == ' ' || c == '-') c = '_';
  return s;
}

/// The rule as one sentence, printed by the demo and written in sweep.json.
inline const char* regime_rule_text() {
  return "a damper's regime over the last record window from its stick fraction s (fraction of samples "
         "stuck): gross slip if s < 0.05, stick if s >= 0.999, stick-slip otherwise, unless it was separated "
         "from the platform (--restitution) for at least 0.01 of the samples: intermittent contact; a run's regime is "
         "its dampers' common regime (none when they differ or the run stopped)";
}

/// THE regime rule of one damper, from its stick fraction s over the record window:
/// gross slip if s < kGrossSlipBelow (at most brief stops at velocity reversals),
/// stick if s >= kStickFrom, stick-slip otherwise. Throws std::invalid_argument unless 0 <= s <= 1.
inline Regime damper_regime(double stick_fraction) {
  if (!(stick_fraction >= 0 && stick_fraction <= 1))
    throw std::invalid_argument("damper_regime: stick_fraction must be in [0, 1], got " +
                                std::to_string(stick_fraction));
  if (stick_fraction < kGrossSlipBelow) return Regime::GrossSlip;
  if (stick_fraction >= kStickFrom) return Regime::Stick;
  return Regime::StickSlip;
}

/// The rule with separation: intermittent contact when the damper was separated for at least
/// kIntermittentFrom of the window (separated_fraction), else damper_regime(stick_fraction).
/// Throws std::invalid_argument unless both fractions are in [0, 1].
inline Regime damper_regime(double stick_fraction, double separated_fraction) {
  if (!(separated_fraction >= 0 && separated_fraction <= 1))
    throw std::invalid_argument("damper_regime: separated_fraction must be in [0, 1], got " +
                                std::to_string(separated_fraction));
  const Regime by_stick = damper_regime(stick_fraction);
  return separated_fraction >= kIntermittentFrom ? Regime::IntermittentContact : by_stick;
}

/// A run's regime: the regime both dampers share; none when they differ or one is unknown
/// (the run stopped before the record window).
inline std::optional<Regime> common_regime(std::optional<Regime> a, std::optional<Regime> b) {
  if (a && b && *a == *b) return a;
  return std::nullopt;
}

/// One representative preload of a regime found in a sweep, and where it came from.
struct Representative {
  Regime regime = Regime::Stick;
  std::size_t index = 0;                      ///< the chosen sweep point
  double preload = 0;                         ///< its preload [N]
  std::size_t band_first = 0, band_last = 0;  ///< the band it was chosen from (sweep indices)
  std::size_t points = 0;                     ///< sweep points with this regime, all bands together
  std::size_t bands = 0;                      ///< bands of this regime in the sweep
};

/// Text of the choice rule, printed by the demo and written in sweep.json.
inline const char* representative_rule_text() {
  return "per regime found in the sweep: its widest band (most consecutive sweep points with that "
         "regime; the lower-preload band on a tie), and in it the median point (the lower of the two "
         "middle points for an even count), i.e. the point deepest inside the band on the sweep's grid";
}

/// One representative per regime found in a sweep (ordered by kRegimes). `preloads` must be
/// increasing; `regimes[k]` is the run regime of sweep point k (none: mixed, stopped).
/// A band is a maximal run of consecutive sweep points with the same regime; the chosen point is
/// the median of the widest band (the lower-preload band on a tie; the lower middle point for an
/// even count), i.e. the point farthest, in sweep points, from the band's edges.
/// Throws std::invalid_argument when the sizes differ or the preloads do not increase.
inline std::vector<Representative> choose_representatives(const std::vector<double>& preloads,
                                                          const std::vector<std::optional<Regime>>& regimes) {
  if (preloads.size() != regimes.size())
    throw std::invalid_argument("choose_representatives: preloads and regimes must have the same size");
  for (std::size_t k = 1; k < preloads.size(); ++k)
    if (!(preloads[k] > preloads[k - 1]))
      throw std::invalid_argument("choose_representatives: preloads must increase");
  std::vector<Representative> chosen;
  for (Regime regime : kRegimes) {
    Representative best;
    best.regime = regime;
    std::size_t widest = 0;
    for (std::size_t k = 0; k < regimes.size();) {
      if (regimes[k] != regime) {
        ++k;
        continue;
      }
      std::size_t last = k;
      while (last + 1 < regimes.size() && regimes[last + 1] == regime) ++last;
      const std::size_t width = last - k + 1;
      ++best.bands;
      best.points += width;
      if (width > widest) {
        widest = width;
        best.band_first = k;
        best.band_last = last;
        best.index = k + (width - 1) / 2;
      }
      k = last + 1;
    }
    if (widest == 0) continue;
    best.preload = preloads[best.index];
    chosen.push_back(best);
  }
  return chosen;
}

}  // namespace blade
