// Gutenberg-Richter fits against synthetic samples from known exponential laws: the
// estimators recover b within a few stated errors, the Shi & Bolt error matches the
// scatter over repeated samples, the KS window finds a known break, the two-power-law
// fit finds a known crossover and the excess detector finds an added bump.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "stats/gutenberg_richter.hpp"

namespace bkq {
namespace {

// Uniform in [0, 1) from 53 random bits: portable, unlike std::uniform_real_distribution.
double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}
double exponential(std::mt19937_64& rng, double b) {
  return -std::log1p(-uniform(rng)) / b;
}

std::vector<double> exp_sample(std::mt19937_64& rng, std::size_t n, double b, double mu0) {
  std::vector<double> mu(n);
  for (auto& m : mu) m = mu0 + exponential(rng, b);
  return mu;
}

class GrRecovery : public ::testing::TestWithParam<double> {};

TEST_P(GrRecovery, UnbinnedAndBinnedMleRecoverB) {
  const double b = GetParam();
  std::mt19937_64 rng(20240917);
  const auto mu = exp_sample(rng, 20000, b, 1.0);
  const GrFit f = fit_magnitudes(mu, 0.2, 1.0, std::nullopt);
  EXPECT_EQ(f.n_in_window, 20000);
  EXPECT_NEAR(f.b_aki, b, 3 * f.b_aki_err);
  EXPECT_NEAR(f.b_mle, b, 3 * f.b_mle_err);
  // Shi & Bolt: sigma ~ b / sqrt(n) for an untruncated exponential.
  EXPECT_NEAR(f.b_aki_err, b / std::sqrt(20000.0), 0.1 * b / std::sqrt(20000.0));
  EXPECT_NEAR(f.b_lsq, b, 0.1 * b);
  EXPECT_LT(f.ks_distance, 0.02);
  EXPECT_FALSE(f.excess_found);
}

TEST_P(GrRecovery, TruncatedWindowRecoversB) {
  const double b = GetParam();
  std::mt19937_64 rng(77);
  const auto mu = exp_sample(rng, 20000, b, 0.0);
  const GrFit f = fit_magnitudes(mu, 0.2, 0.4, 2.4);  // cut both ends
  EXPECT_TRUE(f.truncated);
  EXPECT_DOUBLE_EQ(f.mu_max, 2.4);
  EXPECT_NEAR(f.b_aki, b, 3 * f.b_aki_err);
  EXPECT_NEAR(f.b_mle, b, 3 * f.b_mle_err);
}

TEST_P(GrRecovery, AutomaticWindowOnPureLawStartsAtTheBottom) {
  const double b = GetParam();
  std::mt19937_64 rng(5);
  const auto mu = exp_sample(rng, 20000, b, 0.0);
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  EXPECT_TRUE(f.window_auto);
  EXPECT_NEAR(f.b_mle, b, 3 * f.b_mle_err);
}

INSTANTIATE_TEST_SUITE_P(Slopes, GrRecovery, ::testing::Values(0.5, 1.0, 1.5));

TEST(GrFit, BinnedFormUsesTheCentreOfTheFirstBin) {
  // A geometric bin-index sample with p = e^{-bw} exactly: the Tinti-Mulargia estimate
  // must return b itself (with the lower edge in place of the centre it would be ~9 % low).
  const double b = 1.0, w = 0.2, p = std::exp(-b * w);
  MagnitudeHistogram h(w);
  for (int j = 0; j < 200; ++j) {
    const auto c = static_cast<std::int64_t>(std::llround(1e6 * std::pow(p, j) * (1 - p)));
    for (std::int64_t i = 0; i < c; ++i) h.add((j + 0.5) * w);
  }
  const BEstimate e = binned_mle(h, h.first_bin(), h.last_bin(), false);
  EXPECT_NEAR(e.b, b, 2e-3);
}

TEST(GrFit, ShiBoltErrorMatchesScatter) {
  std::mt19937_64 rng(1234);
  const int reps = 300;
  const std::size_t n = 1000;
  double s = 0, s2 = 0, err = 0, sb = 0, sb2 = 0, err_b = 0;
  for (int r = 0; r < reps; ++r) {
    const auto mu = exp_sample(rng, n, 1.0, 0.0);
    const BEstimate a = aki_mle(mu, 0.0, std::nullopt);
    s += a.b;
    s2 += a.b * a.b;
    err += a.err;
    MagnitudeHistogram h(0.2);
    for (double m : mu) h.add(m);
    const BEstimate c = binned_mle(h, 0, h.last_bin(), false);
    sb += c.b;
    sb2 += c.b * c.b;
    err_b += c.err;
  }
  const double sd = std::sqrt(s2 / reps - (s / reps) * (s / reps));
  const double sd_b = std::sqrt(sb2 / reps - (sb / reps) * (sb / reps));
  EXPECT_NEAR(err / reps, sd, 0.3 * sd);
  EXPECT_NEAR(err_b / reps, sd_b, 0.3 * sd_b);
}

TEST(GrFit, AutomaticWindowFindsTheBreak) {
  // Flat (uniform) below mu = 1, exponential with b = 1 above: mu_min should be 1.
  std::mt19937_64 rng(99);
  std::vector<double> mu;
  for (int i = 0; i < 6000; ++i) mu.push_back(uniform(rng));
  for (int i = 0; i < 14000; ++i) mu.push_back(1.0 + exponential(rng, 1.0));
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  EXPECT_TRUE(f.window_auto);
  EXPECT_NEAR(f.mu_min, 1.0, 0.2 + 1e-9);
  EXPECT_NEAR(f.b_mle, 1.0, 3 * f.b_mle_err);
}

TEST(GrFit, TwoPowerLawsFindTheCrossover) {
  // D(mu) with slope 1 up to mu = 4 and slope 0.3 above, up to mu = 7 (thesis eq. 2.10).
  std::mt19937_64 rng(31);
  std::vector<double> mu;
  for (int i = 0; i < 40000; ++i) {
    const double m = 4.0 * uniform(rng);
    if (uniform(rng) < std::exp(-1.0 * m)) mu.push_back(m);
  }
  const double d4 = std::exp(-4.0);
  for (int i = 0; i < 40000; ++i) {
    const double m = 4.0 + 3.0 * uniform(rng);
    if (uniform(rng) < d4 * std::exp(-0.3 * (m - 4.0)) * 20) mu.push_back(m);
  }
  const GrFit f = fit_magnitudes(mu, 0.2, 0.0, std::nullopt);
  ASSERT_TRUE(f.two_law_ok) << f.two_law_reason;
  EXPECT_NEAR(f.two_law_mu_cross, 4.0, 0.2 + 1e-9);
  EXPECT_NEAR(f.two_law_b1, 1.0, 0.1);
  EXPECT_NEAR(f.two_law_b2, 0.3, 0.15);
}

TEST(GrFit, ExcessOfLargeEventsIsFound) {
  std::mt19937_64 rng(8);
  auto mu = exp_sample(rng, 20000, 1.0, 0.0);
  for (int i = 0; i < 200; ++i) mu.push_back(11.0 + 0.3 * uniform(rng));  // delocalised bump
  const GrFit f = fit_magnitudes(mu, 0.2, 0.0, 8.0);
  ASSERT_TRUE(f.excess_found);
  EXPECT_GE(f.excess_mu, 8.0 - 1e-9);
  EXPECT_LE(f.excess_mu, 11.0 + 1e-9);
  EXPECT_NEAR(f.excess_count, 200, 15);
}

TEST(GrFit, AutomaticWindowIgnoresTheBumpOfLargeEvents) {
  std::mt19937_64 rng(8);
  auto mu = exp_sample(rng, 20000, 1.0, 0.0);
  for (int i = 0; i < 200; ++i) mu.push_back(11.0 + 0.3 * uniform(rng));
  const GrFit f = fit_magnitudes(mu, 0.2, std::nullopt, std::nullopt);
  EXPECT_LT(f.mu_min, 2.0);
  // mu_max is chosen too: the window stops below the bump (which would pull b_mle down to
  // ~0.92) and b is recovered. The crossover and excess still see the bump.
  EXPECT_TRUE(f.mu_max_auto);
  EXPECT_LE(f.mu_max, 11.0 + 1e-9);
  EXPECT_NEAR(f.b_mle, 1.0, 3 * f.b_mle_err);
  ASSERT_TRUE(f.two_law_ok);
  EXPECT_NEAR(f.two_law_mu_cross, 11.0, 0.2 + 1e-9);
  ASSERT_TRUE(f.excess_found);
  EXPECT_LE(f.excess_mu, 11.0 + 1e-9);
  EXPECT_GT(f.excess_count, 20);
}

TEST(GrFit, TooFewEventsIsAnError) {
  MagnitudeHistogram h(0.2);
  h.add(1.0);
  try {
    fit_histogram(h, std::nullopt, std::nullopt);
    FAIL() << "expected bkq::Error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "need at least 2 events to fit, found 1");
  }
}

}  // namespace
}  // namespace bkq
