// Extending a finished run: a finished run keeps its final state (checkpoint.final.bin,
// never mistaken for an interruption), and `run --resume --set run.events=N2` (event runs)
// or `--set run.duration=T2` (continuous runs) continues it. The result equals a run made
// at full length from the start: every output byte for byte (provenance comments aside),
// summary.json except its clocks and resume count. A smaller or equal value, or any other
// key changed, is refused in one line and changes no file; so is a continuous extension
// whose open speed segment would need steps the finished run did not keep.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "io/checkpoint.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
using test::expect_refused;
using test::read_file;
using test::run_bkquake;
using test::TempDir;

const std::vector<std::string> kScene = {"--set", "model.blocks=50", "--set",
                                         "run.transient_events=300", "--quiet"};

std::vector<std::string> args(std::vector<std::string> more) {
  std::vector<std::string> a{"run"};
  a.insert(a.end(), kScene.begin(), kScene.end());
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// Lines without '#' comments (provenance) and without the keys that name a clock or a
// session count.
std::string without(const std::string& text, const std::vector<std::string>& keys) {
  std::istringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] == '#') continue;
    bool drop = false;
    for (const auto& k : keys) drop = drop || line.find("\"" + k + "\"") != std::string::npos;
    if (!drop) out += line + "\n";
  }
  return out;
}

TEST(ExtendRun, EqualsARunMadeAtFullLength) {
  TempDir tmp;
  const std::string full = tmp.file("full"), ext = tmp.file("ext");
  ASSERT_EQ(run_bkquake(args({"--set", "run.events=6000", "--out", full})).status, 0);
  ASSERT_EQ(run_bkquake(args({"--set", "run.events=2500", "--out", ext})).status, 0);
  EXPECT_TRUE(fs::exists(ext + "/checkpoint.final.bin"));
  EXPECT_FALSE(CheckpointFiles(ext).exist()) << "the final state is no interruption";

  const auto r = run_bkquake(args({"--set", "run.events=6000", "--out", ext, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"catalog.csv", "histogram.csv"})
    EXPECT_TRUE(read_file(full + "/" + f) == read_file(ext + "/" + f)) << f << " differs";
  EXPECT_EQ(without(read_file(full + "/scene.ini"), {}),
            without(read_file(ext + "/scene.ini"), {}));
  const std::vector<std::string> clocks = {
      "written",           "wall_seconds",     "wall_seconds_total",
      "events_per_second", "steps_per_second", "resumes"};
  const std::string a = without(read_file(full + "/summary.json"), clocks);
  const std::string b = without(read_file(ext + "/summary.json"), clocks);
  EXPECT_EQ(a, b);
  EXPECT_NE(read_file(ext + "/summary.json").find("\"resumes\": 1"), std::string::npos);
  EXPECT_TRUE(fs::exists(ext + "/checkpoint.final.bin"));  // extendable again
}

TEST(ExtendRun, SmallerOrOtherwiseChangedRunsAreRefusedAndChangeNothing) {
  TempDir tmp;
  const std::string out = tmp.file("out");
  ASSERT_EQ(run_bkquake(args({"--set", "run.events=1500", "--out", out})).status, 0);
  const auto before = test::tree_bytes(out);
  expect_refused(run_bkquake(args({"--set", "run.events=1500", "--out", out, "--resume"})),
                 {"finished run", "of 1500 events", "run.events = 1500", "more than 1500",
                  "nothing to continue"});
  expect_refused(run_bkquake(args({"--set", "run.events=900", "--out", out, "--resume"})),
                 {"run.events = 900", "more than 1500"});
  expect_refused(run_bkquake(args({"--set", "run.events=3000", "--set", "friction.alpha=3", "--out",
                                   out, "--resume"})),
                 {"friction.alpha"});
  EXPECT_TRUE(test::tree_bytes(out) == before);
}

// ---- continuous runs ----

std::vector<std::string> continuous(std::vector<std::string> more) {
  std::vector<std::string> a = {"run",
                                "--set",
                                "drive.mode=continuous",
                                "--set",
                                "model.blocks=10",
                                "--set",
                                "drive.speed=0.05",
                                "--set",
                                "output.every=2",
                                "--quiet"};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// Every file of a run folder but its final state (machine state with clocks), without '#'
// provenance lines and, for summary.json, without clocks and session counts.
std::map<std::string, std::string> outputs_of(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "checkpoint.final.bin") continue;
    const std::string bytes = read_file(e.path().string());
    files[name] = name == "summary.json" ? test::summary_without_timing(bytes) : without(bytes, {});
  }
  return files;
}

