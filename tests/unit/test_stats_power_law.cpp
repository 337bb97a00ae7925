// Power-law fits of any size measure (Clauset, Shalizi & Newman 2009):
// synthetic continuous and discrete power laws, with and without an upper cut-off, give a
// mean exponent over 5 fixed seeds within 2 sigma / sqrt(5) of the truth (sigma the mean
// reported error) and a goodness-of-fit p > 0.1 in at least 4 of 5; a lognormal sample is
// told apart by Vuong's likelihood ratio, a power law with an exponential cut-off by the
// nested one; correlated events (each repeated k times) have a bootstrap error sqrt(k)
// times the Fisher one; the automatic x_max stops below a bump.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "stats/power_law.hpp"

namespace bkq {
namespace {

double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Continuous power law with exponent alpha on [a, b] (b = inf: none), by inversion.
double continuous(std::mt19937_64& rng, double alpha, double a, double b) {
  const double beta = alpha - 1;
  const double c = std::isinf(b) ? 1.0 : -std::expm1(-beta * std::log(b / a));
  return a * std::exp(-std::log1p(-c * uniform(rng)) / beta);
}

// Discrete power law on the integers [a, b] by inversion of its tabulated distribution
// (b = inf: tabulated to 10^6, beyond which the mass is below 1e-7 for alpha >= 2.2).
struct Discrete {
  std::vector<double> cdf;
  double a;
  Discrete(double alpha, double a_, double b) : a(a_) {
    const double end = std::isinf(b) ? 1e6 : b;
    double z = 0;
    for (double x = a; x <= end; x += 1) z += std::pow(x, -alpha);
    double c = 0;
    for (double x = a; x <= end; x += 1) cdf.push_back(c += std::pow(x, -alpha) / z);
  }
  double operator()(std::mt19937_64& rng) const {
    const double r = uniform(rng);
    return a + static_cast<double>(std::upper_bound(cdf.begin(), cdf.end(), r) - cdf.begin());
  }
};

struct Case {
  const char* name;
  bool discrete;
  double alpha, a, b;  // b: the upper cut-off of the data (inf: none), given to the fit
  int n;
};

class PowerLawRecovery : public ::testing::TestWithParam<Case> {};

TEST_P(PowerLawRecovery, MeanExponentIsTheTruthAndTheFitPasses) {
  const Case c = GetParam();
  const Discrete table = c.discrete ? Discrete(c.alpha, c.a, c.b) : Discrete(2, 1, 1);
  double sum_alpha = 0, sum_err = 0;
  int passed = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    std::mt19937_64 rng(seed);
    std::vector<double> x(static_cast<std::size_t>(c.n));
    for (auto& v : x) v = c.discrete ? table(rng) : continuous(rng, c.alpha, c.a, c.b);
    PowerLawOptions opt;
    opt.discrete = c.discrete;
    if (std::isfinite(c.b)) opt.x_max = c.b;
    opt.gof_sets = 50;
    const PowerLawFit f = fit_power_law(x, opt);
    ASSERT_TRUE(f.ok) << c.name << ": " << f.no_fit_reason;
    EXPECT_GE(f.x_min, c.a);
    EXPECT_GT(f.n_tail, c.n / 10);
    sum_alpha += f.alpha;
    sum_err += f.alpha_err;
    passed += f.p > 0.1;
    // Independent events: the bootstrap error agrees with the Fisher one (within 25 %).
    EXPECT_NEAR(f.alpha_boot_err / f.alpha_err, 1.0, 0.25) << c.name << " seed " << seed;
  }
  const double mean = sum_alpha / 5, sigma = sum_err / 5;
  EXPECT_NEAR(mean, c.alpha, 2 * sigma / std::sqrt(5.0)) << c.name;
  EXPECT_GE(passed, 4) << c.name;
}

constexpr double kNone = std::numeric_limits<double>::infinity();

INSTANTIATE_TEST_SUITE_P(Samples, PowerLawRecovery,
                         ::testing::Values(Case{"continuous", false, 2.5, 1.0, kNone, 5000},
                                           Case{"continuous_cut", false, 1.6, 1.0, 1000.0, 5000},
                                           Case{"discrete", true, 2.2, 1.0, kNone, 5000},
                                           Case{"discrete_cut", true, 1.5, 1.0, 300.0, 5000}),
                         [](const auto& info) { return std::string(info.param.name); });

// A lognormal sample (mu = 0, sigma = 1.5, 20000 values): Vuong's ratio prefers the
// lognormal (negative) with p < 0.1 on the tail the fit chose.
TEST(PowerLawCompare, ALognormalSampleIsToldApart) {
  std::mt19937_64 rng(3);
  std::vector<double> x;
  for (int i = 0; i < 20000; ++i) {
    const double z =
        std::sqrt(-2 * std::log1p(-uniform(rng))) * std::cos(2 * std::numbers::pi * uniform(rng));
    x.push_back(std::exp(1.5 * z));
  }
  PowerLawOptions opt;
  opt.gof_sets = 0;
  opt.x_min = 1.0;
  const PowerLawFit f = fit_power_law(x, opt);
  ASSERT_TRUE(f.ok) << f.no_fit_reason;
  EXPECT_LT(f.lognormal_ratio, 0);
  EXPECT_LT(f.lognormal_p, 0.1);
  EXPECT_NEAR(f.lognormal_sigma, 1.5, 0.15);
  // And a power-law sample is not taken for a lognormal.
  std::vector<double> y;
  for (int i = 0; i < 20000; ++i) y.push_back(continuous(rng, 2.5, 1.0, kNone));
  const PowerLawFit g = fit_power_law(y, opt);
  EXPECT_FALSE(g.lognormal_ratio < 0 && g.lognormal_p < 0.1)
      << g.lognormal_ratio << " p " << g.lognormal_p;
}

// x^-1.5 e^{-x / 100} (by rejection from the power law): the nested ratio finds the
// cut-off (p < 0.01, lambda near 1/100); on a pure power law it does not (p > 0.01).
TEST(PowerLawCompare, AnExponentialCutOffIsFound) {
  std::mt19937_64 rng(4);
  std::vector<double> x;
  while (x.size() < 20000) {
    const double v = continuous(rng, 1.5, 1.0, kNone);
    if (uniform(rng) < std::exp(-(v - 1) / 100)) x.push_back(v);
  }
  PowerLawOptions opt;
  opt.gof_sets = 0;
  opt.x_min = 1.0;
  const PowerLawFit f = fit_power_law(x, opt);
  ASSERT_TRUE(f.ok) << f.no_fit_reason;
  EXPECT_LT(f.cutoff_p, 0.01);
  EXPECT_NEAR(f.cutoff_lambda, 0.01, 0.003);
  EXPECT_NEAR(f.cutoff_alpha, 1.5, 0.05);
  std::vector<double> y;
  for (int i = 0; i < 20000; ++i) y.push_back(continuous(rng, 1.5, 1.0, kNone));
  const PowerLawFit g = fit_power_law(y, opt);
  EXPECT_GT(g.cutoff_p, 0.01) << g.cutoff_ratio;
}

// Each value repeated k times in a row: the block bootstrap's error is sqrt(k) times the
// Fisher error, within 15 %.
class PowerLawBootstrap : public ::testing::TestWithParam<int> {};

TEST_P(PowerLawBootstrap, ErrorGrowsBySqrtK) {
  const int k = GetParam();
  std::mt19937_64 rng(static_cast<std::uint64_t>(10 + k));
  std::vector<double> x;
  for (int i = 0; i < 10000; ++i) {
    const double v = continuous(rng, 2.0, 1.0, kNone);
    for (int j = 0; j < k; ++j) x.push_back(v);
  }
  PowerLawOptions opt;
  opt.gof_sets = 0;
  opt.compare = false;
  opt.x_min = 1.0;
  const PowerLawFit f = fit_power_law(x, opt);
  ASSERT_TRUE(f.ok);
  EXPECT_NEAR(f.alpha_boot_err / f.alpha_err, std::sqrt(static_cast<double>(k)),
              0.15 * std::sqrt(static_cast<double>(k)));
}

INSTANTIATE_TEST_SUITE_P(K, PowerLawBootstrap, ::testing::Values(1, 4, 9));

// A discrete power law with a bump of large sizes above a gap: the automatic x_max stops
// below the bump, and the exponent is that of the power law.
TEST(PowerLawXMax, StopsBelowABump) {
  std::mt19937_64 rng(6);
  const Discrete table(2.0, 1, 200);
  std::vector<double> x;
  for (int i = 0; i < 50000; ++i)
    x.push_back(uniform(rng) < 0.02 ? std::floor(2000 + 500 * uniform(rng)) : table(rng));
  PowerLawOptions opt;
  opt.discrete = true;
  opt.gof_sets = 0;
  const PowerLawFit f = fit_power_law(x, opt);
  ASSERT_TRUE(f.ok) << f.no_fit_reason;
  EXPECT_LE(f.x_max, 2000);
  EXPECT_NE(f.x_max_reason, "none");
  EXPECT_NEAR(f.alpha, 2.0, 3 * f.alpha_err);
}

// Too few values: no fit, and the reason.
TEST(PowerLawFitInputs, TooFewValuesGiveNoFitAndAReason) {
  const std::vector<double> x{1, 2, 3, -1, 0};
  const PowerLawFit f = fit_power_law(x);
  EXPECT_FALSE(f.ok);
  EXPECT_NE(f.no_fit_reason.find("fewer than"), std::string::npos) << f.no_fit_reason;
  EXPECT_TRUE(std::isnan(f.alpha));
}

}  // namespace
}  // namespace bkq
