// The work–precision study (app/accuracy.hpp, `bkquake accuracy`) on a small chain:
// errors shrink with dt and with the scheme's order, the adaptive reference beats the
// fixed-step schemes, a dt above the stability limit is kept and marked, the table and
// accuracy.csv carry every point, and the command refuses bad options.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../cli_helpers.hpp"
#include "../scene_sim.hpp"
#include "app/accuracy.hpp"
#include "core/error.hpp"

namespace bkq {
namespace {

const AccuracyPoint& point(const AccuracyStudy& s, const std::string& scheme, double dt,
                           double tol = 0) {
  for (const AccuracyPoint& p : s.points)
    if (p.scheme == scheme && p.dt == dt && p.tolerance == tol) return p;
  throw std::runtime_error("no point " + scheme);
}

TEST(Accuracy, SmallStudyOrdersTheSchemesAndKeepsUnstablePoints) {
  const Scene scene = test::make_scene({{"model.blocks", "30"}, {"run.transient_events", "300"}});
  AccuracyOptions opt;
  opt.schemes = {"rk2", "rk4", "theta", "adaptive"};
  opt.dts = {0.05, 0.02, 0.005};
  opt.tolerances = {1e-8};
  opt.samples = 12;
  opt.sample_spacing = 10;
  opt.long_events = 400;
  const AccuracyStudy study = run_accuracy(scene, opt);
  // rk2 and rk4 in both transition modes, theta once, adaptive once.
  ASSERT_EQ(study.points.size(), 2u + 2 * 2 * 3 + 3 + 1);
  EXPECT_EQ(study.points[0].scheme, "reference");
  EXPECT_EQ(study.points[0].ks_distance, 0.0);
  EXPECT_EQ(study.points[1].scheme, "noise-floor");
  EXPECT_GT(study.points[1].ks_distance, 0.0);  // another seed: a different sample

  // rk2 at dt 0.05 is beyond its limit (0.5 / omega_max = 0.025): kept, marked, not run.
  const AccuracyPoint& rk2_big = point(study, "rk2", 0.05);
  EXPECT_EQ(rk2_big.status, "unstable");
  EXPECT_NE(rk2_big.note.find("stability limit"), std::string::npos);
  EXPECT_EQ(rk2_big.sampled, 0);

  for (const char* scheme : {"rk2", "rk4", "theta"}) {
    const AccuracyPoint& coarse = point(study, scheme, 0.02);
    const AccuracyPoint& fine = point(study, scheme, 0.005);
    ASSERT_EQ(coarse.status, "ok") << scheme << ": " << coarse.note;
    ASSERT_EQ(fine.status, "ok") << scheme << ": " << fine.note;
    EXPECT_EQ(fine.sampled, 12);
    // Smaller dt: smaller per-event error, more time per event.
    EXPECT_LT(fine.moment_error_median, coarse.moment_error_median) << scheme;
    EXPECT_GT(fine.steps_per_event, 2 * coarse.steps_per_event) << scheme;
  }
  const AccuracyPoint& adaptive = point(study, "adaptive", scene.real("integrator.dt"), 1e-8);
  ASSERT_EQ(adaptive.status, "ok") << adaptive.note;
  EXPECT_LT(adaptive.moment_error_median, point(study, "rk4", 0.005).moment_error_median);
  EXPECT_LT(adaptive.moment_error_max, 1e-4);

  const std::string csv = accuracy_csv(study);
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')),
            study.points.size() + 1);
  EXPECT_EQ(csv.rfind("scheme,transitions,dt,tolerance,status,", 0), 0u);
  EXPECT_NE(accuracy_table(study).find("unstable"), std::string::npos);

