// Segment statistics (thesis eqs. 4.1-4.4): synthetic signals with known mean, amplitude
// and block errors; the last-half rule; segments.csv of real runs against the schedule and
// against the time series sampled at every step.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "app/observers/segments.hpp"
#include "app/run.hpp"
#include "io/segments_csv.hpp"
#include "stats/segment_stats.hpp"

namespace bkq {
namespace {

TEST(SegmentStats, SineOverWholePeriodsGivesOffsetAndAmplitude) {
  const double a = 2.5, c = -7.25;
  const int per_period = 97, periods = 40;
  BlockedMoments m(per_period * periods, 4);
  for (int i = 0; i < per_period * periods; ++i)
    m.add(c + a * std::sin(2 * std::numbers::pi * i / per_period + 0.3));
  const SegmentStat s = m.result();
  EXPECT_NEAR(s.mean, c, 1e-6);
  EXPECT_NEAR(s.amp, a, 1e-6);
  // Each block holds 10 whole periods: the same mean and amplitude, so no error.
  EXPECT_NEAR(s.mean_err, 0.0, 1e-9);
  EXPECT_NEAR(s.amp_err, 0.0, 1e-9);
}

TEST(SegmentStats, ConstantHasNoAmplitudeAndNoError) {
  BlockedMoments m(1001, 4);
  for (int i = 0; i < 1001; ++i) m.add(3.75);
  const SegmentStat s = m.result();
  EXPECT_EQ(s.mean, 3.75);
  EXPECT_EQ(s.amp, 0.0);
  EXPECT_EQ(s.mean_err, 0.0);
  EXPECT_EQ(s.amp_err, 0.0);
}

TEST(SegmentStats, EqualBlocksHaveZeroErrorAndUnequalOnesFollowEq43) {
  // The same pattern in each of M = 5 blocks: no error.
  const std::vector<double> pattern = {1.0, -2.0, 4.0, 0.5};
  BlockedMoments equal(20, 5);
  for (int b = 0; b < 5; ++b)
    for (double x : pattern) equal.add(x);
  EXPECT_NEAR(equal.result().mean_err, 0.0, 1e-12);
  EXPECT_NEAR(equal.result().amp_err, 0.0, 1e-12);
  // Blocks of constants 0, 2, 4, 6 (M = 4): block means Y_j, whole mean 3, sigma^2 = 5,
  // eps = sqrt(5)/2; each block's amplitude is 0 about its own mean, the whole one is
  // sqrt(2 * 5), so the amplitude error is sqrt(10)/2.
  BlockedMoments steps(8, 4);
  for (double x : {0.0, 0.0, 2.0, 2.0, 4.0, 4.0, 6.0, 6.0}) steps.add(x);
  const SegmentStat s = steps.result();
  EXPECT_NEAR(s.mean, 3.0, 1e-12);
  EXPECT_NEAR(s.mean_err, std::sqrt(5.0) / 2.0, 1e-12);
  EXPECT_NEAR(s.amp, std::sqrt(10.0), 1e-12);
  EXPECT_NEAR(s.amp_err, std::sqrt(10.0) / 2.0, 1e-12);
}

TEST(SegmentStats, RemainderGoesToTheLastBlock) {
  // n = 10, M = 4: blocks of 2, 2, 2 and 4. Values 0 0 | 0 0 | 0 0 | 1 1 1 1: the last block
  // alone has mean 1, so the block means are 0, 0, 0, 1 around the whole mean 0.4.
  BlockedMoments m(10, 4);
  for (int i = 0; i < 10; ++i) m.add(i >= 6 ? 1.0 : 0.0);
  const SegmentStat s = m.result();
  EXPECT_NEAR(s.mean, 0.4, 1e-12);
  const double var = (3 * 0.4 * 0.4 + 0.6 * 0.6) / 4.0;
  EXPECT_NEAR(s.mean_err, std::sqrt(var) / 2.0, 1e-12);
}

TEST(SegmentStats, LastHalfRuleTakesExactlyTheSecondHalf) {
  // (5, 10] at dt = 1: steps 6..10.
  StepRange r = input_steps(0.0, 10.0, 1.0);
  EXPECT_EQ(r.first, 6);
  EXPECT_EQ(r.last, 10);
  // A segment from 2000 to 4000 at dt = 0.005: times in (3000, 4000].
  r = input_steps(2000.0, 4000.0, 0.005);
  EXPECT_EQ(r.first, 600001);
  EXPECT_EQ(r.last, 800000);
  EXPECT_EQ(r.count(), 200000);
  // An odd span: (1.5, 3] at dt = 1 holds steps 2 and 3.
  r = input_steps(0.0, 3.0, 1.0);
  EXPECT_EQ(r.first, 2);
  EXPECT_EQ(r.last, 3);
}

TEST(SegmentStats, SpansFollowTheSchedule) {
  DriveSettings d;
  d.schedule = Schedule::Steps;
  d.speed = 0.1;
  d.step_increment = 0.05;
  d.step_interval = 10;
  const auto spans = segment_spans(d, 35);
  ASSERT_EQ(spans.size(), 4u);
  EXPECT_DOUBLE_EQ(spans[3].t_start, 30);
  EXPECT_DOUBLE_EQ(spans[3].t_end, 35);
  EXPECT_DOUBLE_EQ(spans[2].speed, 0.2);
  d.schedule = Schedule::Ramp;
  EXPECT_TRUE(segment_spans(d, 35).empty());
  d.schedule = Schedule::Constant;
  ASSERT_EQ(segment_spans(d, 35).size(), 1u);
}

RunRequest thesis_run(const std::vector<std::pair<std::string, std::string>>& keys,
                      const std::string& out) {
  RunRequest req;
  const std::vector<std::pair<std::string, std::string>> base = {
      {"model.kind", "bkp"},        {"model.parameterisation", "thesis"},
      {"model.blocks", "10"},       {"friction.law", "thesis"},
      {"drive.mode", "continuous"}, {"integrator.scheme", "rk2"},
      {"integrator.dt", "0.005"},   {"run.initial_disorder", "0.75"},
      {"model.pad_mass", "10"},     {"model.caliper_stiffness", "10"},
  };
  for (const auto& [k, v] : base) req.scene.set(k, v);
  for (const auto& [k, v] : keys) req.scene.set(k, v);
  req.scene.validate();
  req.out_dir = out;
  req.quiet = true;
  return req;
}

TEST(SegmentStats, StepsRunHasTheScheduleSpeedsAndTheTimeSeriesStatistics) {
  test::TempDir dir;
  const std::string out = dir.file("run");
  ASSERT_EQ(run_scene(thesis_run({{"drive.schedule", "steps"},
                                  {"drive.speed", "0.05"},
                                  {"drive.step_increment", "0.1"},
                                  {"drive.step_interval", "20"},
                                  {"run.duration", "70"},
                                  {"output.every", "0.005"}},
                                 out)),
            0);
  const auto rows = read_segments_csv(out + "/segments.csv");
  ASSERT_EQ(rows.size(), 4u);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].segment, static_cast<std::int64_t>(k));
    EXPECT_NEAR(rows[k].speed, 0.05 + 0.1 * static_cast<double>(k), 1e-12);
    EXPECT_DOUBLE_EQ(rows[k].t_start, 20.0 * static_cast<double>(k));
  }
  EXPECT_DOUBLE_EQ(rows[3].t_end, 70.0);
  // The time series holds every step: the statistics of its rows in (t_mid, t_end] must be
  // those of segments.csv (same values, summed in another order).
  const auto ts = read_numeric_columns(out + "/timeseries.csv", {"t", "pad_friction", "pad_x"});
  for (const SegmentRow& r : rows) {
    const double mid = 0.5 * (r.t_start + r.t_end);
    double sum = 0, sum_x = 0;
    int n = 0;
    for (std::size_t i = 0; i < ts[0].size(); ++i) {
      if (ts[0][i] > mid + 1e-9 && ts[0][i] <= r.t_end + 1e-9) {
        sum += ts[1][i];
        sum_x += ts[2][i];
        ++n;
      }
    }
    ASSERT_GT(n, 0);
    double var = 0;
    for (std::size_t i = 0; i < ts[0].size(); ++i)
      if (ts[0][i] > mid + 1e-9 && ts[0][i] <= r.t_end + 1e-9)
        var += (ts[1][i] - sum / n) * (ts[1][i] - sum / n);
    EXPECT_NEAR(r.stats[0].mean, sum / n, 1e-9 * (1 + std::abs(sum / n)));
    EXPECT_NEAR(r.stats[0].amp, std::sqrt(2 * var / n), 1e-9 * (1 + r.stats[0].amp));
    EXPECT_NEAR(r.stats[1].mean, sum_x / n, 1e-9);
  }
  EXPECT_NE(test::read_file(out + "/summary.json").find("\"segments\": 4"), std::string::npos);
}

