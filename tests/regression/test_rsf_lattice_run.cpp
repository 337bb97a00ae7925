// Rate-and-state runs on lattices and with range and power coupling, the catalogue's
// rate-and-state columns, slow_slip.csv, per-block patterns and the scene hash of a per-block
// file, from the command line and the shipped scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "io/catalog.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"

namespace bkq {
namespace {

using test::expect_refused;
using test::read_file;
using test::run_bkquake;

const std::string kScenes = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/rsf/";

// A CSV file as its header's names and rows of text cells.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int col(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<int>(it - header.begin());
  }
  double x(std::size_t row, const std::string& name) const {
    return std::stod(rows.at(row).at(col(name)));
  }
};

Csv read_csv(const std::string& path) {
  Csv c;
  std::istringstream in(read_file(path));
  std::string line;
  const auto split = [](const std::string& l) {
    std::vector<std::string> f;
    std::istringstream row(l);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(cell);
    return f;
  };
  if (std::getline(in, line)) c.header = split(line);
  while (std::getline(in, line)) c.rows.push_back(split(line));
  return c;
}

// The shipped lattice scene: its catalogue has the row columns and the rate-and-state columns,
// rows inside the lattice, ruptures across rows, the hypocentre time at load / V_pl; it goes
// through fit and seismicity.
TEST(RsfLatticeRun, ShippedLatticeSceneRunsThroughFitAndSeismicity) {
  test::TempDir tmp;
  const auto r = run_bkquake({"run", kScenes + "lattice-patches.ini", "--quiet", "--set",
                              "run.duration=4000", "--out", tmp.file("out")});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv cat = read_csv(tmp.file("out/catalog.csv"));
  EXPECT_EQ(cat.header.size(), kCatalogColumns + 6);
  int across = 0;
  for (std::size_t i = 0; i < cat.rows.size(); ++i) {
    ASSERT_EQ(cat.rows[i].size(), cat.header.size());
    const double t_row = cat.x(i, "trigger_row"), lo = cat.x(i, "first_row"),
                 hi = cat.x(i, "last_row");
    EXPECT_LE(lo, t_row);
    EXPECT_GE(hi, t_row);
    EXPECT_GE(lo, 0);
    EXPECT_LT(hi, 8);
    EXPECT_LT(cat.x(i, "last_block"), 16);
    EXPECT_LE(cat.x(i, "blocks"),
              (cat.x(i, "last_block") - cat.x(i, "first_block") + 1) * (hi - lo + 1));
    across += hi > lo;
    EXPECT_NEAR(cat.x(i, "hypocentre_time") * 1e-6, cat.x(i, "load"), 1e-12 * cat.x(i, "load"));
    EXPECT_GE(cat.x(i, "peak_time"), cat.x(i, "hypocentre_time"));
    EXPECT_LE(cat.x(i, "peak_time"), cat.x(i, "hypocentre_time") + cat.x(i, "duration"));
    EXPECT_EQ(cat.x(i, "peak_slip_rate"), cat.x(i, "max_speed"));
    EXPECT_GT(cat.x(i, "peak_slip_rate"), 1e-3);
  }
  EXPECT_GT(cat.rows.size(), 50u);
  EXPECT_GT(across, 0);
  const std::string summary = read_file(tmp.file("out/summary.json"));
  EXPECT_NE(summary.find("\"rows\": 8"), std::string::npos) << summary;
  const auto f = run_bkquake({"fit", tmp.file("out/catalog.csv")});
  EXPECT_EQ(f.status, 0) << f.out << f.err;
  const auto s = run_bkquake({"seismicity", tmp.file("out")});
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "out" / "seismicity" / "seismicity.json"));
}

// A chain with range and with power coupling runs (they were refused before), and a chain's
// catalogue has the rate-and-state columns but no row columns.
TEST(RsfLatticeRun, RangeAndPowerChainsRun) {
  test::TempDir tmp;
  for (const char* coupling : {"range", "power"}) {
    const std::string out = tmp.file(coupling);
    const auto r = run_bkquake(
        {"run", kScenes + "chain-asperities.ini", "--quiet", "--set", "run.duration=3000", "--set",
         std::string("model.coupling=") + coupling, "--set", "model.range=4", "--out", out});
    ASSERT_EQ(r.status, 0) << r.err;
    const Csv cat = read_csv(out + "/catalog.csv");
    EXPECT_EQ(cat.header.size(), kCatalogColumns + 3);
    EXPECT_EQ(std::count(cat.header.begin(), cat.header.end(), "trigger_row"), 0);
    EXPECT_GT(cat.rows.size(), 5u) << coupling;
    const std::string summary = read_file(out + "/summary.json");
    EXPECT_NE(summary.find("\"springs_per_block\": 8"), std::string::npos) << summary;
  }
}

// rsf.pattern = asperities: blocks in the pattern's patches keep rsf.a, rsf.b, the others have
// them swapped; the pattern and a file together, and a patch as wide as its period, are refused.
TEST(RsfLatticeRun, AsperityPattern) {
  Scene s = Scene::from_file(kScenes + "lattice-patches.ini");
  s.validate();
  const Settings st = settings_from_scene(s);
  ASSERT_EQ(st.rsf.chain.n(), 128);
  EXPECT_EQ(st.rsf.chain.rows, 8);
  for (int j = 0; j < 128; ++j) {
    const int x = j % 16, y = j / 16;
    const bool asperity = x % 4 < 3 && y % 4 < 3;
    EXPECT_EQ(st.rsf.chain.law[j].params().a, asperity ? 0.01 : 0.025) << j;
    EXPECT_EQ(st.rsf.chain.law[j].params().b_rsf, asperity ? 0.025 : 0.01) << j;
  }
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const std::string scene = kScenes + "lattice-patches.ini";
  expect_refused(
      run_bkquake({"run", scene, "--quiet", "--set", "rsf.pattern_width=4", "--out", out}),
      {"rsf.pattern_width = 4", "rsf.pattern_period = 4", "allowed: 1 to 3"});
  expect_refused(
      run_bkquake({"run", scene, "--quiet", "--set",
                   "rsf.blocks=" + kScenes + "chain-asperities-blocks.csv", "--out", out}),
      {"rsf.pattern = asperities", "rsf.blocks", "allowed"});
}

