// The blade_damper example's regime rule and its choice of one representative preload per regime
// (examples/blade_damper/blade_regime.hpp). The references are the rule as docs/blade_damper.md
// states it and sweeps whose bands are counted by hand; the randomised test checks the choice
// against the definition (widest maximal band, median point) by brute force.
#include "blade_damper/blade_regime.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace blade_regime_test {

using blade::Regime;
using Sweep = std::vector<std::optional<Regime>>;
constexpr auto G = Regime::GrossSlip;
constexpr auto SS = Regime::StickSlip;
constexpr auto S = Regime::Stick;
const std::optional<Regime> none = std::nullopt;

/// Log-spaced preloads like the demo's sweep (0.5 .. 40 N); the choice only needs them increasing.
std::vector<double> preloads_for(std::size_t n) {
  std::vector<double> p(n);
  for (std::size_t k = 0; k < n; ++k) p[k] = 0.5 * std::pow(80.0, n > 1 ? double(k) / double(n - 1) : 0.0);
  return p;
}

TEST(BladeRegime, DamperRegimeFollowsTheDocumentedThresholds) {
  // docs/blade_damper.md: gross slip when stuck less than 5 % of the window, stick from 99.9 %.
  EXPECT_EQ(blade::damper_regime(0.0), G);
  EXPECT_EQ(blade::damper_regime(0.0499), G);
  EXPECT_EQ(blade::damper_regime(0.05), SS);
  EXPECT_EQ(blade::damper_regime(0.78), SS);
  EXPECT_EQ(blade::damper_regime(0.9989), SS);
  EXPECT_EQ(blade::damper_regime(0.999), S);
  EXPECT_EQ(blade::damper_regime(1.0), S);
}

TEST(BladeRegime, DamperRegimeRejectsFractionsOutsideTheUnitInterval) {
  for (double s : {-1e-9, 1.0 + 1e-9, std::numeric_limits<double>::quiet_NaN()}) {
    try {
      (void)blade::damper_regime(s);
      ADD_FAILURE() << "no exception for stick_fraction = " << s;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("stick_fraction"), std::string::npos) << e.what();
    }
  }
}

TEST(BladeRegime, NamesAndFoldersAreDistinctAndOrderedByPreload) {
  ASSERT_EQ(blade::kRegimes.size(), 3u);
  EXPECT_EQ(blade::kRegimes[0], G);
  EXPECT_EQ(blade::kRegimes[1], SS);
  EXPECT_EQ(blade::kRegimes[2], S);
  EXPECT_STREQ(blade::to_string(G), "gross slip");
  EXPECT_STREQ(blade::to_string(SS), "stick-slip");
  EXPECT_STREQ(blade::to_string(S), "stick");
  EXPECT_EQ(blade::regime_folder(G), "regime_gross_slip");
  EXPECT_EQ(blade::regime_folder(SS), "regime_stick_slip");
  EXPECT_EQ(blade::regime_folder(S), "regime_stick");
}

TEST(BladeRegime, CommonRegimeOnlyWhenBothDampersAgree) {
  EXPECT_EQ(blade::common_regime(SS, SS), SS);
  EXPECT_EQ(blade::common_regime(G, SS), none);
  EXPECT_EQ(blade::common_regime(S, none), none);
  EXPECT_EQ(blade::common_regime(none, none), none);
}

