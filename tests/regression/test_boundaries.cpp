// Every number that enters bkquake is checked where it enters:
// a scene key or a command-line option that is not finite, outside its declared sane range,
// or that would overflow a step counter or drive the substrate backwards exits 2 with one
// line naming it, before any work (the fit used to loop for ever on stats.mu_min = -1e300,
// and run.duration = 1e23 gave a negative step count). Each case runs under a time limit,
// so a regression fails here instead of hanging the suite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"

namespace bkq {
namespace {

// The shared refusal check, not hung, and the line is bkquake's error line.
void expect_refused_promptly(const test::ProcessResult& r, const std::vector<std::string>& parts) {
  EXPECT_FALSE(r.timed_out) << "hung";
  test::expect_refused(r, parts);
  const auto lines = r.err_lines();
  if (lines.size() == 1) {
    EXPECT_EQ(lines[0].rfind("bkquake: error: ", 0), 0u) << lines[0];
  }
}

// `bkquake run` of a short scene with `sets` as --set overrides, under a time limit.
test::ProcessResult run_with(const std::vector<std::string>& sets) {
  test::TempDir tmp;
  std::vector<std::string> args = {"run", "--quiet", "--set", "model.blocks=10"};
  if (std::find(sets.begin(), sets.end(), "drive.mode=continuous") == sets.end())
    args.insert(args.end(), {"--set", "run.events=200", "--set", "run.transient_events=10"});
  for (const auto& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  args.push_back("--out");
  args.push_back(tmp.file("out"));
  return test::run_bkquake_for(30, args);
}

TEST(Boundaries, FitWindowKeysOutsideMinusFiftyFiftyOrNotFinite) {
  expect_refused_promptly(run_with({"stats.mu_min=-1e300"}),
                          {"stats.mu_min", "-1e300", "[-50, 50]"});
  expect_refused_promptly(run_with({"stats.mu_max=1e300"}), {"stats.mu_max", "1e300", "[-50, 50]"});
  expect_refused_promptly(run_with({"stats.mu_max=50.5"}), {"stats.mu_max", "[-50, 50]"});
  for (const char* bad : {"nan", "inf", "-inf", "NaN", "1e999"})
    expect_refused_promptly(run_with({std::string("stats.mu_min=") + bad}), {"stats.mu_min", bad});
}

TEST(Boundaries, EveryNumericKeyDeclaresAFiniteRange) {
  for (const auto& p : parameter_table()) {
    if (p.type != ParamType::Real && p.type != ParamType::Integer) continue;
    EXPECT_TRUE(p.has_min && p.has_max) << p.key << " is declared without a finite range";
  }
}

TEST(Boundaries, HugeButFiniteValuesAreRefusedAtTheBoundary) {
  expect_refused_promptly(run_with({"model.parameterisation=thesis", "model.pad_mass=1e300"}),
                          {"model.pad_mass", "1e300"});
  expect_refused_promptly(run_with({"integrator.dt=1e300"}), {"integrator.dt", "1e300"});
  expect_refused_promptly(run_with({"run.checkpoint_seconds=1e300"}), {"run.checkpoint_seconds"});
  expect_refused_promptly(run_with({"run.events=1e23"}), {"run.events", "1e23"});
  expect_refused_promptly(run_with({"run.events=99999999999999999999"}),
                          {"run.events", "too large"});
}

TEST(Boundaries, DurationsBeyondWhatTheStepCounterHolds) {
  expect_refused_promptly(run_with({"drive.mode=continuous", "run.duration=1e23"}),
                          {"run.duration", "1e23"});
  expect_refused_promptly(
      run_with({"drive.mode=continuous", "run.duration=1e15", "integrator.dt=0.001"}),
      {"run.duration = 1e+15", "integrator.dt = 0.001", "time steps", "1e15"});
}

TEST(Boundaries, StepsScheduleThatWouldDriveTheSubstrateBackwardsIsRefused) {
  // 0.01, 0.005, 0, -0.005: the fourth step (t = 6000) would run backwards.
  const std::vector<std::string> steps = {"drive.mode=continuous", "drive.schedule=steps",
                                          "drive.speed=0.01", "drive.step_increment=-0.005",
                                          "drive.step_interval=2000"};
  auto bad = steps;
  bad.push_back("run.duration=7000");
  expect_refused_promptly(run_with(bad), {"drive.step_increment = -0.005", "at step 3", "time 6000",
                                          "backwards", "run.duration = 7000"});
  // A decreasing schedule that stays at or above zero is fine.
  auto good = steps;
  good.insert(good.end(), {"run.duration=5000", "integrator.dt=0.05", "output.every=50"});
  const auto r = run_with(good);
  EXPECT_EQ(r.status, 0) << r.err;
  // Speeds above drive.speed's range are refused the same way.
  expect_refused_promptly(
      run_with({"drive.mode=continuous", "drive.schedule=steps", "drive.step_increment=1e6",
                "drive.step_interval=1", "run.duration=10"}),
      {"drive.step_increment = 1e+06", "out of [0, 1e+06]", "at step 1"});
}

TEST(Boundaries, FitOptionsAreCheckedLikeTheirSceneKeys) {
  test::TempDir tmp;
  std::string catalog = "event,moment\n";
  for (int i = 1; i <= 300; ++i)
    catalog += std::to_string(i) + "," + std::to_string(1.0 + i) + "\n";
  const std::string path = tmp.write("catalog.csv", catalog);
  for (const char* v : {"nan", "1e308", "-1e300", "inf"}) {
    expect_refused_promptly(test::run_bkquake_for(30, {"fit", path, "--mu-min", v}),
                            {"fit: --mu-min", v, "[-50, 50]"});
    expect_refused_promptly(test::run_bkquake_for(30, {"fit", path, "--mu-max", v}),
                            {"fit: --mu-max", v, "[-50, 50]"});
  }
  expect_refused_promptly(test::run_bkquake_for(30, {"fit", path, "--bin-width", "nan"}),
                          {"fit: --bin-width", "nan", "(0, 10]"});
  expect_refused_promptly(test::run_bkquake_for(30, {"fit", path, "--blocks", "0"}),
                          {"fit: --blocks", "[1, 10000000]"});
  const auto ok = test::run_bkquake_for(30, {"fit", path, "--mu-min", "auto", "--mu-max", "6"});
  EXPECT_EQ(ok.status, 0) << ok.err;
}

TEST(Boundaries, AccuracyOptionsAreCheckedLikeTheirSceneKeys) {
  test::TempDir tmp;
  expect_refused_promptly(
      test::run_bkquake_for(30, {"accuracy", "--dt", "0.01,nan", "--out", tmp.file("a")}),
      {"accuracy: --dt", "nan", "integrator.dt"});
  expect_refused_promptly(test::run_bkquake_for(30, {"accuracy", "--reference-tolerance", "nan",
                                                     "--out", tmp.file("a")}),
                          {"accuracy: --reference-tolerance", "nan", "integrator.tolerance"});
}

// Numbers in messages and summaries with enough digits to mean something.
TEST(Boundaries, ADtJustAboveTheStabilityLimitReadsAsAbove) {
  const Settings settings = settings_from_scene(Scene());
  const auto stepper = stepper_of(settings.integrator, settings.model.n);
  const double limit = stability_limit(*stepper, settings.model);
  const double dt = std::nextafter(limit, 1.0);
  try {
    check_time_step(*stepper, settings.model, dt);
    FAIL() << "dt above the limit accepted";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("integrator.dt: " + format_real(dt) + " is above the stability limit " +
                       format_real(limit)),
              std::string::npos)
        << msg;
    EXPECT_NE(format_real(dt), format_real(limit));
  }
}

TEST(Boundaries, AnErrorNeverRoundsToZero) {
  EXPECT_EQ(format_with_error(0.9, 0.0004), "0.90000 ± 0.00040");
  EXPECT_EQ(format_with_error(0.975, 0.015), "0.975 ± 0.015");
  EXPECT_EQ(format_with_error(0.9, 0.2), "0.900 ± 0.200");
  EXPECT_EQ(format_with_error(1.5, 0), "1.500 ± 0.000");
}

}  // namespace
}  // namespace bkq
