// Extending a finished event run: a finished run keeps its final state
// (checkpoint.final.bin, never mistaken for an interruption), and `run --resume --set
// run.events=N2` continues it to N2 events. The result equals a run made at N2 from the
// start: catalog.csv, histogram.csv and scene.ini byte for byte (scene.ini's provenance
// comments aside), summary.json except its clocks and resume count. A smaller or equal
// run.events, or any other key changed, is refused in one line and changes no file.
#include <gtest/gtest.h>

#include <filesystem>
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

}  // namespace
}  // namespace bkq