TEST(BladeRegime, ChoosesTheMedianOfEachRegimesBand) {
  // Shaped like the demo's sweep: stopped runs, gross slip, one stick-slip point, a long stick band.
  //                index:  0     1     2  3  4  5  6   7  8  9  10 11 12
  const Sweep regimes{none, none, G, G, G, G, SS, S, S, S, S, S, S};
  const auto p = preloads_for(regimes.size());
  const auto chosen = blade::choose_representatives(p, regimes);
  ASSERT_EQ(chosen.size(), 3u);
  // Gross slip: band 2..5 (4 points), middle points 3 and 4, the lower one.
  EXPECT_EQ(chosen[0].regime, G);
  EXPECT_EQ(chosen[0].index, 3u);
  EXPECT_EQ(chosen[0].preload, p[3]);
  EXPECT_EQ(chosen[0].band_first, 2u);
  EXPECT_EQ(chosen[0].band_last, 5u);
  // Stick-slip: the single point 6.
  EXPECT_EQ(chosen[1].regime, SS);
  EXPECT_EQ(chosen[1].index, 6u);
  EXPECT_EQ(chosen[1].band_first, 6u);
  EXPECT_EQ(chosen[1].band_last, 6u);
  // Stick: band 7..12 (6 points), middle points 9 and 10, the lower one.
  EXPECT_EQ(chosen[2].regime, S);
  EXPECT_EQ(chosen[2].index, 9u);
  EXPECT_EQ(chosen[2].points, 6u);
  EXPECT_EQ(chosen[2].bands, 1u);
}

TEST(BladeRegime, TakesTheWidestBandAndTheLowerOneOnATie) {
  // Stick in two bands, 0..1 and 3..5 (mixed regime at 2): the wider, median 4.
  const Sweep two_bands{S, S, none, S, S, S};
  auto chosen = blade::choose_representatives(preloads_for(two_bands.size()), two_bands);
  ASSERT_EQ(chosen.size(), 1u);
  EXPECT_EQ(chosen[0].index, 4u);
  EXPECT_EQ(chosen[0].bands, 2u);
  EXPECT_EQ(chosen[0].points, 5u);
  // Gross slip in 0..1 and 3..4, equally wide: the lower-preload band, its lower middle point 0.
  const Sweep tie{G, G, SS, G, G};
  chosen = blade::choose_representatives(preloads_for(tie.size()), tie);
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_EQ(chosen[0].regime, G);
  EXPECT_EQ(chosen[0].index, 0u);
  EXPECT_EQ(chosen[0].band_last, 1u);
  EXPECT_EQ(chosen[1].regime, SS);
  EXPECT_EQ(chosen[1].index, 2u);
}

TEST(BladeRegime, RegimesAbsentFromTheSweepAreNotChosen) {
  EXPECT_TRUE(blade::choose_representatives({}, {}).empty());
  const Sweep stopped{none, none, none};
  EXPECT_TRUE(blade::choose_representatives(preloads_for(3), stopped).empty());
  const Sweep only_stick{none, S, S, S, S, S};  // odd band 1..5: its middle point 3
  const auto chosen = blade::choose_representatives(preloads_for(only_stick.size()), only_stick);
  ASSERT_EQ(chosen.size(), 1u);
  EXPECT_EQ(chosen[0].regime, S);
  EXPECT_EQ(chosen[0].index, 3u);
}

TEST(BladeRegime, ChoiceRejectsMismatchedOrUnsortedSweeps) {
  EXPECT_THROW(blade::choose_representatives({1.0, 2.0}, Sweep{S}), std::invalid_argument);
  EXPECT_THROW(blade::choose_representatives({1.0, 1.0}, Sweep{S, S}), std::invalid_argument);
  EXPECT_THROW(blade::choose_representatives({2.0, 1.0}, Sweep{S, S}), std::invalid_argument);
}