TEST(BlockTrajectories, ChosenBlocksWithVelocitiesThatMatchThePositions) {
  test::TempDir dir;
  const std::string out = dir.file("run");
  ASSERT_EQ(run_scene(thesis_run({{"drive.schedule", "constant"},
                                  {"drive.speed", "0.1"},
                                  {"run.duration", "20"},
                                  {"output.every", "0.005"},
                                  {"output.blocks", "true"},
                                  {"output.block_first", "2"},
                                  {"output.block_count", "3"}},
                                 out)),
            0);
  const std::string csv = test::read_file(out + "/blocks.csv");
  ASSERT_EQ(csv.substr(0, csv.find('\n')), "t,u2,u3,u4,v2,v3,v4");
  const auto c = read_numeric_columns(out + "/blocks.csv", {"t", "u3", "v3"});
  // Lab-frame velocity against the positions' finite differences (trapezoid rule).
  ASSERT_GT(c[0].size(), 100u);
  double worst = 0;
  for (std::size_t i = 0; i + 1 < c[0].size(); ++i) {
    const double h = c[0][i + 1] - c[0][i];
    const double fd = (c[1][i + 1] - c[1][i]) / h;
    worst = std::max(worst, std::abs(fd - 0.5 * (c[2][i] + c[2][i + 1])));
  }
  // (Stick transitions make the velocity jump within a step; a frame error would be 0.1.)
  EXPECT_LT(worst, 0.01);
  // Stuck at the start: the block moves with the substrate, u' = -v.
  EXPECT_DOUBLE_EQ(c[2][0], -0.1);
}

TEST(SegmentStats, RampWritesNoSegmentsAndSaysSo) {
  test::TempDir dir;
  const std::string out = dir.file("run");
  ASSERT_EQ(run_scene(thesis_run({{"drive.schedule", "ramp"},
                                  {"drive.ramp_from", "0.1"},
                                  {"drive.ramp_to", "0.2"},
                                  {"drive.ramp_duration", "5"},
                                  {"run.duration", "5"}},
                                 out)),
            0);
  EXPECT_FALSE(std::filesystem::exists(out + "/segments.csv"));
  EXPECT_NE(test::read_file(out + "/summary.json").find("a ramp has no speed segments"),
            std::string::npos);
}

}  // namespace
}  // namespace bkq
