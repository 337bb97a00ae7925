// output.catalog = csv | hdf5 | none: catalog.h5 holds the rows of catalog.csv exactly and
// `bkquake fit` reads both alike; none still writes the histogram and the fit; a run
// killed with SIGKILL resumes its catalog.h5 to the table of a run that never stopped; a
// damaged catalog.h5 is refused with exit 2 and one line, by fit and by --resume; the
// analysis loader returns the same arrays for both formats. Short runs as subprocesses.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "io/catalog.hpp"
#include "io/catalog_h5.hpp"
#include "io/checkpoint.hpp"
#include "io/csv_util.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::run_bkquake;

std::vector<std::string> run_args(const std::string& out, const std::string& format,
                                  const std::string& events = "3000") {
  return {"run",
          "--set",
          "model.blocks=50",
          "--set",
          "run.events=" + events,
          "--set",
          "run.transient_events=100",
          "--set",
          "output.catalog=" + format,
          "--out",
          out,
          "--quiet"};
}

std::vector<std::string> schema_names() {
  std::vector<std::string> names;
  for (const auto& c : catalog_schema()) names.emplace_back(c.name);
  return names;
}

// Every value of catalog.csv, row by row, as doubles.
std::vector<double> csv_values(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, catalog_header());
  std::vector<double> v;
  while (std::getline(in, line))
    for (const auto f : csv::split(line)) v.push_back(std::strtod(std::string(f).c_str(), nullptr));
  return v;
}

// Every value of catalog.h5's table, row by row, as doubles.
std::vector<double> h5_values(const std::string& path) {
  CatalogH5Reader r(path, schema_names());
  for (std::size_t k = 0; k < catalog_schema().size(); ++k) EXPECT_TRUE(r.has(k));
  std::vector<double> all, block;
  while (r.next_block(block) > 0) all.insert(all.end(), block.begin(), block.end());
  return all;
}

// Equal value by value, NaN equal to NaN.
bool same(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  return true;
}

// Exit 2 and one error line naming `part` (a resume may say first that it took over the
// lock of the killed run).
void expect_one_line_refusal(const test::ProcessResult& r, const std::string& part) {
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  std::vector<std::string> errors;
  for (const auto& line : r.err_lines())
    if (line.find("stale lock") == std::string::npos) errors.push_back(line);
  ASSERT_EQ(errors.size(), 1u) << r.err;
  EXPECT_NE(errors[0].find(part), std::string::npos) << errors[0];
}

// A name longer than a file name may be is refused as one that does not exist, in one line
// (the checks on it must not throw a filesystem error).
TEST(FitInput, ANameLongerThanAFileNameIsOneLine) {
  const std::string too_long(300, 'x');
  expect_one_line_refusal(run_bkquake({"fit", too_long}), "does not exist");
}

class CatalogFormats : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!hdf5_available()) GTEST_SKIP() << "built without HDF5";
  }
  test::TempDir tmp_;
};

TEST_F(CatalogFormats, Hdf5HoldsTheCsvRowsAndFitReadsBothAlike) {
  const std::string a = tmp_.file("csv"), b = tmp_.file("h5");
  ASSERT_EQ(run_bkquake(run_args(a, "csv")).status, 0);
  ASSERT_EQ(run_bkquake(run_args(b, "hdf5")).status, 0);
  EXPECT_FALSE(fs::exists(b + "/catalog.csv"));
  const std::vector<double> rows = csv_values(a + "/catalog.csv");
  ASSERT_EQ(rows.size(), 3000 * catalog_schema().size());
  EXPECT_TRUE(same(rows, h5_values(b + "/catalog.h5")));
  EXPECT_EQ(read_file(a + "/histogram.csv"), read_file(b + "/histogram.csv"));

  const auto fa = run_bkquake({"fit", a + "/catalog.csv"});
  const auto fb = run_bkquake({"fit", b + "/catalog.h5"});
  ASSERT_EQ(fa.status, 0) << fa.err;
  ASSERT_EQ(fb.status, 0) << fb.err;
  // The same report but for the first line, which names the file.
  EXPECT_EQ(fa.out.substr(fa.out.find('\n')), fb.out.substr(fb.out.find('\n')));
  EXPECT_NE(fb.out.find("classes"), std::string::npos) << "blocks/first/last read from the h5";
}

// hdf5-deflate: the same rows, shuffled and deflated, in a smaller file.
TEST_F(CatalogFormats, Hdf5DeflateHoldsTheSameRowsInASmallerFile) {
  const std::string a = tmp_.file("h5"), b = tmp_.file("h5z");
  ASSERT_EQ(run_bkquake(run_args(a, "hdf5")).status, 0);
  ASSERT_EQ(run_bkquake(run_args(b, "hdf5-deflate")).status, 0);
  EXPECT_TRUE(same(h5_values(a + "/catalog.h5"), h5_values(b + "/catalog.h5")));
  EXPECT_LT(fs::file_size(b + "/catalog.h5"), fs::file_size(a + "/catalog.h5") / 2);
  EXPECT_EQ(read_file(a + "/histogram.csv"), read_file(b + "/histogram.csv"));
}