TEST(BladeRegime, RandomSweepsMatchTheDefinitionByBruteForce) {
  const unsigned seed = 20261124;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> draw(0, 3);  // 3: no common regime
  for (int trial = 0; trial < 500; ++trial) {
    const std::size_t n = 1 + static_cast<std::size_t>(trial % 40);
    Sweep regimes(n);
    for (auto& r : regimes) {
      const int v = draw(rng);
      r = v == 3 ? none : std::optional<Regime>(blade::kRegimes[static_cast<std::size_t>(v)]);
    }
    const auto chosen = blade::choose_representatives(preloads_for(n), regimes);
    std::size_t next = 0;
    for (Regime regime : blade::kRegimes) {
      // Brute force: the width of the maximal band through every point of this regime.
      std::size_t widest = 0, count = 0;
      for (std::size_t k = 0; k < n; ++k) {
        if (regimes[k] != regime) continue;
        ++count;
        std::size_t a = k, b = k;
        while (a > 0 && regimes[a - 1] == regime) --a;
        while (b + 1 < n && regimes[b + 1] == regime) ++b;
        widest = std::max(widest, b - a + 1);
      }
      if (count == 0) continue;
      ASSERT_LT(next, chosen.size()) << "seed " << seed << ", trial " << trial;
      const auto& rep = chosen[next++];
      ASSERT_EQ(rep.regime, regime) << "seed " << seed << ", trial " << trial;
      EXPECT_EQ(rep.points, count);
      // The band is maximal, of this regime, and the widest.
      EXPECT_EQ(rep.band_last - rep.band_first + 1, widest);
      for (std::size_t k = rep.band_first; k <= rep.band_last; ++k) EXPECT_EQ(regimes[k], regime);
      if (rep.band_first > 0) {
        EXPECT_NE(regimes[rep.band_first - 1], regime);
      }
      if (rep.band_last + 1 < n) {
        EXPECT_NE(regimes[rep.band_last + 1], regime);
      }
      // No wider or equally wide band at lower preload.
      for (std::size_t k = 0; k + widest <= rep.band_first; ++k) {
        bool all = true;
        for (std::size_t j = k; j < k + widest; ++j) all = all && regimes[j] == regime;
        EXPECT_FALSE(all) << "an equally wide band starts at " << k << ", seed " << seed << ", trial " << trial;
      }
      // The median: (width - 1) / 2 points from the lower edge, at least as many from the upper.
      EXPECT_EQ(rep.index - rep.band_first, (widest - 1) / 2);
      EXPECT_GE(rep.band_last - rep.index, rep.index - rep.band_first);
      EXPECT_EQ(rep.preload, preloads_for(n)[rep.index]);
    }
    EXPECT_EQ(next, chosen.size());
  }
}

// The example names regimes by the library's rule: the same name for every stick fraction, at
// and around both thresholds.
TEST(BladeRegime, NamesEveryFractionAsTheLibrarysClassifyRegime) {
  for (double s : {0.0, 0.01, 0.0499999, 0.05, 0.05000001, 0.3, 0.5, 0.998, 0.9989999, 0.999, 0.9995, 1.0})
    EXPECT_STREQ(blade::to_string(blade::damper_regime(s)), stickslip::to_string(stickslip::classify_regime(s))) << s;
}

}  // namespace blade_regime_test

namespace blade_regime_test_separation {

// The rule with separation (--restitution): a damper separated for at least 1 % of the window
// is in intermittent contact whatever its stick fraction, the library's threshold; below, the
// stick-fraction rule; fractions outside [0, 1] are refused.
TEST(BladeRegime, IntermittentContactFromTheSeparatedFraction) {
  using blade::Regime;
  EXPECT_EQ(blade::damper_regime(0.5, 0.01), Regime::IntermittentContact);
  EXPECT_EQ(blade::damper_regime(1.0, 0.2), Regime::IntermittentContact);
  EXPECT_EQ(blade::damper_regime(0.5, 0.0099), Regime::StickSlip);
  EXPECT_EQ(blade::damper_regime(1.0, 0.0), Regime::Stick);
  EXPECT_EQ(blade::kIntermittentFrom, stickslip::regime_intermittent_from);
  EXPECT_STREQ(blade::to_string(Regime::IntermittentContact),
               stickslip::to_string(stickslip::DamperRegime::IntermittentContact));
  EXPECT_THROW((void)blade::damper_regime(0.5, 1.5), std::invalid_argument);
  EXPECT_THROW((void)blade::damper_regime(-0.1, 0.0), std::invalid_argument);
  EXPECT_EQ(blade::kRegimes.size(), 3u);  // not one of the paper's regimes (no representative)
}

}  // namespace blade_regime_test_separation