void expect_same_outputs(const std::string& want_dir, const std::string& got_dir) {
  const auto want = outputs_of(want_dir);
  const auto got = outputs_of(got_dir);
  ASSERT_EQ(want.size(), got.size());
  for (const auto& [name, bytes] : want) {
    const auto it = got.find(name);
    ASSERT_NE(it, got.end()) << name;
    EXPECT_TRUE(it->second == bytes) << name << " differs from the full-length run's";
  }
}

// Constant speed: the energy windows (300 long) and the one speed segment are open at the
// end of the shorter run; the extension to more than twice its length is exact.
TEST(ExtendRun, ContinuousEqualsARunMadeAtFullLength) {
  TempDir tmp;
  const std::string full = tmp.file("full"), ext = tmp.file("ext");
  const std::vector<std::string> energy = {"--set", "output.energy=true", "--set",
                                           "output.energy_window=300"};
  auto with = [&](std::vector<std::string> more) {
    more.insert(more.end(), energy.begin(), energy.end());
    return continuous(more);
  };
  ASSERT_EQ(run_bkquake(with({"--set", "run.duration=1000", "--out", full})).status, 0);
  ASSERT_EQ(run_bkquake(with({"--set", "run.duration=400", "--out", ext})).status, 0);
  EXPECT_TRUE(fs::exists(ext + "/checkpoint.final.bin"));
  EXPECT_FALSE(CheckpointFiles(ext).exist()) << "the final state is no interruption";

  const auto r = run_bkquake(with({"--set", "run.duration=1000", "--out", ext, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  expect_same_outputs(full, ext);
  for (const char* f : {"catalog.csv", "timeseries.csv", "energy.csv", "segments.csv"})
    EXPECT_TRUE(fs::exists(ext + "/" + f)) << f;
  EXPECT_NE(read_file(ext + "/summary.json").find("\"resumes\": 1"), std::string::npos);
  EXPECT_TRUE(fs::exists(ext + "/checkpoint.final.bin"));  // extendable again
}

// A steps schedule (one speed segment per 1000 of time): extended from a segment's end,
// and from inside a segment before its averaged last half begins.
TEST(ExtendRun, ContinuousStepsScheduleFromAndInsideASegment) {
  TempDir tmp;
  const std::string full = tmp.file("full");
  auto thesis = [](std::vector<std::string> more) {
    std::vector<std::string> a = {
        "run",    std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/thesis.ini",
        "--set",  "drive.step_interval=1000",
        "--set",  "model.blocks=20",
        "--set",  "output.every=2",
        "--quiet"};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  ASSERT_EQ(run_bkquake(thesis({"--set", "run.duration=2500", "--out", full})).status, 0);
  for (const char* t1 : {"1000", "1200"}) {
    const std::string ext = tmp.file(std::string("ext") + t1);
    ASSERT_EQ(
        run_bkquake(thesis({"--set", std::string("run.duration=") + t1, "--out", ext})).status, 0);
    const auto r = run_bkquake(thesis({"--set", "run.duration=2500", "--out", ext, "--resume"}));
    ASSERT_EQ(r.status, 0) << r.err;
    SCOPED_TRACE(std::string("extended from run.duration = ") + t1);
    expect_same_outputs(full, ext);
  }
}

TEST(ExtendRun, ContinuousShorterChangedOrUnreachableIsRefusedAndChangesNothing) {
  TempDir tmp;
  const std::string out = tmp.file("out");
  ASSERT_EQ(run_bkquake(continuous({"--set", "run.duration=300", "--out", out})).status, 0);
  const auto before = test::tree_bytes(out);
  expect_refused(run_bkquake(continuous({"--set", "run.duration=300", "--out", out, "--resume"})),
                 {"finished run", "of duration 300", "run.duration = 300", "more than 300",
                  "nothing to continue"});
  expect_refused(run_bkquake(continuous({"--set", "run.duration=200", "--out", out, "--resume"})),
                 {"run.duration = 200", "more than 300"});
  expect_refused(run_bkquake(continuous({"--set", "run.duration=900", "--set", "drive.speed=0.06",
                                         "--out", out, "--resume"})),
                 {"drive.speed"});
  // The one constant-speed segment averages its last half: from 500 of a 1000 run, before
  // the end (300) of the finished run.
  expect_refused(run_bkquake(continuous({"--set", "run.duration=500", "--out", out, "--resume"})),
                 {"run.duration = 500", "speed segment 0", "t = 300", "allowed: more than 600"});
  EXPECT_TRUE(test::tree_bytes(out) == before);
  // What the refusals left extends.
  const auto r = run_bkquake(continuous({"--set", "run.duration=700", "--out", out, "--resume"}));
  EXPECT_EQ(r.status, 0) << r.err;
}

}  // namespace
}  // namespace bkq