TEST_F(CatalogFormats, NoneWritesNoCatalogButTheHistogramAndTheFit) {
  const std::string a = tmp_.file("csv"), n = tmp_.file("none");
  ASSERT_EQ(run_bkquake(run_args(a, "csv")).status, 0);
  const auto r = run_bkquake(run_args(n, "none"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(n + "/catalog.csv"));
  EXPECT_FALSE(fs::exists(n + "/catalog.h5"));
  EXPECT_EQ(read_file(a + "/histogram.csv"), read_file(n + "/histogram.csv"));
  const std::string summary = read_file(n + "/summary.json");
  EXPECT_NE(summary.find("\"b_mle\""), std::string::npos) << summary;
  // A forced rerun with another format leaves no catalogue of the old one behind.
  ASSERT_EQ(run_bkquake(run_args(a, "none", "2000")).status, 2) << "a finished run is kept";
  auto force = run_args(a, "hdf5", "2000");
  force.push_back("--force");
  ASSERT_EQ(run_bkquake(force).status, 0);
  EXPECT_FALSE(fs::exists(a + "/catalog.csv"));
  EXPECT_TRUE(fs::exists(a + "/catalog.h5"));
}

TEST_F(CatalogFormats, Hdf5ResumesAfterSigkillToTheTableOfAStraightRun) {
  const std::string straight = tmp_.file("straight"), out = tmp_.file("out");
  auto args = [&](const std::string& dir) {
    auto a = run_args(dir, "hdf5", "200000");
    a.insert(a.end(), {"--set", "run.checkpoint_events=20000"});
    return a;
  };
  ASSERT_EQ(run_bkquake(args(straight)).status, 0);
  // Killed once two checkpoints are on disk, between checkpoints.
  const int status = test::run_and_signal_when(
      args(out), [&] { return fs::exists(out + "/checkpoint.prev.bin"); }, SIGKILL);
  ASSERT_EQ(status, 128 + SIGKILL);
  const Checkpoint c = CheckpointFiles(out).read();
  ASSERT_LT(c.progress.events_done, 200000);
  // The killed file is readable as it stands, and holds at least the checkpoint's rows.
  const auto fit = run_bkquake({"fit", out + "/catalog.h5"});
  EXPECT_EQ(fit.status, 0) << fit.err;

  const auto r = run_bkquake({"run", out + "/scene.ini", "--out", out, "--resume", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<double> want = h5_values(straight + "/catalog.h5");
  ASSERT_EQ(want.size(), 200000 * catalog_schema().size());
  EXPECT_TRUE(same(h5_values(out + "/catalog.h5"), want));
  EXPECT_EQ(read_file(out + "/histogram.csv"), read_file(straight + "/histogram.csv"));
}

TEST_F(CatalogFormats, DamagedHdf5IsRefusedWithExit2AndOneLine) {
  const std::string run = tmp_.file("h5");
  ASSERT_EQ(run_bkquake(run_args(run, "hdf5")).status, 0);
  const std::string whole = read_file(run + "/catalog.h5");
  ASSERT_GT(whole.size(), 4000u);
  const std::string truncated = tmp_.write("truncated.h5", whole.substr(0, whole.size() / 2));
  expect_one_line_refusal(run_bkquake({"fit", truncated}), "truncated.h5");
  std::string flipped = whole;
  for (std::size_t i = 600; i < flipped.size(); i += 97)
    flipped[i] = static_cast<char>(~flipped[i]);
  const std::string garbled = tmp_.write("garbled.h5", flipped);
  expect_one_line_refusal(run_bkquake({"fit", garbled}), "garbled.h5");
  expect_one_line_refusal(run_bkquake({"fit", tmp_.write("tiny.h5", whole.substr(0, 100))}),
                          "tiny.h5");

  // A resume refuses a damaged catalog.h5 and changes nothing.
  const std::string out = tmp_.file("out");
  auto args = run_args(out, "hdf5", "200000");
  args.insert(args.end(), {"--set", "run.checkpoint_events=20000"});
  ASSERT_EQ(test::run_and_signal_when(
                args, [&] { return fs::exists(out + "/checkpoint.prev.bin"); }, SIGKILL),
            128 + SIGKILL);
  const std::string damaged = whole.substr(0, whole.size() / 3);
  tmp_.write("out/catalog.h5", damaged);
  const auto r = run_bkquake({"run", out + "/scene.ini", "--out", out, "--resume", "--quiet"});
  expect_one_line_refusal(r, "catalog.h5");
  EXPECT_EQ(read_file(out + "/catalog.h5"), damaged);
}

TEST_F(CatalogFormats, PythonLoaderReturnsTheSameArraysForBothFormats) {
  if (std::system("/usr/bin/python3 -c 'import h5py, numpy' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "/usr/bin/python3 with h5py and numpy not installed";
  const std::string a = tmp_.file("csv"), b = tmp_.file("h5");
  ASSERT_EQ(run_bkquake(run_args(a, "csv", "500")).status, 0);
  ASSERT_EQ(run_bkquake(run_args(b, "hdf5", "500")).status, 0);
  const std::string script = tmp_.write("check.py",
                                        "import sys\n"
                                        "sys.path.insert(0, '" BKQUAKE_SOURCE_DIR
                                        "/analysis')\n"
                                        "import numpy as np\n"
                                        "import bkquake_io\n"
                                        "a = bkquake_io.load_catalog(sys.argv[1])\n"
                                        "b = bkquake_io.load_catalog(sys.argv[2])\n"
                                        "assert list(a) == list(b), (list(a), list(b))\n"
                                        "assert len(a['event']) == 500\n"
                                        "for k in a:\n"
                                        "    assert a[k].dtype == b[k].dtype, k\n"
                                        "    assert np.array_equal(a[k], b[k], equal_nan=True), k\n"
                                        "print('same')\n");
  const auto r = test::run_process("/usr/bin/python3", {script, a, b});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "same\n");
}

}  // namespace
}  // namespace bkq
