// Every run measures its own accuracy indicators (the largest energy-balance residual of
// an event, the fastest mode's omega*dt, the largest event's share of
// run.max_steps_per_event) and puts them in summary.json; above the documented thresholds
// it prints one warning line per indicator naming it, its value, the threshold and what to
// change, and with run.accuracy = error it fails with exit 2, keeping its outputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"

namespace bkq {
namespace {

using test::read_file;
using test::run_bkquake;

std::vector<std::string> run_args(const std::vector<std::string>& scene, const std::string& out) {
  std::vector<std::string> a = {"run", "--quiet", "--out", out};
  a.insert(a.end(), scene.begin(), scene.end());
  return a;
}

// stderr lines that are accuracy warnings.
std::vector<std::string> warnings(const test::ProcessResult& r) {
  std::vector<std::string> w;
  for (const auto& line : r.err_lines())
    if (line.find("warning: accuracy") != std::string::npos) w.push_back(line);
  return w;
}

const std::vector<std::string> kAlpha100 = {
    "--set", "friction.alpha=100", "--set", "run.events=3000", "--set", "model.blocks=50"};
// The theta-method is stable at any omega*dt: l = 100 gives omega_max = 200, so dt = 0.1
// is omega*dt = 20.
const std::vector<std::string> kThetaCoarse = {
    "--set", "integrator.scheme=theta", "--set", "model.l=100",    "--set", "integrator.dt=0.1",
    "--set", "run.events=500",          "--set", "model.blocks=50"};

TEST(AccuracyCheck, DefaultSceneIsQuietAndReportsItsIndicators) {
  test::TempDir tmp;
  const auto r = run_bkquake(
      run_args({"--set", "run.events=2000", "--set", "model.blocks=50"}, tmp.file("out")));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(warnings(r).empty()) << r.err;
  const std::string summary = read_file(tmp.file("out/summary.json"));
  for (const char* f : {"\"accuracy\"", "\"energy_residual_max\"", "\"omega_dt\"",
                        "\"event_steps_max\"", "\"warnings\": []"})
    EXPECT_NE(summary.find(f), std::string::npos) << f << " missing in\n" << summary;
}

TEST(AccuracyCheck, AlphaHundredWarnsAboutTheEnergyResidual) {
  test::TempDir tmp;
  const auto r = run_bkquake(run_args(kAlpha100, tmp.file("out")));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto w = warnings(r);
  ASSERT_EQ(w.size(), 1u) << r.err;
  for (const char* part : {"energy_residual_max", "above 0.05", "integrator.dt"})
    EXPECT_NE(w[0].find(part), std::string::npos) << w[0] << " lacks " << part;
  EXPECT_NE(read_file(tmp.file("out/summary.json")).find("\"warnings\": [\"energy_residual_max\"]"),
            std::string::npos);
}

TEST(AccuracyCheck, ThetaAtOmegaDtTwentyWarns) {
  test::TempDir tmp;
  const auto r = run_bkquake(run_args(kThetaCoarse, tmp.file("out")));
  ASSERT_EQ(r.status, 0) << r.err;
  bool named = false;
  for (const auto& line : warnings(r))
    named = named || (line.find("omega_dt = 20") != std::string::npos &&
                      line.find("above 1") != std::string::npos &&
                      line.find("integrator.dt") != std::string::npos);
  EXPECT_TRUE(named) << r.err;
}

TEST(AccuracyCheck, ErrorModeFailsWithExitTwoAndKeepsTheOutputs) {
  for (const auto& scene : {kAlpha100, kThetaCoarse}) {
    test::TempDir tmp;
    std::vector<std::string> strict = scene;
    strict.insert(strict.end(), {"--set", "run.accuracy=error"});
    const auto r = run_bkquake(run_args(strict, tmp.file("out")));
    EXPECT_EQ(r.status, 2) << r.err;
    const auto lines = r.err_lines();
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_NE(lines[0].find("error: accuracy"), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("run.accuracy"), std::string::npos) << lines[0];
    for (const char* f : {"catalog.csv", "histogram.csv", "summary.json", "scene.ini"})
      EXPECT_TRUE(std::filesystem::exists(tmp.file(std::string("out/") + f))) << f;
  }
}

TEST(AccuracyCheck, ContinuousRunsReportOmegaDtToo) {
  test::TempDir tmp;
  const auto r = run_bkquake(run_args(
      {"--set", "drive.mode=continuous", "--set", "integrator.scheme=theta", "--set", "model.l=100",
       "--set", "integrator.dt=0.1", "--set", "model.blocks=20", "--set", "run.duration=100"},
      tmp.file("out")));
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(warnings(r).size(), 1u) << r.err;
  EXPECT_NE(warnings(r)[0].find("omega_dt"), std::string::npos);
  EXPECT_NE(read_file(tmp.file("out/summary.json")).find("\"omega_dt\": 20"), std::string::npos);
}

}  // namespace
}  // namespace bkq
