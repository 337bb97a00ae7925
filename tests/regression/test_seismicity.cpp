// `bkquake seismicity` as users call it: on a run folder, a bare catalogue, the same
// catalogue as CSV and as HDF5, a merged folder (refused), with --export; the moment budget
// of a real run; the folder's lock and the replacement of seismicity/ alone; and the docs
// page's column tables against the schemas (io/seismicity_csv.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>

#include "cli_helpers.hpp"
#include "io/catalog_h5.hpp"
#include "io/folder_lock.hpp"
#include "io/json.hpp"
#include "io/readme_tables.hpp"
#include "io/seismicity_csv.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::run_bkquake;
using test::TempDir;

const std::vector<std::string> kScene = {"--set", "model.blocks=20", "--set", "run.events=20000"};

// One event run shared by the tests below (N = 20, 20000 events, a third of a second).
class SeismicityCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    const auto r = run_bkquake(test::run_args(kScene, {"--out", run()}));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static std::string run() { return dir_->file("run"); }
  static std::unique_ptr<TempDir> dir_;
};
std::unique_ptr<TempDir> SeismicityCli::dir_;

double number(const std::string& json, const std::string& key) {
  const auto v = json_top_level_number(json, key, "seismicity.json");
  return v ? *v : NAN;
}

// seismicity.json without what names the input file and the writer (path, time).
std::string without_provenance(const std::string& json) {
  std::string out = json.substr(0, json.find("\"provenance\""));
  std::istringstream in(out);
  std::string kept;
  for (std::string line; std::getline(in, line);)
    if (line.find("\"input\"") == std::string::npos) kept += line + "\n";
  return kept;
}

