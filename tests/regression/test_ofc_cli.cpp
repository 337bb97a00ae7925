// model.kind = ofc through `bkquake run`: the catalogue keeps every catalogue's columns and
// adds topplings, a run killed between checkpoints resumes to the straight run's files byte
// for byte, the shipped scene runs, and the scenes that cannot run are refused in one line.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "io/catalog.hpp"
#include "io/checkpoint.hpp"
#include "io/scene.hpp"
#include "refusal.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::run_args;
using test::run_bkquake;

const std::vector<std::string> kOfc = {"--set",           "model.kind=ofc", "--set",
                                       "model.blocks=24", "--set",          "model.rows=20",
                                       "--set",           "ofc.alpha=0.2",  "--quiet"};

std::vector<std::string> ofc_with(std::vector<std::string> more) {
  std::vector<std::string> a = kOfc;
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(OfcCli, CatalogueHasTheCommonColumnsPlusTopplings) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const auto r = run_bkquake(run_args(ofc_with({"--set", "run.events=3000"}), {"--out", out}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines_of(read_file(out + "/catalog.csv"));
  ASSERT_EQ(rows.size(), 3001u);
  EXPECT_EQ(rows[0], catalog_header() + ",topplings");
  EXPECT_EQ(rows[0], catalog_header(true));
  std::int64_t several = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    std::vector<std::string> cells;
    std::istringstream in(rows[k]);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    ASSERT_EQ(cells.size(), ofc_catalog_schema().size()) << rows[k];
    const long blocks = std::stol(cells[3]), topplings = std::stol(cells.back());
    const long trigger = std::stol(cells[2]);
    ASSERT_GE(topplings, blocks) << rows[k];
    ASSERT_GE(blocks, 1) << rows[k];
    ASSERT_GE(trigger, 0);
    ASSERT_LT(trigger, 24 * 20);
    several += blocks > 1;
  }
  EXPECT_GT(several, 100);
  EXPECT_TRUE(fs::exists(out + "/histogram.csv"));
  const std::string summary = read_file(out + "/summary.json");
  EXPECT_NE(summary.find("\"b_mle\""), std::string::npos) << summary;
  const std::string scene = read_file(out + "/scene.ini");
  EXPECT_NE(scene.find("kind = ofc"), std::string::npos) << scene;
  EXPECT_NE(scene.find("rows = 20"), std::string::npos) << scene;
  // Keys of the chain's physics do not apply to the automaton: written as comments.
  EXPECT_EQ(scene.find("\nscheme = "), std::string::npos) << scene;
  // A chain run keeps today's columns.
  const std::string bk = tmp.file("bk");
  ASSERT_EQ(run_bkquake({"run", "--set", "run.events=50", "--quiet", "--out", bk}).status, 0);
  EXPECT_EQ(lines_of(read_file(bk + "/catalog.csv"))[0], catalog_header());
}

TEST(OfcCli, ResumeAfterSigkillWritesTheStraightRunsFiles) {
  test::TempDir tmp;
  const std::string straight = tmp.file("straight"), out = tmp.file("out");
  const auto scene = ofc_with({"--set", "run.events=20000", "--set", "run.checkpoint_events=200"});
  ASSERT_EQ(run_bkquake(run_args(scene, {"--out", straight})).status, 0);
  const int status = test::run_and_signal_when(
      run_args(scene, {"--out", out}), [&] { return fs::exists(out + "/checkpoint.prev.bin"); },
      SIGKILL);
  ASSERT_EQ(status, 128 + SIGKILL);
  const Checkpoint c = CheckpointFiles(out).read();
  ASSERT_LT(c.progress.events_done, 20000);
  ASSERT_NE(c.find("ofc.engine"), nullptr);
  const auto r = run_bkquake({"run", out + "/scene.ini", "--out", out, "--resume", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(read_file(out + "/catalog.csv") == read_file(straight + "/catalog.csv"));
  EXPECT_EQ(read_file(out + "/histogram.csv"), read_file(straight + "/histogram.csv"));
  EXPECT_EQ(test::summary_without_timing(read_file(out + "/summary.json")),
            test::summary_without_timing(read_file(straight + "/summary.json")));
}

TEST(OfcCli, ShippedSceneRuns) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const auto r =
      run_bkquake({"run", BKQUAKE_SOURCE_DIR "/data/scenes/ofc-256-a020.ini", "--set",
                   "run.events=300", "--set", "run.transient_events=0", "--quiet", "--out", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines_of(read_file(out + "/catalog.csv")).size(), 301u);
}

TEST(OfcCli, ScenesThatCannotRunAreRefusedInOneLine) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  test::expect_refused(
      run_bkquake(run_args(ofc_with({"--set", "ofc.alpha=0.25", "--set", "model.boundary=periodic",
                                     "--set", "model.boundary_y=periodic"}),
                           {"--out", out})),
      {"ofc.alpha = 0.25", "never end", "model.boundary_y"});
  test::expect_refused(run_bkquake(run_args(ofc_with({"--set", "ofc.alpha=0.3"}), {"--out", out})),
                       {"ofc.alpha", "0.3", "(0, 0.25]"});
  test::expect_refused(run_bkquake(run_args({"--set", "model.rows=4", "--quiet"}, {"--out", out})),
                       {"model.rows = 4", "BK lattice", "not implemented"});
  test::expect_refused(
      run_bkquake(run_args(ofc_with({"--set", "drive.mode=continuous"}), {"--out", out})),
      {"drive.mode = continuous", "model.kind = ofc", "event by event"});
  test::expect_refused(
      run_bkquake(run_args(ofc_with({"--set", "output.catalog=hdf5"}), {"--out", out})),
      {"output.catalog = hdf5", "csv, none"});
  test::expect_refused(run_bkquake(run_args({"--set", "ofc.alpha=0.1", "--quiet"}, {"--out", out})),
                       {"ofc.alpha", "model.kind = ofc"});
  EXPECT_FALSE(fs::exists(out + "/catalog.csv"));
}

// scene.ini writes a [section] line where the table's section changes: a section split in
// two would repeat its header, which INI readers (Python's configparser) refuse.
TEST(OfcCli, EachSceneSectionIsDeclaredInOneRun) {
  std::vector<std::string> seen;
  for (const auto& p : parameter_table()) {
    const std::string section = p.key.substr(0, p.key.find('.'));
    if (!seen.empty() && seen.back() == section) continue;
    for (const auto& s : seen) ASSERT_NE(s, section) << p.key << " splits [" << section << "]";
    seen.push_back(section);
  }
}

}  // namespace
}  // namespace bkq
