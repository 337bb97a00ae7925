// The fit ends on any input: window limits that are not finite or lie
// absurdly far from the magnitudes are errors, not loops over 10^300 bins; a histogram
// too wide for the window search is an error; and a fit asked to stop (a run got SIGTERM)
// stops with FitCancelled instead of finishing. Each case would hang or run for minutes
// before the bounds were added, so the tests only check that an error comes back.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>

#include "../cli_helpers.hpp"
#include "core/error.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {
namespace {

MagnitudeHistogram sample(double w = 0.2, int n = 5000) {
  std::mt19937_64 rng(5);
  MagnitudeHistogram h(w);
  for (int i = 0; i < n; ++i) h.add(-std::log1p(-static_cast<double>(rng() >> 11) * 0x1.0p-53));
  return h;
}

void expect_error(const MagnitudeHistogram& h, std::optional<double> lo, std::optional<double> hi,
                  const std::string& fragment) {
  try {
    fit_histogram(h, lo, hi);
    FAIL() << "expected bkq::Error mentioning '" << fragment << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(FitBounds, HugeOrNonFiniteLimitsAreErrors) {
  const MagnitudeHistogram h = sample();
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  constexpr double inf = std::numeric_limits<double>::infinity();
  expect_error(h, -1e300, std::nullopt, "mu_min");
  expect_error(h, std::nullopt, 1e308, "mu_max");
  expect_error(h, -1e300, 1e300, "mu_min");
  expect_error(h, nan, std::nullopt, "mu_min = nan");
  expect_error(h, std::nullopt, nan, "mu_max = nan");
  expect_error(h, -inf, std::nullopt, "mu_min");
  expect_error(h, 0.0, inf, "mu_max");
  // Finite but a million bins away: refused as well (the window would span them all).
  expect_error(h, -2e5, std::nullopt, "bins");
  expect_error(h, std::nullopt, 2e5, "bins");
}

TEST(FitBounds, GivenLimitsAFewBinsOutsideTheDataStillFit) {
  const MagnitudeHistogram h = sample();
  const GrFit f = fit_histogram(h, -50.0, 50.0);
  EXPECT_DOUBLE_EQ(f.mu_min, -50.0);
  EXPECT_DOUBLE_EQ(f.mu_max, 50.0);
  EXPECT_EQ(f.n_in_window, h.events());
  // b is ~0 on such a window: either a finite b or no b with the reason why.
  EXPECT_TRUE(f.b_ok ? std::isfinite(f.b_mle) : !f.no_b_reason.empty()) << f.no_b_reason;
}

TEST(FitBounds, TooManyBinsForTheWindowSearchIsAnError) {
  // 5000 events spanning ~9 units of mu in bins of 10^-3: ~9000 bins, beyond what the
  // automatic window search covers; explicit limits still fit.
  const MagnitudeHistogram h = sample(1e-3);
  expect_error(h, std::nullopt, std::nullopt, "bin width");
  const GrFit f = fit_histogram(h, 0.5, 3.0);
  EXPECT_NEAR(f.b_mle, 1.0, 4 * f.b_mle_err);
}

TEST(FitBounds, ABinWidthTooSmallForTheMagnitudesIsAnError) {
  // Every magnitude lands in a bin index near the int64 limit; the loops used to wrap.
  MagnitudeHistogram h(1e-300);
  for (double mu : {-2.0, -1.0, 0.5, 1.5}) h.add(mu);
  expect_error(h, std::nullopt, std::nullopt, "too small");
}

TEST(FitBounds, ACancelledFitStops) {
  const MagnitudeHistogram h = sample();
  GrFitOptions opt;
  int polls = 0;
  opt.cancelled = [&polls] { return ++polls > 3; };
  EXPECT_THROW(fit_histogram(h, std::nullopt, std::nullopt, opt), FitCancelled);
  EXPECT_EQ(polls, 4);  // it stopped at the first poll that said so
  opt.cancelled = [] { return false; };
  EXPECT_NO_THROW(fit_histogram(h, std::nullopt, std::nullopt, opt));
}

// Through the program: `bkquake fit` refuses such a limit with exit 2 and one line; a run
// given one (the scene key, before the boundary check refuses it) ends instead of hanging.
TEST(FitBounds, TheProgramEndsOnAbsurdLimits) {
  test::TempDir dir;
  const std::string out = dir.file("run");
  const auto r = test::run_bkquake({"run", "--set", "model.blocks=30", "--set", "run.events=3000",
                                    "--set", "run.transient_events=100", "--set",
                                    "stats.mu_min=-1e300", "--out", out, "--quiet"});
  EXPECT_TRUE(r.status == 0 || r.status == 2) << r.status << r.err;
  if (r.status == 0) {
    EXPECT_NE(test::read_file(out + "/summary.json").find("fit_error"), std::string::npos);
  }
  const std::string catalog = out + "/catalog.csv";
  if (r.status != 0) {
    const auto ok =
        test::run_bkquake({"run", "--set", "model.blocks=30", "--set", "run.events=3000", "--set",
                           "run.transient_events=100", "--out", out, "--quiet", "--force"});
    ASSERT_EQ(ok.status, 0) << ok.err;
  }
  for (const char* opt : {"--mu-min=-1e300", "--mu-max=1e308", "--mu-min=nan", "--mu-max=-inf"}) {
    const auto f = test::run_bkquake({"fit", catalog, opt});
    EXPECT_EQ(f.status, 2) << opt << ": " << f.out << f.err;
    EXPECT_EQ(f.err_lines().size(), 1u) << f.err;
  }
}

}  // namespace
}  // namespace bkq
