// The automatic fit window on real catalogues (issue 19, item 10), 10^5 events each (under a
// second per scene): on the Carlson-Langer scenes alpha = 2, 2.5, 3 the automatic b agrees
// with the b on the window read off by eye, [-7.6, -2.0), on the same catalogue within two
// combined errors (statistical, and the automatic b's systematic one); on the
// Mori-Kawamura ring the window stays below the bump of large events and b is positive; a
// given window on which the events increase gives no b in summary.json, with the reason.
// Before the rules of docs/explanation/b-fit.md the default scene gave 0.975 +/- 0.015 on
// [-6.4, 1.8) against 0.920 +/- 0.009 by eye, and the ring b = -0.43.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../cli_helpers.hpp"
#include "io/histogram_csv.hpp"
#include "stats/gutenberg_richter.hpp"

namespace bkq {
namespace {

std::string scene(const std::string& name) {
  return std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/" + name;
}

MagnitudeHistogram run_scene(const test::TempDir& dir, const std::string& name,
                             const std::string& events) {
  const std::string out = dir.file(name);
  const auto r = test::run_bkquake(
      {"run", scene(name), "--set", "run.events=" + events, "--out", out, "--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
  return read_histogram_csv(out + "/histogram.csv", 0, 0);
}

class CarlsonLangerWindow : public ::testing::TestWithParam<const char*> {};

TEST_P(CarlsonLangerWindow, AutomaticBAgreesWithTheWindowByEye) {
  test::TempDir dir;
  const MagnitudeHistogram h = run_scene(dir, GetParam(), "100000");
  const GrFit eye = fit_histogram(h, -7.6, -2.0);
  const GrFit f = fit_histogram(h, std::nullopt, std::nullopt);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  // Two combined errors: statistical of both, systematic of the automatic b.
  const double combined = std::sqrt(f.b_mle_err * f.b_mle_err + f.b_mle_sys_err * f.b_mle_sys_err +
                                    eye.b_mle_err * eye.b_mle_err);
  EXPECT_NEAR(f.b_mle, eye.b_mle, 2 * combined)
      << "automatic [" << f.mu_min << ", " << f.mu_max << ")";
  EXPECT_LE(f.b_mle_sys_err, 0.05);
  // In the power-law region: above the atom of one-block events (mu = -8.9) and its
  // few-block neighbours, below the bump (which peaks at mu ~ 4.2 at N = 100).
  EXPECT_GE(f.mu_min, -8.4 - 1e-9);
  EXPECT_LE(f.mu_min, -6.4 + 1e-9);
  EXPECT_LE(f.mu_max, 3.0 + 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Alpha, CarlsonLangerWindow,
                         ::testing::Values("cl-l10-a2-n100.ini", "cl-l10-a2.5-n100.ini",
                                           "cl-l10-a3-n100.ini"));

TEST(MoriKawamuraWindow, StaysBelowTheBumpWithAPositiveB) {
  test::TempDir dir;
  const MagnitudeHistogram h = run_scene(dir, "mori-kawamura-l3-n800-periodic.ini", "100000");
  const GrFit f = fit_histogram(h, std::nullopt, std::nullopt);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  EXPECT_GT(f.b_mle, 0.5);
  // D(mu) turns up again above mu ~ 0.8 (the bump peaks near 3.6).
  EXPECT_LE(f.mu_max, 1.2 + 1e-9);
  // Above the few-block bins, at the start of the power law (stability from -2.8 at
  // 10^5 events; the rule before 2026-11 took -4.0, inside the uneven bins).
  EXPECT_LE(f.mu_min, -2.6);
}

TEST(NoAcceptableWindow, SummaryGivesNoBAndSaysWhy) {
  test::TempDir dir;
  const std::string out = dir.file("ring");
  // On the ring's bump the number of events grows with magnitude: b_mle < 0 there.
  const auto r = test::run_bkquake({"run", scene("mori-kawamura-l3-n800-periodic.ini"), "--set",
                                    "run.events=20000", "--set", "stats.mu_min=0.2", "--set",
                                    "stats.mu_max=4", "--out", out, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string summary = test::read_file(out + "/summary.json");
  EXPECT_NE(summary.find("\"b_mle\": null"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"fit_error\": \"no acceptable fit window: b_mle = -"), std::string::npos)
      << summary;
  EXPECT_NE(r.out.find("b: not fitted (no acceptable fit window"), std::string::npos) << r.out;
}

TEST(NoAcceptableWindow, ARunOfOneEventSaysWhyItHasNoB) {
  test::TempDir dir;
  const std::string out = dir.file("one");
  const auto r = test::run_bkquake(
      {"run", "--set", "run.events=1", "--set", "run.transient_events=0", "--out", out, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string summary = test::read_file(out + "/summary.json");
  EXPECT_NE(summary.find("\"b_mle\": null"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"fit_error\": \"fewer than 2 events\""), std::string::npos) << summary;
  EXPECT_NE(r.out.find("b: not fitted (fewer than 2 events)"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace bkq