TEST_F(SeismicityCli, RunFolderGetsEveryFileAndTheMomentBudgetIsOne) {
  fs::remove_all(fs::path(run()) / "seismicity");
  const auto r = run_bkquake({"seismicity", run()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("mainshocks: events whose slipped extent spans more than half the chain "
                       "(more than 10 of 20 blocks)"),
            std::string::npos)
      << r.out;
  const fs::path out = fs::path(run()) / "seismicity";
  for (const auto& [name, schema] : seismicity_schemas()) {
    if (name == "export" || name == "event_slip.csv") continue;
    const std::string text = read_file((out / name).string());
    std::string header = "\n";
    header += header_of(*schema);
    header += '\n';
    EXPECT_NE(text.find(header), std::string::npos) << name;
    EXPECT_NE(text.find("# bkquake "), std::string::npos) << name << ": provenance";
  }
  const std::string json = read_file((out / "seismicity.json").string());
  // A chain slips as much as it is loaded: 20000 events of 20 blocks come within 1 %.
  EXPECT_NEAR(number(json, "moment_budget"), 1.0, 0.01);
  EXPECT_EQ(number(json, "events"), 20000);
  for (const char* key : {"\"interevent\"",
                          "\"recurrence\"",
                          "\"omori\"",
                          "\"foreshock\"",
                          "\"bath\"",
                          "\"weibull_k\"",
                          "\"weibull_k_err\"",
                          "\"p_err\"",
                          "\"aftershocks\"",
                          "\"p_inverse\"",
                          "\"delta_mu\"",
                          "\"delta_mw\"",
                          "\"cov\"",
                          "\"mean\"",
                          "\"K\"",
                          "\"c\"",
                          "\"p\"",
                          "\"seed\"",
                          "\"version\"",
                          "\"git\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

TEST_F(SeismicityCli, CsvAndHdf5CataloguesGiveTheSameJson) {
  if (!hdf5_available()) GTEST_SKIP() << "built without HDF5";
  const std::string h5 = dir_->file("run_h5");
  auto r = run_bkquake(test::run_args(kScene, {"--set", "output.catalog=hdf5", "--out", h5}));
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_bkquake({"seismicity", h5});
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_bkquake({"seismicity", run(), "--out", dir_->file("csv_out")});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string a = read_file(dir_->file("csv_out/seismicity.json"));
  const std::string b = read_file(h5 + "/seismicity/seismicity.json");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(without_provenance(a), without_provenance(b));
  EXPECT_EQ(read_file(dir_->file("csv_out/omori.csv"))
                .substr(read_file(dir_->file("csv_out/omori.csv")).find("side,")),
            read_file(h5 + "/seismicity/omori.csv")
                .substr(read_file(h5 + "/seismicity/omori.csv").find("side,")));
}

TEST_F(SeismicityCli, BareCatalogueTakesNFromItsExtentOrBlocks) {
  TempDir bare;
  fs::copy_file(fs::path(run()) / "catalog.csv", bare.path() / "cat.csv");
  auto r = run_bkquake({"seismicity", bare.file("cat.csv")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("N = 20, from max(last_block) + 1"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(bare.path() / "seismicity" / "seismicity.json"));
  r = run_bkquake(
      {"seismicity", bare.file("cat.csv"), "--blocks", "40", "--out", bare.file("o40")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("N = 40, from --blocks"), std::string::npos) << r.out;
  // Beside its scene.ini, --blocks must agree with it.
  r = run_bkquake({"seismicity", run(), "--blocks", "40", "--out", bare.file("x")});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--blocks = 40 contradicts"), std::string::npos) << r.err;
}

TEST_F(SeismicityCli, MergedFolderIsRefusedWithTheReason) {
  const std::string merged = dir_->file("merged"), other = dir_->file("other");
  auto r = run_bkquake(test::run_args(kScene, {"--set", "run.seed=7", "--out", other}));
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_bkquake({"merge", run(), other, "--out", merged});
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_bkquake({"seismicity", merged});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("is a merged folder: merged runs have no single clock"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(fs::path(merged) / "seismicity"));
}

TEST_F(SeismicityCli, ReplacesOnlyItsOwnFolderUnderTheLock) {
  const fs::path out = fs::path(run()) / "seismicity";
  fs::create_directories(out);
  test::TempDir scratch;
  std::ofstream(out / "stale.txt") << "from an earlier version";
  const std::string catalog = read_file(run() + "/catalog.csv");
  const std::string summary = read_file(run() + "/summary.json");
  {
    FolderLock held(run(), "test", StaleLock::Refuse);
    const auto r = run_bkquake({"seismicity", run()});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("bkquake test"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(out / "stale.txt"));
  }
  const auto r = run_bkquake({"seismicity", run()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(out / "stale.txt"));
  EXPECT_TRUE(fs::exists(out / "seismicity.json"));
  EXPECT_EQ(read_file(run() + "/catalog.csv"), catalog);
  EXPECT_EQ(read_file(run() + "/summary.json"), summary);
  for (const auto& e : fs::directory_iterator(run()))
    EXPECT_EQ(e.path().filename().string().rfind(".seismicity", 0), std::string::npos) << e.path();
  EXPECT_FALSE(fs::exists(fs::path(run()) / FolderLock::kFileName));
}

// A sweep folder: tests/regression/test_analysis_reliability.cpp runs a real sweep
// (SeismicityOfARealSweepAnalysesEveryReplica).

TEST_F(SeismicityCli, ExportUsesSeismologyConventions) {
  TempDir t;
  const auto r = run_bkquake({"seismicity", run(), "--out", t.file("o"), "--export",
                              t.file("quakes.csv"), "--mw-offset", "1.5"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream in(read_file(t.file("quakes.csv")));
  std::string line;
  while (std::getline(in, line) && line.rfind("#", 0) == 0) {
  }
  EXPECT_EQ(line, "time,Mw,x,length,mu,event");
  int rows = 0;
  while (std::getline(in, line)) {
    double time, mw, x, length, mu, event;
    ASSERT_EQ(
        std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &time, &mw, &x, &length, &mu, &event),
        6)
        << line;
    // Mw = (2/3) log10 M + C, so mu = ln M = 1.5 ln 10 (Mw - C).
    EXPECT_NEAR(mu, 1.5 * std::log(10.0) * (mw - 1.5), 1e-9 * (1 + std::abs(mu)));
    EXPECT_GE(x, 0);
    EXPECT_LT(x, 20);
    ++rows;
  }
  EXPECT_EQ(rows, 20000);
}

TEST_F(SeismicityCli, PlotDrawsUnderTheLockAndRefusesInOneLine) {
  const std::string python = "/usr/bin/python3";
  if (test::run_process(python, {"-c", "import numpy, matplotlib"}).status != 0)
    GTEST_SKIP() << "no numpy/matplotlib for /usr/bin/python3";
  const std::string script = std::string(BKQUAKE_SOURCE_DIR) + "/analysis/plot_seismicity.py";
  TempDir t;
  auto p = test::run_process(python, {script, t.path().string()});
  EXPECT_EQ(p.status, 1);
  EXPECT_NE(p.err.find("has no seismicity/ (run bkquake seismicity"), std::string::npos) << p.err;
  EXPECT_EQ(p.err.find("Traceback"), std::string::npos) << p.err;
  ASSERT_EQ(run_bkquake({"seismicity", run()}).status, 0);
  const fs::path png = fs::path(run()) / "seismicity" / "seismicity.png";
  {
    FolderLock held(run(), "test", StaleLock::Refuse);
    p = test::run_process(python, {script, run()});
    EXPECT_NE(p.status, 0);
    EXPECT_NE(p.err.find("is in use"), std::string::npos) << p.err;
    EXPECT_FALSE(fs::exists(png));
  }
  p = test::run_process(python, {script, run()});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_GT(fs::file_size(png), 20000u);
  EXPECT_FALSE(fs::exists(fs::path(run()) / FolderLock::kFileName));
}

TEST(SeismicityCliInput, BadInputIsOneLineAndExitTwo) {
  TempDir t;
  const std::string no_load = t.write("a.csv", "event,moment\n1,0.5\n2,0.7\n");
  auto r = run_bkquake({"seismicity", no_load, "--blocks", "4"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("missing column 'load'"), std::string::npos) << r.err;
  r = run_bkquake({"seismicity", no_load, "--blocks", "0"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--blocks = 0: expected at least 1"), std::string::npos) << r.err;
  const std::string no_extent = t.write("b.csv", "event,load,moment\n1,0.1,0.5\n2,0.2,0.7\n");
  r = run_bkquake({"seismicity", no_extent, "--blocks", "4"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("give --mainshock-mu X"), std::string::npos) << r.err;
  const std::string backwards =
      t.write("c.csv", "event,load,moment\n1,0.2,0.5\n2,0.1,0.7\n3,0.3,0.7\n");
  r = run_bkquake({"seismicity", backwards, "--blocks", "4", "--mainshock-mu", "0"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("must be in time order"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(t.path() / "seismicity"));
  r = run_bkquake({"seismicity", t.file("missing.csv")});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}

TEST(SeismicityDocs, ColumnTablesMatchTheSchemas) {
  const std::string page =
      read_file(std::string(BKQUAKE_SOURCE_DIR) + "/docs/explanation/seismicity.md");
  ASSERT_FALSE(page.empty());
  for (const auto& [name, schema] : seismicity_schemas()) {
    const auto block = readme_block(page, name);
    ASSERT_TRUE(block) << "docs/explanation/seismicity.md lacks the block of " << name << ":\n"
                       << readme_begin_marker(name) << "\n"
                       << column_table(*schema) << readme_end_marker(name);
    EXPECT_EQ(*block, column_table(*schema)) << name;
  }
}

}  // namespace
}  // namespace bkq
