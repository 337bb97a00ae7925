// Automatic fit window (both ends): a bump of large events above a truncated exponential
// is left out of the window and b is recovered; on a pure exponential the window spans
// (almost) the whole sample; a given mu_max still fixes the upper end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "stats/gutenberg_richter.hpp"

namespace bkq {
namespace {

double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Exponential with slope b truncated to [lo, hi), by inversion.
double truncated_exponential(std::mt19937_64& rng, double b, double lo, double hi) {
  const double c = -std::expm1(-b * (hi - lo));
  return lo - std::log1p(-c * uniform(rng)) / b;
}

class WindowBump : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(WindowBump, AutomaticWindowExcludesTheBumpAndRecoversB) {
  std::mt19937_64 rng(GetParam());
  std::vector<double> mu;
  for (int i = 0; i < 20000; ++i) mu.push_back(truncated_exponential(rng, 1.0, 0.0, 6.0));
  for (int i = 0; i < 300; ++i) mu.push_back(7.0 + uniform(rng));  // bump at mu = 7-8
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  EXPECT_TRUE(f.window_auto);
  EXPECT_TRUE(f.mu_max_auto);
  EXPECT_TRUE(f.truncated);
  EXPECT_LE(f.mu_max, 6.2 + 1e-9);
  EXPECT_GE(f.mu_max, 4.0 - 1e-9);
  EXPECT_LE(f.mu_min, 0.6 + 1e-9);
  EXPECT_NEAR(f.b_mle, 1.0, 3 * f.b_mle_err);
  EXPECT_NEAR(f.b_aki, 1.0, 3 * f.b_aki_err);
  // The bump lies above the window and is reported as an excess.
  ASSERT_TRUE(f.excess_found);
  EXPECT_GE(f.excess_mu, f.mu_max - 1e-9);
  EXPECT_LE(f.excess_mu, 7.0 + 1e-9);
  EXPECT_NEAR(f.excess_count, 300, 30);
}

INSTANTIATE_TEST_SUITE_P(Seeds, WindowBump, ::testing::Values(1u, 2u, 3u, 4u, 5u));

class WindowPure : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(WindowPure, AutomaticWindowCoversAPureExponential) {
  std::mt19937_64 rng(GetParam());
  std::vector<double> mu(20000);
  for (auto& m : mu) m = -std::log1p(-uniform(rng));  // b = 1 above 0
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  EXPECT_TRUE(f.mu_max_auto);
  EXPECT_LE(f.mu_min, 0.6 + 1e-9);
  // Most of the range and almost all the events (the top bins hold a handful).
  const double range = *std::max_element(mu.begin(), mu.end());
  EXPECT_GE(f.mu_max - f.mu_min, 0.75 * range);
  const auto above_min =
      std::count_if(mu.begin(), mu.end(), [&](double m) { return m >= f.mu_min; });
  EXPECT_GE(static_cast<double>(f.n_in_window), 0.99 * static_cast<double>(above_min));
  EXPECT_NEAR(f.b_mle, 1.0, 3 * f.b_mle_err);
}

INSTANTIATE_TEST_SUITE_P(Seeds, WindowPure, ::testing::Values(1u, 2u, 3u, 4u, 5u));

TEST(Window, GivenMuMinScansOnlyMuMax) {
  std::mt19937_64 rng(6);
  std::vector<double> mu;
  for (int i = 0; i < 20000; ++i) mu.push_back(truncated_exponential(rng, 1.0, 0.0, 6.0));
  for (int i = 0; i < 300; ++i) mu.push_back(7.0 + uniform(rng));
  const GrFit f = fit_magnitudes(mu, 0.2, 0.4, std::nullopt);
  EXPECT_FALSE(f.window_auto);
  EXPECT_TRUE(f.mu_max_auto);
  EXPECT_DOUBLE_EQ(f.mu_min, 0.4);
  EXPECT_LE(f.mu_max, 6.2 + 1e-9);
  EXPECT_NEAR(f.b_mle, 1.0, 3 * f.b_mle_err);
}

TEST(Window, GivenMuMaxIsKept) {
  std::mt19937_64 rng(7);
  std::vector<double> mu;
  for (int i = 0; i < 20000; ++i) mu.push_back(truncated_exponential(rng, 1.0, 0.0, 6.0));
  for (int i = 0; i < 300; ++i) mu.push_back(7.0 + uniform(rng));
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, 8.0);
  EXPECT_FALSE(f.mu_max_auto);
  EXPECT_TRUE(f.truncated);
  EXPECT_DOUBLE_EQ(f.mu_max, 8.0);
  EXPECT_LT(f.b_mle, 1.0);  // the bump is inside the given window and pulls b down
}

// The shape of a Burridge-Knopoff D(mu) (issue 19, item 10): an atom of one-block events and
// a few uneven few-block bins at the bottom, a power law with b = 0.9 over six units, a
// flat dip, then a bump of large events. The automatic window starts above the uneven bins,
// ends below the bump, keeps the power law's events and recovers b. Before the rule of
// README "How b is fitted" the window narrowed to a few units inside the power law.
class WindowShape : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(WindowShape, WindowCoversThePowerLawBetweenTheBottomStructureAndTheBump) {
  std::mt19937_64 rng(GetParam());
  std::vector<double> mu;
  for (int i = 0; i < 60000; ++i) mu.push_back(-2.9 + 0.05 * uniform(rng));  // the atom
  for (int i = 0; i < 4000; ++i) mu.push_back(-1.6 + 0.2 * uniform(rng));    // 2-block bins
  for (int i = 0; i < 1000; ++i) mu.push_back(-1.2 + 0.2 * uniform(rng));
  for (int i = 0; i < 3000; ++i) mu.push_back(-0.8 + 0.2 * uniform(rng));
  for (int i = 0; i < 20000; ++i) mu.push_back(truncated_exponential(rng, 0.9, 0.0, 6.0));
  for (int i = 0; i < 40; ++i) mu.push_back(6.0 + 3.0 * uniform(rng));  // the dip
  for (int i = 0; i < 500; ++i) mu.push_back(10.0 + 0.8 * (uniform(rng) + uniform(rng) - 1));
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  EXPECT_GE(f.mu_min, -0.6 - 1e-9);
  EXPECT_LE(f.mu_min, 0.4 + 1e-9);
  EXPECT_GE(f.mu_max, 5.0 - 1e-9);
  EXPECT_LE(f.mu_max, 9.6 + 1e-9);
  EXPECT_GE(f.n_in_window, 18000);
  EXPECT_NEAR(f.b_mle, 0.9, 3 * f.b_mle_err);
}

INSTANTIATE_TEST_SUITE_P(Seeds, WindowShape, ::testing::Values(1u, 2u, 3u, 4u, 5u));

TEST(Window, RisingDistributionGivesNoB) {
  // The number of events grows with magnitude everywhere: no window, no b, and why.
  std::mt19937_64 rng(9);
  std::vector<double> mu;
  for (int i = 0; i < 5000; ++i) mu.push_back(4.0 * std::sqrt(uniform(rng)));
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  EXPECT_FALSE(f.b_ok);
  EXPECT_FALSE(f.no_b_reason.empty());
  EXPECT_TRUE(std::isnan(f.b_mle));
  EXPECT_TRUE(std::isnan(f.b_aki));
  // A given window on it: b_mle would be negative, so no b either.
  const GrFit g = fit_magnitudes(mu, 0.2, 0.0, 4.0);
  EXPECT_FALSE(g.b_ok);
  EXPECT_NE(g.no_b_reason.find("do not decrease"), std::string::npos) << g.no_b_reason;
}

// The search fits the widest windows first and stops at the first width holding an
// accepted one: with mu_max given (so no rise rule) and a curved D(mu) that KS rejects
// over its whole range, the window picked is accepted and every wider one that meets the
// cheap conditions (populated first bin, >= 50 events, >= 10 bins) is rejected by b or KS.
TEST(Window, PicksTheWidestAcceptedWindowWhenTheWidestAreRejected) {
  std::mt19937_64 rng(11);
  std::vector<double> mu;
  for (int i = 0; i < 20000; ++i) mu.push_back(truncated_exponential(rng, 0.4, 0.0, 3.0));
  for (int i = 0; i < 20000; ++i) mu.push_back(truncated_exponential(rng, 1.5, 0.0, 8.0));
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, 8.0);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  MagnitudeHistogram h(0.2);
  for (const double m : mu) h.add(m);
  const GrFitOptions opt;
  const auto k_of = [&](double edge) { return std::llround(edge / 0.2); };
  const std::int64_t lo_pick = k_of(f.mu_min), hi = k_of(f.mu_max) - 1;
  const auto accepted = [&](std::int64_t lo) {
    const BEstimate e = binned_mle(h, lo, hi, true);
    if (!(e.b > 0) || !std::isfinite(e.err)) return false;
    const double n = static_cast<double>(h.count_range(lo, hi));
    return ks_distance_binned(h, lo, hi, e.b, true) <=
           opt.ks_systematic + opt.ks_tolerance / std::sqrt(n);
  };
  EXPECT_TRUE(accepted(lo_pick));
  int wider = 0;
  for (std::int64_t lo = h.first_bin(); lo < lo_pick; ++lo) {
    if (h.count(lo) == 0 || hi - lo + 1 < opt.min_window_bins ||
        h.count_range(lo, hi) < opt.min_tail)
      continue;
    ++wider;
    EXPECT_FALSE(accepted(lo)) << "a wider window [" << h.mu_low(lo) << ", 8) is accepted";
  }
  EXPECT_GT(wider, 3) << "the widest windows were not rejected: the test shows nothing";
}

}  // namespace
}  // namespace bkq
