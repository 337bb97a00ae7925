// The OFC automaton's lattice outputs through the commands: event_slip.csv's slip maps (one
// row per toppled site, block = x and row = y, the stress released and the topplings)
// agree with the catalogue event by event and a run killed (SIGKILL) and resumed writes
// the straight run's bytes; merge keeps a lattice's shape and refuses another shape
// naming the keys; a sweep over ofc.alpha on a lattice runs and keeps the row columns.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "io/catalog.hpp"
#include "io/checkpoint.hpp"
#include "refusal.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::run_args;
using test::run_bkquake;

std::vector<std::string> ofc(int nx, int ny, std::vector<std::string> more) {
  std::vector<std::string> a = {"--set",  "model.kind=ofc",
                                "--set",  "model.blocks=" + std::to_string(nx),
                                "--set",  "model.rows=" + std::to_string(ny),
                                "--set",  "ofc.alpha=0.2",
                                "--quiet"};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string c; std::getline(in, c, ',');) out.push_back(c);
  return out;
}

// One event's map as read back from event_slip.csv.
struct Map {
  std::int64_t sites = 0, topplings = 0;
  double released = 0;
  int x0 = 1 << 30, x1 = -1, y0 = 1 << 30, y1 = -1;
};

// Every event with mu >= 1 of a 16 x 12 lattice is in event_slip.csv, and only those: as
// many rows as the catalogue's distinct sites, the sites inside the event's box, the
// topplings adding up to the catalogue's and the released stress to its moment. Killed
// after a checkpoint and resumed, the run writes the straight run's event_slip.csv.
TEST(LatticeOutputs, SlipMapsAgreeWithTheCatalogueAndResumeByteForByte) {
  test::TempDir tmp;
  const std::string straight = tmp.file("straight"), out = tmp.file("out");
  const auto scene = ofc(16, 12,
                         {"--set", "run.events=20000", "--set", "run.checkpoint_events=200",
                          "--set", "output.event_slip=1"});
  auto r = run_bkquake(run_args(scene, {"--out", straight}));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string slips = read_file(straight + "/event_slip.csv");
  const auto rows = lines_of(slips);
  ASSERT_GT(rows.size(), 1000u);
  EXPECT_EQ(rows[0], "event,block,row,slip,topplings");
  std::map<long long, Map> maps;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto c = cells_of(rows[k]);
    ASSERT_EQ(c.size(), 5u) << rows[k];
    Map& m = maps[std::stoll(c[0])];
    const int x = std::stoi(c[1]), y = std::stoi(c[2]);
    ASSERT_TRUE(0 <= x && x < 16 && 0 <= y && y < 12) << rows[k];
    ++m.sites;
    m.released += std::stod(c[3]);
    m.topplings += std::stoll(c[4]);
    m.x0 = std::min(m.x0, x);
    m.x1 = std::max(m.x1, x);
    m.y0 = std::min(m.y0, y);
    m.y1 = std::max(m.y1, y);
  }
  const auto catalogue = lines_of(read_file(straight + "/catalog.csv"));
  ASSERT_EQ(catalogue[0], catalog_header({.topplings = true, .rows = true}));
  std::size_t mapped = 0;
  for (std::size_t k = 1; k < catalogue.size(); ++k) {
    const auto c = cells_of(catalogue[k]);
    const long long event = std::stoll(c[0]);
    const double moment = std::stod(c[4]), mu = std::stod(c[5]);
    const auto it = maps.find(event);
    if (!(mu >= 1)) {
      ASSERT_EQ(it, maps.end()) << catalogue[k];
      continue;
    }
    ASSERT_NE(it, maps.end()) << catalogue[k];
    const Map& m = it->second;
    ++mapped;
    EXPECT_EQ(m.sites, std::stoll(c[3])) << catalogue[k];
    EXPECT_EQ(m.topplings, std::stoll(c[12])) << catalogue[k];
    EXPECT_NEAR(m.released, moment, 1e-12 * moment) << catalogue[k];
    // The map's extent is the catalogue's box: first/last_block and first/last_row.
    EXPECT_EQ(m.x0, std::stoi(c[9])) << catalogue[k];
    EXPECT_EQ(m.x1, std::stoi(c[10])) << catalogue[k];
    EXPECT_EQ(m.y0, std::stoi(c[14])) << catalogue[k];
    EXPECT_EQ(m.y1, std::stoi(c[15])) << catalogue[k];
  }
  EXPECT_GT(mapped, 500u);
  EXPECT_EQ(maps.size(), mapped);

  const int status = test::run_and_signal_when(
      run_args(scene, {"--out", out}), [&] { return fs::exists(out + "/checkpoint.prev.bin"); },
      SIGKILL);
  ASSERT_EQ(status, 128 + SIGKILL);
  ASSERT_LT(CheckpointFiles(out).read().progress.events_done, 20000);
  r = run_bkquake({"run", out + "/scene.ini", "--out", out, "--resume", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(read_file(out + "/event_slip.csv") == slips) << "event_slip.csv differs";
  EXPECT_TRUE(read_file(out + "/catalog.csv") == read_file(straight + "/catalog.csv"));
}

// A single row of the automaton has no row column; its block is the site's index.
TEST(LatticeOutputs, SingleRowSlipMapHasNoRowColumn) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const auto r = run_bkquake(run_args(
      ofc(64, 1, {"--set", "run.events=2000", "--set", "output.event_slip=0"}), {"--out", out}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines_of(read_file(out + "/event_slip.csv"));
  ASSERT_GT(rows.size(), 100u);
  EXPECT_EQ(rows[0], "event,block,slip,topplings");
  for (std::size_t k = 1; k < rows.size(); ++k) ASSERT_EQ(cells_of(rows[k]).size(), 4u);
}

// Two 16 x 16 runs merge: the merged folder keeps the lattice (scene.ini's model.rows, 256
// sites in summary.json, so the per-site rates and fit's classes are the lattice's); a
// 16 x 16 run and an 8 x 32 run (also 256 sites) are refused in one line naming both keys.
TEST(LatticeOutputs, MergeKeepsTheLatticeAndRefusesAnotherShape) {
  test::TempDir tmp;
  const std::string a = tmp.file("a"), b = tmp.file("b"), c = tmp.file("c");
  ASSERT_EQ(run_bkquake(run_args(ofc(16, 16, {"--set", "run.events=3000", "--set", "run.seed=1"}),
                                 {"--out", a}))
                .status,
            0);
  ASSERT_EQ(run_bkquake(run_args(ofc(16, 16, {"--set", "run.events=2000", "--set", "run.seed=2"}),
                                 {"--out", b}))
                .status,
            0);
  ASSERT_EQ(run_bkquake(run_args(ofc(8, 32, {"--set", "run.events=2000", "--set", "run.seed=3"}),
                                 {"--out", c}))
                .status,
            0);
  const std::string merged = tmp.file("merged");
  auto r = run_bkquake({"merge", a, b, "--out", merged});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string scene = read_file(merged + "/scene.ini");
  EXPECT_NE(scene.find("\nrows = 16\n"), std::string::npos) << scene;
  EXPECT_NE(scene.find("\nkind = ofc\n"), std::string::npos) << scene;
  const std::string summary = read_file(merged + "/summary.json");
  EXPECT_NE(summary.find("\"events\": 5000"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"blocks\": 256"), std::string::npos) << summary;

  const std::string refused = tmp.file("refused");
  test::expect_refused(
      run_bkquake({"merge", a, c, "--out", refused}),
      {"merge: ", c, "another scene", "model.blocks = 8 (not 16)", "model.rows = 32 (not 16)"});
  EXPECT_FALSE(fs::exists(refused + "/histogram.csv"));
}

// A sweep over ofc.alpha on a 12 x 10 lattice: both points run and merge their replicas,
// the replicas' catalogues and slip maps keep the row columns, and the larger alpha makes
// the larger avalanches.
TEST(LatticeOutputs, SweepOverAlphaOnALatticeKeepsTheRows) {
  test::TempDir tmp;
  const std::string sweep = tmp.write("alpha.ini", R"([sweep]
replicas = 2
collect = catalog, histogram, summary
[vary]
ofc.alpha = 0.1, 0.22
[set]
model.kind = ofc
model.blocks = 12
model.rows = 10
run.events = 1500
run.transient_events = 1000
output.event_slip = 2
)");
  const std::string out = tmp.file("out");
  const auto r = run_bkquake({"sweep", sweep, "--out", out});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto csv = lines_of(read_file(out + "/sweep.csv"));
  ASSERT_EQ(csv.size(), 3u);
  EXPECT_EQ(csv[1].rfind("0,0.1,ok,2,3000,", 0), 0u) << csv[1];
  EXPECT_EQ(csv[2].rfind("1,0.22,ok,2,3000,", 0), 0u) << csv[2];
  double mean_topplings[2] = {0, 0};
  for (int p = 0; p < 2; ++p) {
    const fs::path point = fs::path(out) / "points" / ("p000" + std::to_string(p));
    EXPECT_NE(read_file((point / "summary.json").string()).find("\"blocks\": 120"),
              std::string::npos);
    for (int k = 0; k < 2; ++k) {
      const fs::path replica = point / ("r0" + std::to_string(k));
      const auto rows = lines_of(read_file((replica / "catalog.csv").string()));
      ASSERT_EQ(rows.size(), 1501u) << replica;
      EXPECT_EQ(rows[0], catalog_header({.topplings = true, .rows = true}));
      for (std::size_t i = 1; i < rows.size(); ++i)
        mean_topplings[p] += std::stod(cells_of(rows[i])[12]) / 3000;
      EXPECT_EQ(lines_of(read_file((replica / "event_slip.csv").string()))[0],
                "event,block,row,slip,topplings")
          << replica;
    }
  }
  EXPECT_GT(mean_topplings[1], 1.5 * mean_topplings[0]);
}

}  // namespace
}  // namespace bkq