  // Located transitions: the same ladder, and at the finest dt a smaller error than the step.
  for (const char* scheme : {"rk2", "rk4"}) {
    const AccuracyPoint* step = nullptr;
    const AccuracyPoint* located = nullptr;
    for (const AccuracyPoint& p : study.points)
      if (p.scheme == scheme && p.dt == 0.005) (p.transitions == "step" ? step : located) = &p;
    ASSERT_TRUE(step && located) << scheme;
    ASSERT_EQ(located->status, "ok") << located->note;
    EXPECT_LT(located->moment_error_median, step->moment_error_median) << scheme;
    // rk4's durations too; rk2's stick time is its velocity error over the small deceleration
    // at a stick (sigma), which at this dt is still larger than the step's quantisation.
    if (std::string(scheme) == "rk4") {
      EXPECT_LT(located->duration_error_median, step->duration_error_median) << scheme;
    }
  }
  // One observed order per scheme, mode, quantity and event set: rk2 and rk4 twice, theta.
  ASSERT_EQ(study.orders.size(), (2u * 2 + 1) * 4);
  EXPECT_EQ(study.orders[0].scheme, "rk2");
  EXPECT_EQ(study.orders[0].transitions, "step");
  EXPECT_EQ(study.orders[0].quantity, "moment");
  EXPECT_EQ(study.orders[0].events, "all");
  const std::string orders = accuracy_orders_csv(study);
  EXPECT_EQ(orders.rfind("scheme,transitions,quantity,events,order,", 0), 0u);
  EXPECT_EQ(static_cast<std::size_t>(std::count(orders.begin(), orders.end(), '\n')),
            study.orders.size() + 1);
}

// The observed order is the least-squares slope over the points above 10x the floor.
TEST(Accuracy, ObservedOrderIsTheSlopeAboveTheFloor) {
  AccuracyStudy study;
  for (double dt : {0.04, 0.02, 0.01, 0.005}) {
    AccuracyPoint p;
    p.scheme = "rk4";
    p.transitions = "located";
    p.dt = dt;
    p.sampled = 10;
    p.moment_error_median = 3.0 * std::pow(dt, 4);  // exactly 4th order
    p.duration_error_median = std::max(0.1 * dt, 1e-3);
    p.sampled_single = 0;
    p.moment_error_median_single = p.duration_error_median_single = std::nan("");
    study.points.push_back(p);
  }
  ReferenceFloor floor{1e-9, std::nan(""), 1e-5, std::nan("")};
  fit_orders(study, floor);
  ASSERT_EQ(study.orders.size(), 4u);
  // 3 * 0.005^4 = 1.9e-9 is within 10x of the floor 1e-9: left out.
  EXPECT_EQ(study.orders[0].points, 3);
  EXPECT_NEAR(study.orders[0].order, 4.0, 1e-12);
  EXPECT_EQ(study.orders[0].dt_min, 0.01);
  EXPECT_EQ(study.orders[1].points, 0);  // no single-block events
  EXPECT_TRUE(std::isnan(study.orders[1].order));
  // Durations: 0.004, 0.002, 0.001 (and the 1e-3 clamp at 0.005, equal: slope over three
  // points and a flat one is below 1).
  EXPECT_EQ(study.orders[2].points, 4);
  EXPECT_LT(study.orders[2].order, 1.0);
  EXPECT_GT(study.orders[2].order, 0.5);
}

TEST(Accuracy, BinnedKolmogorovSmirnovDistance) {
  MagnitudeHistogram a(0.5), b(0.5);
  for (double mu : {-1.0, -0.2, 0.3, 1.1}) a.add(mu);
  EXPECT_EQ(ks_binned(a, a), 0.0);
  for (double mu : {1.2, 1.3, 1.4, 1.6}) b.add(mu);
  // Three of a's four events lie below all of b's.
  EXPECT_DOUBLE_EQ(ks_binned(a, b), 0.75);
}

TEST(AccuracyProgram, RefusesBadOptionsAndWritesTheTable) {
  test::TempDir dir;
  const auto bad = test::run_process(
      BKQUAKE_BINARY, {"accuracy", "--schemes", "rk4,euler", "--out", dir.path().string()});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("euler"), std::string::npos) << bad.err;
  const auto bad_dt = test::run_process(
      BKQUAKE_BINARY, {"accuracy", "--dt", "0.01,-1", "--out", dir.path().string()});
  EXPECT_EQ(bad_dt.status, 2);
  EXPECT_NE(bad_dt.err.find("--dt"), std::string::npos) << bad_dt.err;

  const std::vector<std::string> args = {"accuracy",
                                         "--set",
                                         "model.blocks=20",
                                         "--schemes",
                                         "rk4",
                                         "--dt",
                                         "0.01",
                                         "--samples",
                                         "3",
                                         "--long-events",
                                         "200",
                                         "--quiet",
                                         "--out",
                                         dir.path().string()};
  const auto ok = test::run_process(BKQUAKE_BINARY, args);
  ASSERT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find("rk4"), std::string::npos);
  std::ifstream csv(dir.file("accuracy.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("scheme,transitions,dt,", 0), 0u);
  std::ifstream orders(dir.file("accuracy_orders.csv"));
  std::string orders_header;
  std::getline(orders, orders_header);
  EXPECT_EQ(orders_header.rfind("scheme,transitions,quantity,", 0), 0u);
  EXPECT_TRUE(std::ifstream(dir.file("scene.ini")).good());
  // A second run does not overwrite the table without --force.
  const auto again = test::run_process(BKQUAKE_BINARY, args);
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
}

// --samples and --spacing have finite ranges (each sample is relaxed by every scheme and
// the reference; samples x spacing events are run first): outside them, one error line,
// exit 2, and the output folder is not touched. run_accuracy checks the same.
TEST(Accuracy, SamplesAndSpacingHaveFiniteRanges) {
  test::TempDir dir;
  const std::string out = dir.file("out");
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
      {{"--samples", "10001"}, "accuracy: --samples: expected an integer in [1, 10000], got 10001"},
      {{"--samples", "0"}, "accuracy: --samples: expected an integer in [1, 10000], got 0"},
      {{"--spacing", "100001"},
       "accuracy: --spacing: expected an integer in [1, 100000], got 100001"},
      {{"--spacing", "-3"}, "accuracy: --spacing: expected an integer in [1, 100000], got -3"},
      {{"--samples", "2147483648"}, "--samples"},  // beyond int: boost's one-line refusal
  };
  for (const auto& [options, message] : bad) {
    std::vector<std::string> args = {"accuracy", "--quiet", "--out", out};
    args.insert(args.end(), options.begin(), options.end());
    const auto r = test::run_bkquake(args);
    EXPECT_EQ(r.status, 2) << options[0] << " " << options[1];
    EXPECT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << "refused before the folder is made";
  }
  AccuracyOptions opt;
  opt.samples = kMaxAccuracySamples + 1;
  EXPECT_THROW(run_accuracy(Scene(), opt), Error);
  opt.samples = kMaxAccuracySamples;
  opt.sample_spacing = kMaxAccuracySpacing;
  EXPECT_NO_THROW(check_accuracy_options(opt));
}

}  // namespace
}  // namespace bkq
