// The automatic window never takes in a gap or a bump: synthetic
// catalogues with a known b and, above the scaling region, a gap of empty bins or a bump of
// large events, at 10^4 and 10^6 events. The window ends below the gap or the bump and the
// mean b over 5 fixed seeds lies within 2 sigma / sqrt(5) of the truth (sigma the mean
// reported statistical error). A catalogue with no scaling region gets no b and a reason;
// a window given across a gap or a rise is fitted and warned about; the block bootstrap's
// error of a catalogue of events repeated k times is sqrt(k) times the Poisson one.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "stats/gutenberg_richter.hpp"

namespace bkq {
namespace {

double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}
double truncated_exponential(std::mt19937_64& rng, double b, double lo, double hi) {
  const double c = -std::expm1(-b * (hi - lo));
  return lo - std::log1p(-c * uniform(rng)) / b;
}

constexpr double kB = 1.0;

// b = 1 on [0, 6), nothing on [6, 8) (a gap of 10 bins), a bump of 3 % of the events on
// [8, 9); in the order drawn (no correlation).
std::vector<double> with_gap(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::vector<double> mu;
  for (int i = 0; i < n; ++i)
    mu.push_back(uniform(rng) < 0.03 ? 8.0 + uniform(rng) : truncated_exponential(rng, kB, 0, 6));
  return mu;
}
// b = 1 on [0, 5.4), then a plateau of large events rising into a bump on [5.4, 8.4)
// (no gap: 2 % of the events, density rising towards 7.5).
std::vector<double> with_bump(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::vector<double> mu;
  for (int i = 0; i < n; ++i)
    mu.push_back(uniform(rng) < 0.02 ? 5.4 + 3.0 * std::sqrt(uniform(rng))
                                     : truncated_exponential(rng, kB, 0, 5.4));
  return mu;
}

struct Case {
  const char* name;
  std::vector<double> (*make)(std::uint64_t, int);
  int events;
  double top;  // the window's upper end lies at or below
};

class WindowStopsBelow : public ::testing::TestWithParam<Case> {};

TEST_P(WindowStopsBelow, TheGapOrTheBumpAndMeanBIsTheTruth) {
  const Case c = GetParam();
  double sum_b = 0, sum_err = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const GrFit f = fit_magnitudes(c.make(seed, c.events), 0.2, std::nullopt, std::nullopt);
    ASSERT_TRUE(f.b_ok) << c.name << " seed " << seed << ": " << f.no_b_reason;
    EXPECT_LE(f.mu_max, c.top + 1e-9) << c.name << " seed " << seed << " [" << f.mu_min << ", "
                                      << f.mu_max << ") " << f.mu_max_reason;
    EXPECT_GE(f.mu_max - f.mu_min, 2.0 - 1e-9);
    EXPECT_NE(f.mu_max_reason, "end of data");
    EXPECT_TRUE(f.warnings.empty());
    sum_b += f.b_mle;
    sum_err += f.b_mle_err;
  }
  const double mean_b = sum_b / 5, sigma = sum_err / 5;
  EXPECT_NEAR(mean_b, kB, 2 * sigma / std::sqrt(5.0)) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Catalogues, WindowStopsBelow,
                         ::testing::Values(Case{"gap_1e4", with_gap, 10'000, 6.0},
                                           Case{"gap_1e6", with_gap, 1'000'000, 6.0},
                                           Case{"bump_1e4", with_bump, 10'000, 5.6},
                                           Case{"bump_1e6", with_bump, 1'000'000, 5.6}),
                         [](const auto& info) { return std::string(info.param.name); });

// The gap stops the window: its top is "gap" on the catalogue with a gap.
TEST(WindowGap, TheTopSaysItStopsAtTheGap) {
  const GrFit f = fit_magnitudes(with_gap(7, 100'000), 0.2, std::nullopt, std::nullopt);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  EXPECT_EQ(f.mu_max_reason, "gap");
  EXPECT_DOUBLE_EQ(f.mu_max, 6.0);
}

// Isolated empty bins (integer sizes: ln 1, ln 2, ln 3, ... leave runs of at most 3 empty
// bins of 0.2) are no gap: a discrete power law in the size s keeps its window.
TEST(WindowGap, IsolatedEmptyBinsOfIntegerSizesAreNoGap) {
  std::mt19937_64 rng(3);
  std::vector<double> mu;
  for (int i = 0; i < 200'000; ++i) {
    const double s = std::floor(std::pow(1 - uniform(rng), -1.0 / 1.2));  // tau = 2.2
    mu.push_back(std::log(s));
  }
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  EXPECT_NE(f.mu_max_reason, "gap");
  EXPECT_GE(f.mu_max, 6.0);
}

// No scaling region (a lognormal moment: a Gaussian in mu, 10^5 events): no window passes
// the goodness-of-fit test, so no b, and the reason names the test.
TEST(WindowGap, NoScalingRegionGivesNoBAndTheReason) {
  std::mt19937_64 rng(5);
  std::vector<double> mu;
  for (int i = 0; i < 100'000; ++i) {
    const double u1 = uniform(rng), u2 = uniform(rng);
    mu.push_back(2.0 * std::sqrt(-2 * std::log1p(-u1)) * std::cos(2 * M_PI * u2));
  }
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  EXPECT_FALSE(f.b_ok) << "b = " << f.b_mle << " on [" << f.mu_min << ", " << f.mu_max << ")";
  EXPECT_TRUE(std::isnan(f.b_mle));
  EXPECT_FALSE(f.no_b_reason.empty());
}

// A window given across the gap is fitted, with a warning that names the gap; one given
// across the rise into the bump, with a warning of the rise.
TEST(WindowGap, AGivenWindowAcrossAGapOrARiseIsWarnedAbout) {
  const GrFit f = fit_magnitudes(with_gap(9, 100'000), 0.2, 0.0, 9.0);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  bool gap = false;
  for (const auto& w : f.warnings) gap = gap || w.find("crosses a gap") != std::string::npos;
  EXPECT_TRUE(gap) << ::testing::PrintToString(f.warnings);
  const GrFit g = fit_magnitudes(with_bump(9, 100'000), 0.2, 0.0, 8.4);
  ASSERT_TRUE(g.b_ok) << g.no_b_reason;
  bool rise = false;
  for (const auto& w : g.warnings) rise = rise || w.find("rise") != std::string::npos;
  EXPECT_TRUE(rise) << ::testing::PrintToString(g.warnings);
  // On the scaling region itself: no warning.
  const GrFit h = fit_magnitudes(with_gap(9, 100'000), 0.2, 0.0, 5.0);
  EXPECT_TRUE(h.warnings.empty()) << ::testing::PrintToString(h.warnings);
}

// Each event repeated k times in a row: the Poisson error treats the copies as independent,
// the block bootstrap (blocks chosen from the data) sees the correlation: its error is
// sqrt(k) times the Poisson one, within 15 % (200 resamples: ~5 % noise on each).
class BootstrapRepeated : public ::testing::TestWithParam<int> {};

TEST_P(BootstrapRepeated, ErrorGrowsBySqrtK) {
  const int k = GetParam();
  std::mt19937_64 rng(static_cast<std::uint64_t>(k));
  std::vector<double> mu;
  for (int i = 0; i < 20'000; ++i) {
    const double m = truncated_exponential(rng, kB, 0, 8);
    for (int j = 0; j < k; ++j) mu.push_back(m);
  }
  const GrFit f = fit_magnitudes(mu, 0.2, 0.0, 6.0);
  ASSERT_TRUE(f.b_ok);
  ASSERT_TRUE(std::isfinite(f.b_mle_boot_err)) << f.boot_note;
  EXPECT_GE(f.boot_block, k);
  EXPECT_NEAR(f.boot_tau_int, k, 0.25 * k);
  EXPECT_NEAR(f.b_mle_boot_err / f.b_mle_err, std::sqrt(static_cast<double>(k)),
              0.15 * std::sqrt(static_cast<double>(k)))
      << "boot " << f.b_mle_boot_err << " poisson " << f.b_mle_err << " block " << f.boot_block;
}

INSTANTIATE_TEST_SUITE_P(K, BootstrapRepeated, ::testing::Values(1, 4, 9));

// Slow correlation, as loading cycles make it: b changes every 2000 events (1.0 +/- 0.15 at
// random), 40000 events. The autocorrelation of neighbouring events is nearly zero, yet b
// varies between catalogues far beyond the Poisson error. The block length found where the
// batch-means error levels off makes the bootstrap error describe the spread between 20
// seeds (sd / mean error in [0.75, 1.33]: the sd of 20 values is uncertain by 16 %), and
// the blocks span the stretches.
TEST(Bootstrap, BlockLengthReachesSlowCorrelations) {
  std::vector<double> b;
  double boot = 0, poisson = 0;
  std::int64_t shortest_block = 1 << 30;
  constexpr int kSeeds = 20;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(1000 + seed));
    std::vector<double> mu;
    for (int stretch = 0; stretch < 20; ++stretch) {
      const double b_here = uniform(rng) < 0.5 ? 0.85 : 1.15;
      for (int i = 0; i < 2000; ++i) mu.push_back(truncated_exponential(rng, b_here, 0, 8));
    }
    const GrFit f = fit_magnitudes(mu, 0.2, 0.0, 6.0);
    ASSERT_TRUE(f.b_ok && std::isfinite(f.b_mle_boot_err)) << f.boot_note;
    b.push_back(f.b_mle);
    boot += f.b_mle_boot_err / kSeeds;
    poisson += f.b_mle_err / kSeeds;
    shortest_block = std::min(shortest_block, f.boot_block);
  }
  double mean = 0, ss = 0;
  for (double v : b) mean += v / kSeeds;
  for (double v : b) ss += (v - mean) * (v - mean);
  const double sd = std::sqrt(ss / (kSeeds - 1));
  EXPECT_GT(sd, 3 * poisson) << "the catalogues are not correlated enough to test anything";
  EXPECT_GE(sd / boot, 0.75) << "sd " << sd << " bootstrap " << boot;
  EXPECT_LE(sd / boot, 1.33) << "sd " << sd << " bootstrap " << boot;
  EXPECT_GE(shortest_block, 1000);
}

// Fixed seed: the bootstrap error is the same on every call.
TEST(Bootstrap, IsReproducible) {
  const std::vector<double> mu = with_gap(2, 20'000);
  const GrFit a = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  const GrFit b = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  EXPECT_EQ(a.b_mle_boot_err, b.b_mle_boot_err);
  EXPECT_GT(a.boot_resamples, 100);
}

}  // namespace
}  // namespace bkq
