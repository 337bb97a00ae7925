// `bkquake stability` end to end: the files it writes (headers from their schemas, one row
// per eigenvalue and per swept value, mode shapes on request) and its refusals (no sliding
// equilibrium, a key that cannot be swept, a mode that does not exist), each one line
// with exit status 2.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "io/schema.hpp"
#include "io/stability_csv.hpp"

namespace bkq {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

const std::string kThesis = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/thesis.ini";

TEST(StabilityCli, WritesTheSweepItsSummaryAndModeShapes) {
  test::TempDir dir;
  const auto r = test::run_bkquake({"stability", kThesis, "--set", "model.blocks=20", "--sweep",
                                    "drive.speed=0.05:0.5:4", "--modes", "pad,0", "--modes",
                                    "chain,3", "--out", dir.file("s")});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines_of(test::read_file(dir.file("s/stability.csv")));
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0], header_of(stability_schema()));
  // bkp, N = 20: 19 chain quadratics + the quartic's two pairs, complex pairs listed once.
  EXPECT_EQ(rows.size(), 1 + 4 * 21u);
  const auto summary = lines_of(test::read_file(dir.file("s/stability_summary.csv")));
  EXPECT_EQ(summary[0], header_of(stability_summary_schema()));
  EXPECT_EQ(summary.size(), 5u);
  EXPECT_EQ(summary[1].rfind("0.05,0.05,", 0), 0u) << summary[1];
  const auto modes = lines_of(test::read_file(dir.file("s/modes.csv")));
  EXPECT_EQ(modes[0], header_of(modes_schema()));
  EXPECT_EQ(modes.size(), 1 + 4 * (21u + 21u));  // 20 blocks and the pad, for both modes
  EXPECT_NE(test::read_file(dir.file("s/scene.ini")).find("# bkquake"), std::string::npos);
}

TEST(StabilityCli, RefusesWhatHasNoAnswer) {
  test::TempDir dir;
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--set", "drive.speed=0"}, "no sliding equilibrium at drive.speed = 0"},
      {{"--set", "model.caliper_stiffness=0"}, "model.caliper_stiffness = 0"},
      {{"--sweep", "model.kind=1:2:3"}, "only real and integer keys can be swept"},
      {{"--sweep", "drive.speed=0.1:1"}, "expected KEY=FROM:TO:COUNT"},
      {{"--modes", "pad,1"}, "mode pad,1 does not exist"},
      {{"--modes", "wobble,1"}, "FAMILY chain|pad|1dof"},
      {{"--dense", "--set", "model.blocks=2000"}, "above the dense solver's limit"},
  };
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"stability", kThesis, "--out", dir.file("x")};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = test::run_bkquake(args);
    EXPECT_EQ(r.status, 2) << extra[1];
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(r.err_lines().size(), 1u) << r.err;
  }
}

TEST(StabilityCli, RunModeStartsAtSteadySlidingPlusTheMode) {
  test::TempDir dir;
  // thesis.ini's first speed step comes at t = 2000: the 5 time units run at v = 0.1.
  const auto r = test::run_bkquake({"run", kThesis, "--set", "model.blocks=10", "--set",
                                    "drive.speed=0.1", "--set", "run.duration=5", "--mode",
                                    "chain,2", "--quiet", "--out", dir.file("r")});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string scene = test::read_file(dir.file("r/scene.ini"));
  EXPECT_NE(scene.find("start = equilibrium"), std::string::npos);
  EXPECT_NE(scene.find("start_mode = chain"), std::string::npos);
  EXPECT_NE(scene.find("start_mode_index = 2"), std::string::npos);
  const auto ts = lines_of(test::read_file(dir.file("r/timeseries.csv")));
  ASSERT_GT(ts.size(), 2u);
  EXPECT_EQ(ts[1].substr(ts[1].rfind(',') + 1), "10");  // every block slides from the start
  const auto bad =
      test::run_bkquake({"run", kThesis, "--mode", "chain,100", "--out", dir.file("b")});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("mode chain,100 does not exist"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace bkq
