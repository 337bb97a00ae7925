// The automatic fit window on real catalogues, 10^5 events each (under a
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
#include <vector>

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

// On the shipped scenes at the sizes a user runs first, the automatic
// window never takes in a gap of empty bins or the rise into the bump, and passes the
// goodness-of-fit test; or there is no b, with the reason. The window is checked by
// fitting it again as a given window, which warns of a gap, a rise or a failed test.
struct SceneCase {
  const char* name;
  const char* scene;  // empty: the built-in default
  const char* events;
  const char* transient;
  std::vector<std::string> sets;
};

class ShippedSceneWindow : public ::testing::TestWithParam<SceneCase> {};

TEST_P(ShippedSceneWindow, StopsBelowGapsAndRisesOrGivesNoB) {
  const SceneCase c = GetParam();
  test::TempDir dir;
  const std::string out = dir.file("run");
  std::vector<std::string> args{"run"};
  if (*c.scene) args.push_back(scene(c.scene));
  for (const std::string& s :
       {std::string("run.events=") + c.events, std::string("run.transient_events=") + c.transient})
    args.insert(args.end(), {"--set", s});
  for (const auto& s : c.sets) args.insert(args.end(), {"--set", s});
  args.insert(args.end(), {"--out", out, "--quiet"});
  const auto r = test::run_bkquake(args);
  ASSERT_EQ(r.status, 0) << r.err;
  const MagnitudeHistogram h = read_histogram_csv(out + "/histogram.csv", 0, 0);
  const GrFit f = fit_histogram(h, std::nullopt, std::nullopt);
  const std::string summary = test::read_file(out + "/summary.json");
  if (!f.b_ok) {
    EXPECT_FALSE(f.no_b_reason.empty());
    EXPECT_NE(summary.find("\"fit_error\": \"no acceptable fit window: "), std::string::npos);
    return;
  }
  EXPECT_TRUE(f.warnings.empty());
  // No gap or rise inside: the same window given by hand is not warned about either (of
  // the goodness of fit only, when it differs: a given top truncates the likelihood, the
  // automatic window up to the largest event does not); the automatic one passes the test.
  const GrFit again = fit_histogram(h, f.mu_min, f.mu_max);
  for (const auto& w : again.warnings)
    EXPECT_NE(w.find("fails the goodness-of-fit test"), std::string::npos)
        << c.name << " [" << f.mu_min << ", " << f.mu_max << "): " << w;
  EXPECT_LE(f.ks_distance, 0.03 + 0.5 / std::sqrt(static_cast<double>(f.n_in_window)));
  // The reason the window ends, and the bootstrap error, reach summary.json.
  EXPECT_NE(summary.find("\"mu_max_reason\": \"" + f.mu_max_reason + "\""), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("\"b_mle_boot_err\": "), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, ShippedSceneWindow,
    ::testing::Values(
        SceneCase{"default", "", "20000", "2000", {}},
        SceneCase{"cl_a1", "cl-l10-a1-n100.ini", "20000", "5000", {}},
        SceneCase{"cl_a3", "cl-l10-a3-n100.ini", "20000", "5000", {}},
        SceneCase{"ring", "mori-kawamura-l3-n800-periodic.ini", "20000", "10000", {}},
        SceneCase{"lattice32_power", "lattice/bk-power3-r4-l3-a2-32x32.ini", "20000", "10000", {}},
        SceneCase{"ofc64", "lattice/ofc-relaxation-64.ini", "30000", "200000", {}}),
    [](const auto& info) { return std::string(info.param.name); });

// The 64 x 64 nearest-neighbour lattice scene (2 * 10^4 events after 2 * 10^4 transient): D(mu) has
// 27 empty bins between its scaling region and the bump. The window stopped at 7.6, across the gap
// and the bump (b = 1.305 at 3 * 10^4 events); it now ends below the gap.
TEST(WindowOnScenesItOnceFailed, LatticeWindowEndsBelowTheGap) {
  test::TempDir dir;
  const std::string out = dir.file("lattice");
  const auto r = test::run_bkquake({"run", scene("lattice/bk-nearest-l3-a2-64x64.ini"), "--set",
                                    "run.transient_events=20000", "--set", "run.events=20000",
                                    "--out", out, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const MagnitudeHistogram h = read_histogram_csv(out + "/histogram.csv", 0, 0);
  const GrFit f = fit_histogram(h, std::nullopt, std::nullopt);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  EXPECT_EQ(f.mu_max_reason, "gap");
  EXPECT_LE(f.mu_max, 0.4 + 1e-9);
  // The given window across the gap is fitted and warned about.
  const GrFit across = fit_histogram(h, -5.6, 7.6);
  bool gap = false;
  for (const auto& w : across.warnings) gap = gap || w.find("crosses a gap") != std::string::npos;
  EXPECT_TRUE(gap) << ::testing::PrintToString(across.warnings);
  // tau of the blocks that slipped is in summary.json.
  const std::string summary = test::read_file(out + "/summary.json");
  EXPECT_NE(summary.find("\"tau\": {"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"measure\": \"blocks\""), std::string::npos) << summary;
}

// fit --measure: an OFC run's topplings get tau with its error, range and
// goodness of fit, printed and in the JSON; a measure the catalogue lacks, or an unknown
// one, is refused with what is allowed.
TEST(FitMeasure, TopplingsOfAnOfcRunHaveTau) {
  test::TempDir dir;
  const std::string out = dir.file("ofc");
  const auto r =
      test::run_bkquake({"run", scene("lattice/ofc-relaxation-64.ini"), "--set", "run.events=20000",
                         "--set", "run.transient_events=200000", "--out", out, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string json = dir.file("fit.json");
  const auto fit = test::run_bkquake({"fit", out, "--measure", "topplings", "--json", json});
  ASSERT_EQ(fit.status, 0) << fit.err;
  EXPECT_NE(fit.out.find("tau (MLE)"), std::string::npos) << fit.out;
  const std::string j = test::read_file(json);
  EXPECT_NE(j.find("\"tau\": {"), std::string::npos) << j;
  EXPECT_NE(j.find("\"measure\": \"topplings\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"x_min\": "), std::string::npos);
  EXPECT_NE(j.find("\"vs_lognormal\": "), std::string::npos);
  // The run's own summary carries the same measure's tau.
  const std::string summary = test::read_file(out + "/summary.json");
  EXPECT_NE(summary.find("\"measure\": \"topplings\""), std::string::npos) << summary;

  const auto bad = test::run_bkquake({"fit", out, "--measure", "energy"});
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.err.find("expected one of moment, blocks, topplings, area, duration"),
            std::string::npos)
      << bad.err;
  const std::string chain = dir.file("chain");
  ASSERT_EQ(test::run_bkquake({"run", "--set", "run.events=500", "--out", chain, "--quiet"}).status,
            0);
  const auto none = test::run_bkquake({"fit", chain, "--measure", "topplings"});
  EXPECT_NE(none.status, 0);
  EXPECT_NE(none.err.find("has no topplings column"), std::string::npos) << none.err;
}

// The Mori-Kawamura ring scene at 2 * 10^5 events (about 5 s): D(mu) falls as one power
// law from about -3.8 to -1 before the dip and bump. The automatic fit gave no b ("no lower
// cut keeps b stable"); the lower cut found on windows up to the departure gives it, in
// 0.75-1.0 (0.88 on [-3.8, -1) by hand; 0.80 in earlier versions).
TEST(WindowOnScenesItOnceFailed, MoriKawamuraRingHasItsB) {
  test::TempDir dir;
  const MagnitudeHistogram h = run_scene(dir, "mori-kawamura-l3-n800-periodic.ini", "200000");
  const GrFit f = fit_histogram(h, std::nullopt, std::nullopt);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  EXPECT_GE(f.b_mle, 0.75);
  EXPECT_LE(f.b_mle, 1.0);
  EXPECT_LE(f.mu_max, 0.4 + 1e-9);  // below the dip and the rise into the bump
  EXPECT_LE(f.mu_min, -3.0 + 1e-9);
}

// A chain of 1000 blocks with range-10 coupling (2 * 10^4 events after 2 * 10^4
// transient): the window was [-7.4, 7.0), through the characteristic events above 4.8; it
// now ends below the gap that separates them.
TEST(WindowOnScenesItOnceFailed, RangeCoupledChainStopsBelowTheCharacteristicEvents) {
  test::TempDir dir;
  const std::string out = dir.file("r10");
  const auto r =
      test::run_bkquake({"run", "--set", "model.blocks=1000", "--set", "model.coupling=range",
                         "--set", "model.range=10", "--set", "run.events=20000", "--set",
                         "run.transient_events=20000", "--out", out, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const MagnitudeHistogram h = read_histogram_csv(out + "/histogram.csv", 0, 0);
  const GrFit f = fit_histogram(h, std::nullopt, std::nullopt);
  ASSERT_TRUE(f.b_ok) << f.no_b_reason;
  EXPECT_LE(f.mu_max, 2.0);
  EXPECT_EQ(f.mu_max_reason, "gap");
}

}  // namespace
}  // namespace bkq
