// model.kind = ofc through `bkquake run`: the catalogue keeps every catalogue's columns and
// adds topplings, a run killed between checkpoints resumes to the straight run's files byte
// for byte, the shipped scene runs, and the scenes that cannot run are refused in one line;
// with viscoelastic relaxation the seismicity command finds the Omori excess that the plain
// automaton of the same coupling lacks, a relaxing run resumes byte for byte, and an edited
// OFC checkpoint (with a valid checksum) is refused without changing the folder.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "io/catalog.hpp"
#include "io/catalog_h5.hpp"
#include "io/catalog_reader.hpp"
#include "io/checkpoint.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
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

// Runs the 20 000-event scene straight into `straight`, and into `out` killed (SIGKILL) after a
// checkpoint that holds the named engine state, then resumed: the two catalogues and
// histograms are the same bytes.
void resume_after_sigkill(const std::vector<std::string>& scene, const char* state,
                          const std::string& straight, const std::string& out) {
  ASSERT_EQ(run_bkquake(run_args(scene, {"--out", straight})).status, 0);
  const int status = test::run_and_signal_when(
      run_args(scene, {"--out", out}), [&] { return fs::exists(out + "/checkpoint.prev.bin"); },
      SIGKILL);
  ASSERT_EQ(status, 128 + SIGKILL);
  const Checkpoint c = CheckpointFiles(out).read();
  ASSERT_LT(c.progress.events_done, 20000);
  ASSERT_NE(c.find(state), nullptr);
  const auto r = run_bkquake({"run", out + "/scene.ini", "--out", out, "--resume", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(read_file(out + "/catalog.csv") == read_file(straight + "/catalog.csv"));
  EXPECT_EQ(read_file(out + "/histogram.csv"), read_file(straight + "/histogram.csv"));
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// A lattice of 20 rows: the common columns, topplings, then the rows' columns; the trigger
// and the bounding box lie on the lattice and the trigger inside its box.
TEST(OfcCli, CatalogueHasTheCommonColumnsPlusTopplingsAndRows) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const auto r = run_bkquake(run_args(ofc_with({"--set", "run.events=3000"}), {"--out", out}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines_of(read_file(out + "/catalog.csv"));
  ASSERT_EQ(rows.size(), 3001u);
  EXPECT_EQ(rows[0], catalog_header() + ",topplings,trigger_row,first_row,last_row");
  EXPECT_EQ(rows[0], catalog_header({.topplings = true, .rows = true}));
  std::int64_t several = 0, across = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    std::vector<std::string> cells;
    std::istringstream in(rows[k]);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    ASSERT_EQ(cells.size(), ofc_catalog_schema().size() + 3) << rows[k];
    const long blocks = std::stol(cells[3]), topplings = std::stol(cells[12]);
    const long x = std::stol(cells[2]), x0 = std::stol(cells[9]), x1 = std::stol(cells[10]);
    const long y = std::stol(cells[13]), y0 = std::stol(cells[14]), y1 = std::stol(cells[15]);
    ASSERT_GE(topplings, blocks) << rows[k];
    ASSERT_GE(blocks, 1) << rows[k];
    ASSERT_TRUE(0 <= x0 && x0 <= x && x <= x1 && x1 < 24) << rows[k];
    ASSERT_TRUE(0 <= y0 && y0 <= y && y <= y1 && y1 < 20) << rows[k];
    // The box holds the sites that toppled.
    ASSERT_GE((x1 - x0 + 1) * (y1 - y0 + 1), blocks) << rows[k];
    several += blocks > 1;
    across += y1 > y0;
  }
  EXPECT_GT(several, 100);
  EXPECT_GT(across, 50);
  EXPECT_TRUE(fs::exists(out + "/histogram.csv"));
  const std::string summary = read_file(out + "/summary.json");
  EXPECT_NE(summary.find("\"b_mle\""), std::string::npos) << summary;
  const std::string scene = read_file(out + "/scene.ini");
  EXPECT_NE(scene.find("kind = ofc"), std::string::npos) << scene;
  EXPECT_NE(scene.find("rows = 20"), std::string::npos) << scene;
  // Keys of the chain's physics do not apply to the automaton: written as comments.
  EXPECT_EQ(scene.find("\nscheme = "), std::string::npos) << scene;
  // A chain run keeps today's columns, and so does a single row of the automaton (its
  // trigger and first/last_block are the site indices they always were).
  const std::string bk = tmp.file("bk");
  ASSERT_EQ(run_bkquake({"run", "--set", "run.events=50", "--quiet", "--out", bk}).status, 0);
  EXPECT_EQ(lines_of(read_file(bk + "/catalog.csv"))[0], catalog_header());
  const std::string row = tmp.file("row");
  ASSERT_EQ(run_bkquake(run_args({"--set", "model.kind=ofc", "--set", "model.blocks=64", "--set",
                                  "ofc.alpha=0.2", "--set", "run.events=50", "--quiet"},
                                 {"--out", row}))
                .status,
            0);
  EXPECT_EQ(lines_of(read_file(row + "/catalog.csv"))[0], catalog_header() + ",topplings");
}

// A lattice's catalogue read back (io/catalog_reader.hpp) from catalog.csv and catalog.h5:
// the same triggers (x, y) and bounding boxes; a single row has no row columns.
TEST(OfcCli, CatalogReaderReadsTheRowsOfCsvAndHdf5) {
  test::TempDir tmp;
  const std::string csv = tmp.file("csv"), h5 = tmp.file("h5");
  const auto scene = ofc_with({"--set", "run.events=2000"});
  ASSERT_EQ(run_bkquake(run_args(scene, {"--out", csv})).status, 0);
  std::vector<CatalogEvent> a;
  {
    CatalogReader r(csv + "/catalog.csv");
    EXPECT_TRUE(r.has_rows());
    for (CatalogEvent e; r.next(e);) a.push_back(e);
  }
  ASSERT_EQ(a.size(), 2000u);
  int off_row0 = 0;
  for (const auto& e : a) off_row0 += e.trigger_row > 0;
  EXPECT_GT(off_row0, 1000);
  if (hdf5_available()) {
    auto with_h5 = scene;
    with_h5.insert(with_h5.end(), {"--set", "output.catalog=hdf5"});
    ASSERT_EQ(run_bkquake(run_args(with_h5, {"--out", h5})).status, 0);
    CatalogReader r(h5 + "/catalog.h5");
    EXPECT_TRUE(r.has_rows());
    std::size_t k = 0;
    for (CatalogEvent e; r.next(e); ++k) {
      ASSERT_LT(k, a.size());
      ASSERT_EQ(e.trigger, a[k].trigger) << k;
      ASSERT_EQ(e.trigger_row, a[k].trigger_row) << k;
      ASSERT_EQ(e.first_block, a[k].first_block) << k;
      ASSERT_EQ(e.last_block, a[k].last_block) << k;
      ASSERT_EQ(e.first_row, a[k].first_row) << k;
      ASSERT_EQ(e.last_row, a[k].last_row) << k;
    }
    EXPECT_EQ(k, a.size());
  }
}

TEST(OfcCli, ResumeAfterSigkillWritesTheStraightRunsFiles) {
  test::TempDir tmp;
  const std::string straight = tmp.file("straight"), out = tmp.file("out");
  const auto scene = ofc_with({"--set", "run.events=20000", "--set", "run.checkpoint_events=200"});
  resume_after_sigkill(scene, "ofc.engine", straight, out);
  if (HasFatalFailure()) return;
  EXPECT_EQ(test::summary_without_timing(read_file(out + "/summary.json")),
            test::summary_without_timing(read_file(straight + "/summary.json")));
}

TEST(OfcCli, ShippedSceneRuns) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const auto r =
      run_bkquake({"run", BKQUAKE_SOURCE_DIR "/data/scenes/lattice/ofc-256-a020.ini", "--set",
                   "run.events=300", "--set", "run.transient_events=0", "--quiet", "--out", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines_of(read_file(out + "/catalog.csv")).size(), 301u);
  const std::string relax = tmp.file("relax");
  const auto rr =
      run_bkquake({"run", BKQUAKE_SOURCE_DIR "/data/scenes/lattice/ofc-relaxation-64.ini", "--set",
                   "run.events=300", "--set", "run.transient_events=0", "--quiet", "--out", relax});
  ASSERT_EQ(rr.status, 0) << rr.err;
  EXPECT_EQ(lines_of(read_file(relax + "/catalog.csv")).size(), 301u);
  EXPECT_NE(read_file(relax + "/scene.ini").find("relaxation_time = 0.001"), std::string::npos);
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
  test::expect_refused(
      run_bkquake(run_args({"--set", "model.kind=1dof", "--set", "model.rows=4", "--quiet"},
                           {"--out", out})),
      {"model.rows = 4", "1dof", "one block"});
  test::expect_refused(
      run_bkquake(run_args(ofc_with({"--set", "drive.mode=continuous"}), {"--out", out})),
      {"drive.mode = continuous", "model.kind = ofc", "event by event"});
  test::expect_refused(run_bkquake(run_args({"--set", "ofc.alpha=0.1", "--quiet"}, {"--out", out})),
                       {"ofc.alpha", "model.kind = ofc"});
  EXPECT_FALSE(fs::exists(out + "/catalog.csv"));
}

// seismicity and fit on a lattice's run folder take its shape from scene.ini: the Mogi
// picture's distances are in the plane (a 24 x 40 lattice's largest distance is
// sqrt(23^2 + 39^2) = 45.3, 46 distances in bands of 5, where a chain of 24 has bands of
// 3), and the event classes count sites of the 960; a bare catalogue takes the shape from
// fit --blocks NXxNY.
TEST(OfcCli, SeismicityAndFitTakeTheLatticesShape) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  ASSERT_EQ(run_bkquake(run_args({"--set", "model.kind=ofc", "--set", "model.blocks=24", "--set",
                                  "model.rows=40", "--set", "ofc.alpha=0.2", "--set",
                                  "run.events=4000", "--quiet"},
                                 {"--out", out}))
                .status,
            0);
  auto r = run_bkquake({"seismicity", out, "--mainshock-mu", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("a lattice of 40 rows, from scene.ini"), std::string::npos) << r.out;
  const std::string json = read_file(out + "/seismicity/seismicity.json");
  EXPECT_NE(json.find("\"rows\": 40"), std::string::npos) << json;
  EXPECT_NE(json.find("\"distance_band\": 5"), std::string::npos) << json;
  EXPECT_NE(json.find("Euclidean between trigger sites"), std::string::npos) << json;

  r = run_bkquake({"fit", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("classes (a lattice of 24 x 40 = 960 sites"), std::string::npos) << r.out;
  const std::string bare = tmp.file("bare");
  fs::create_directories(bare);
  fs::copy_file(out + "/catalog.csv", bare + "/catalog.csv");
  const auto b = run_bkquake({"fit", bare + "/catalog.csv", "--blocks", "24x40"});
  ASSERT_EQ(b.status, 0) << b.err;
  // The same classes as from the scene (the table after the header line).
  const auto table = [](const std::string& text) { return text.substr(text.find("classes (")); };
  EXPECT_EQ(table(b.out), table(r.out));
  test::expect_refused(run_bkquake({"fit", bare + "/catalog.csv", "--blocks", "24x0"}),
                       {"--blocks", "model.rows", "0"});
}

// The rows of a catalog.h5 as doubles: event, moment, topplings, trigger_row, last_row.
std::vector<double> h5_rows(const std::string& path) {
  CatalogH5Reader r(path, {"event", "moment", "topplings", "trigger_row", "last_row"});
  EXPECT_TRUE(r.has(2)) << "no topplings column";
  EXPECT_TRUE(r.has(4)) << "no last_row column";
  std::vector<double> all, block;
  while (r.next_block(block) > 0) all.insert(all.end(), block.begin(), block.end());
  return all;
}

// output.catalog = hdf5 writes the OFC catalogue with its topplings column: the same rows
// as catalog.csv, and a run killed between checkpoints resumes to the straight run's rows.
TEST(OfcCli, Hdf5CatalogueHoldsTheCsvRowsAndResumes) {
  if (!hdf5_available()) GTEST_SKIP() << "built without HDF5";
  test::TempDir tmp;
  const std::string csv = tmp.file("csv"), h5 = tmp.file("h5"), out = tmp.file("out");
  const auto scene = ofc_with({"--set", "run.events=20000", "--set", "run.checkpoint_events=200"});
  ASSERT_EQ(run_bkquake(run_args(scene, {"--out", csv})).status, 0);
  auto with_h5 = scene;
  with_h5.insert(with_h5.end(), {"--set", "output.catalog=hdf5"});
  ASSERT_EQ(run_bkquake(run_args(with_h5, {"--out", h5})).status, 0);
  const std::vector<double> rows = h5_rows(h5 + "/catalog.h5");
  const auto lines = lines_of(read_file(csv + "/catalog.csv"));
  ASSERT_EQ(rows.size(), 5 * (lines.size() - 1));
  for (std::size_t k = 1; k < lines.size(); k += 997) {
    std::vector<std::string> cells;
    std::istringstream in(lines[k]);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    EXPECT_EQ(rows[5 * (k - 1)], std::stod(cells[0]));
    EXPECT_EQ(rows[5 * (k - 1) + 1], std::stod(cells[4]));
    EXPECT_EQ(rows[5 * (k - 1) + 2], std::stod(cells[12]));
    EXPECT_EQ(rows[5 * (k - 1) + 3], std::stod(cells[13]));
    EXPECT_EQ(rows[5 * (k - 1) + 4], std::stod(cells[15]));
  }
  const int status = test::run_and_signal_when(
      run_args(with_h5, {"--out", out}), [&] { return fs::exists(out + "/checkpoint.prev.bin"); },
      SIGKILL);
  ASSERT_EQ(status, 128 + SIGKILL);
  const auto r = run_bkquake({"run", out + "/scene.ini", "--out", out, "--resume", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(h5_rows(out + "/catalog.h5") == rows);
  EXPECT_EQ(read_file(out + "/histogram.csv"), read_file(csv + "/histogram.csv"));
}

TEST(OfcCli, RelaxationRefusalsNameTheKeys) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  test::expect_refused(
      run_bkquake(run_args(ofc_with({"--set", "ofc.relaxation_alpha=0.1"}), {"--out", out})),
      {"ofc.relaxation_alpha = 0.1", "0.25 - ofc.alpha"});
  test::expect_refused(
      run_bkquake(run_args(ofc_with({"--set", "ofc.relaxation_time=1"}), {"--out", out})),
      {"ofc.relaxation_time = 1", "nothing would relax"});
  test::expect_refused(
      run_bkquake(run_args(ofc_with({"--set", "ofc.order=random"}), {"--out", out})),
      {"ofc.order", "random", "generations", "sequential"});
  EXPECT_FALSE(fs::exists(out + "/catalog.csv"));
}

// The same total coupling (0.2 per neighbour) passed on at once, or 0.05 of it through the
// viscoelastic element: the stacked rate after mainshocks (mu >= 4) has an Omori-Utsu excess
// with relaxation (likelihood ratio in the thousands) and none worth the name without
// (measured 13, below the detection threshold of 16.3).
TEST(OfcCli, RelaxationShowsTheOmoriExcessThePlainAutomatonLacks) {
  test::TempDir tmp;
  double ratio[2] = {0, 0};
  bool excess[2] = {false, false};
  for (const bool relax : {false, true}) {
    const std::string out = tmp.file(relax ? "relax" : "plain");
    std::vector<std::string> scene = {"--set",  "model.kind=ofc",
                                      "--set",  "model.blocks=32",
                                      "--set",  "model.rows=32",
                                      "--set",  "run.events=100000",
                                      "--set",  "run.transient_events=40000",
                                      "--set",  "output.catalog=csv",
                                      "--quiet"};
    const std::vector<std::string> coupling =
        relax ? std::vector<std::string>{"--set", "ofc.alpha=0.15",
                                         "--set", "ofc.relaxation_alpha=0.05",
                                         "--set", "ofc.relaxation_time=0.01"}
              : std::vector<std::string>{"--set", "ofc.alpha=0.2"};
    scene.insert(scene.end(), coupling.begin(), coupling.end());
    ASSERT_EQ(run_bkquake(run_args(scene, {"--out", out})).status, 0);
    const auto r = run_bkquake({"seismicity", out, "--mainshock-mu", "4"});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string json = read_file(out + "/seismicity/seismicity.json");
    const std::size_t omori = json.find("\"omori\"");
    ASSERT_NE(omori, std::string::npos);
    const std::size_t lr = json.find("\"likelihood_ratio\": ", omori);
    ASSERT_NE(lr, std::string::npos);
    ratio[relax] = std::stod(json.substr(lr + 20));
    excess[relax] = json.find("\"excess\": true", omori) < json.find("\"foreshock\"");
  }
  EXPECT_TRUE(excess[1]);
  EXPECT_GT(ratio[1], 10 * ratio[0]) << ratio[0] << " " << ratio[1];
  EXPECT_GT(ratio[1], 200.0);
}

TEST(OfcCli, RelaxingRunResumesByteForByte) {
  test::TempDir tmp;
  const std::string straight = tmp.file("straight"), out = tmp.file("out");
  const auto scene =
      ofc_with({"--set", "run.events=20000", "--set", "run.checkpoint_events=200", "--set",
                "ofc.alpha=0.15", "--set", "ofc.relaxation_alpha=0.05", "--set",
                "ofc.relaxation_time=0.01", "--set", "ofc.order=sequential"});
  resume_after_sigkill(scene, "ofc.relaxation", straight, out);
}

// An OFC checkpoint edited with its checksum redone: each field is checked as a scene key is,
// and the refusal leaves the folder as it was.
TEST(OfcCli, EditedOfcCheckpointIsRefusedAndChangesNothing) {
  test::TempDir tmp;
  const std::string s = tmp.file("s");
  // Stopped by SIGTERM: a checkpoint and no stale lock (whose removal would change the folder).
  const auto scene = ofc_with({"--set", "run.events=3000000", "--set", "run.checkpoint_events=500",
                               "--set", "ofc.alpha=0.15", "--set", "ofc.relaxation_alpha=0.05",
                               "--set", "ofc.relaxation_time=0.01"});
  ASSERT_EQ(test::run_and_signal_when(
                run_args(scene, {"--out", s}),
                [&] { return fs::exists(s + "/checkpoint.prev.bin"); }, SIGTERM),
            128 + SIGTERM);
  const std::string ckpt = s + "/checkpoint.bin";
  const std::string good = read_file(ckpt);
  const OfcParams p = settings_from_scene(Scene::from_file(s + "/scene.ini")).ofc.lattice;
  const std::vector<std::string> resume = {"run",      s + "/scene.ini", "--quiet",
                                           "--resume", "--out",          s};
  struct Edit {
    const char* name;
    void (*apply)(OfcSnapshot&);
    const char* field;
  };
  const Edit edits[] = {
      {"stress above threshold", [](OfcSnapshot& o) { o.g[7] = 2 - o.offset; },
       "ofc stress[7] = 2"},
      {"not a number", [](OfcSnapshot& o) { o.g[3] = std::nan(""); }, "ofc stress[3]"},
      {"padding", [](OfcSnapshot& o) { o.g.back() = 0.5; }, "ofc padding"},
      {"short field", [](OfcSnapshot& o) { o.g.pop_back(); }, "ofc field length"},
      {"offset", [](OfcSnapshot& o) { o.offset = -1; }, "ofc offset = -1"},
      {"load", [](OfcSnapshot& o) { o.load = 1e300; }, "ofc load = 1e+300"},
      {"events", [](OfcSnapshot& o) { o.counters.events += 1; }, "ofc events"},
      {"topplings", [](OfcSnapshot& o) { o.counters.topplings = 0; }, "ofc topplings = 0"},
      {"pending", [](OfcSnapshot& o) { o.pending[5] = -0.5; }, "ofc pending[5] = -0.5"},
      {"pending at", [](OfcSnapshot& o) { o.pending_at[5] = o.load + 1; }, "ofc pending_at[5]"},
      // An arrival time for a site without pending stress, or none for one with it.
      {"arrival", [](OfcSnapshot& o) { o.arrival[5] = o.pending[5] > 0 ? -1 : 3; },
       "ofc arrival[5]"},
  };
  for (const Edit& e : edits) {
    SCOPED_TRACE(e.name);
    Checkpoint c = decode_checkpoint(good, ckpt);
    OfcSnapshot o = find_ofc_state(c, p, ckpt);
    e.apply(o);
    put_ofc_state(c, o);
    std::ofstream(ckpt, std::ios::binary | std::ios::trunc) << encode_checkpoint(c);
    const auto before = test::tree_bytes(s);
    test::expect_refused(run_bkquake(resume), {"checkpoint.bin' is invalid", e.field});
    EXPECT_EQ(test::tree_bytes(s), before) << "a refused resume changed the folder";
  }
  // The checkpoint as written passes (a short extension: the run was to go on for long).
  std::ofstream(ckpt, std::ios::binary | std::ios::trunc) << good;
  const Checkpoint c = decode_checkpoint(good, ckpt);
  EXPECT_NO_THROW(validate_ofc_state(c, p, ckpt));
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