// The scene hash covers the per-block file's bytes: an edited file is another scene.
TEST(RsfLatticeRun, SceneHashCoversTheBlocksFile) {
  test::TempDir tmp;
  tmp.write("blocks.csv", "block,a,b,dc\n0,0.01,0.025,1e-5\n1,0.01,0.02,2e-5\n");
  std::string text = read_file(kScenes + "qdyn-stickslip.ini");
  text.replace(text.find("kind = 1dof"), 11, "kind = bk\nblocks = 2");
  text.replace(text.find("v_init = 2e-5"), 13, "v_init = 2e-5\nblocks = blocks.csv");
  const std::string scene = tmp.write("s.ini", text);
  const std::uint64_t before = Scene::from_file(scene).hash();
  EXPECT_EQ(Scene::from_file(scene).hash(), before);
  tmp.write("blocks.csv", "block,a,b,dc\n0,0.01,0.025,1e-5\n1,0.01,0.021,2e-5\n");
  EXPECT_NE(Scene::from_file(scene).hash(), before);
}

// rsf.slow_slip_threshold: a spring-slider just below the critical stiffness oscillates
// about the plate rate in slow episodes that grow but, over the scene's 1500 s, never reach V_th:
// they go to slow_slip.csv with their moment and peak rate, one per cycle of the linearisation's
// frequency, none to the catalogue. Out-of-range thresholds are refused.
TEST(RsfLatticeRun, SlowSlipEpisodesAreWrittenApart) {
  test::TempDir tmp;
  const std::string scene = kScenes + "slow-slip.ini";
  const auto r = run_bkquake({"run", scene, "--quiet", "--out", tmp.file("out")});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv slow = read_csv(tmp.file("out/slow_slip.csv"));
  ASSERT_GT(slow.rows.size(), 5u);
  EXPECT_EQ(slow.header.front(), "episode");
  for (std::size_t i = 0; i < slow.rows.size(); ++i) {
    EXPECT_EQ(slow.x(i, "episode"), static_cast<double>(i + 1));
    EXPECT_GT(slow.x(i, "peak_slip_rate"), 2e-6);
    EXPECT_LT(slow.x(i, "peak_slip_rate"), 1e-3);
    EXPECT_GT(slow.x(i, "moment"), 0);
    EXPECT_GT(slow.x(i, "duration"), 0);
    EXPECT_EQ(slow.rows[i][slow.col("kind")], "slow");
    if (i == 0) continue;
    EXPECT_GT(slow.x(i, "peak_slip_rate"), slow.x(i - 1, "peak_slip_rate"));  // growing
    // One episode per cycle: while the oscillation is small, at the linearisation's period
    // (1/0.01936 Hz = 51.65 s at this stiffness) to 6 %; larger ones last longer.
    const double spacing = slow.x(i, "peak_time") - slow.x(i - 1, "peak_time");
    if (i <= 3) {
      EXPECT_NEAR(spacing, 51.65, 0.06 * 51.65) << i;
    }
    EXPECT_GT(spacing, 0.95 * 51.65) << i;
  }
  EXPECT_EQ(read_csv(tmp.file("out/catalog.csv")).rows.size(), 0u);
  expect_refused(run_bkquake({"run", scene, "--quiet", "--set", "rsf.slow_slip_threshold=1e-2",
                              "--out", tmp.file("bad")}),
                 {"rsf.slow_slip_threshold = 0.01", "allowed: 0 (off) or"});
}

// Afterslip: on QDYN's stick-slip block with a slow threshold just above the plate rate, every
// seismic event is followed by an afterslip episode that starts at the event's end.
TEST(RsfLatticeRun, AfterslipFollowsEachEvent) {
  test::TempDir tmp;
  const auto r = run_bkquake({"run", kScenes + "qdyn-stickslip.ini", "--quiet", "--set",
                              "rsf.slow_slip_threshold=2e-6", "--out", tmp.file("out")});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv cat = read_csv(tmp.file("out/catalog.csv"));
  const Csv slow = read_csv(tmp.file("out/slow_slip.csv"));
  ASSERT_GT(cat.rows.size(), 3u);
  std::size_t after = 0;
  for (std::size_t i = 0; i < slow.rows.size(); ++i) {
    if (slow.rows[i][slow.col("kind")] != "afterslip") continue;
    // It starts where an event ends.
    bool found = false;
    for (std::size_t e = 0; e < cat.rows.size(); ++e)
      found |= std::fabs(cat.x(e, "hypocentre_time") + cat.x(e, "duration") - slow.x(i, "start")) <
               1e-9 * slow.x(i, "start");
    EXPECT_TRUE(found) << i;
    EXPECT_LT(slow.x(i, "peak_slip_rate"), 1e-3);
    ++after;
  }
  EXPECT_GE(after + 1, cat.rows.size());
}

}  // namespace
}  // namespace bkq
