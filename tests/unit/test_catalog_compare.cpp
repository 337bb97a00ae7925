// bkquake compare and the statistics behind it (stats/catalog_compare.hpp, app/compare.hpp):
// identical catalogues give KS 0 and the same recurrence, a shifted one the KS distance of the
// shift, periodic large events COV 0; the aftershock fit is read from seismicity.json; bad
// input (one run, a missing folder, an empty or inverted window) is one line naming the value.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/compare.hpp"
#include "cli_helpers.hpp"
#include "core/error.hpp"
#include "io/json.hpp"
#include "stats/catalog_compare.hpp"

namespace {

namespace fs = std::filesystem;

TEST(CatalogCompare, KsDistanceOfSamples) {
  std::vector<double> a, b;
  for (int i = 0; i < 100; ++i) {
    a.push_back(i);
    b.push_back(i + 10);
  }
  EXPECT_EQ(bkq::ks_distance(a, a), 0.0);
  EXPECT_NEAR(bkq::ks_distance(a, b), 0.1, 1e-12);  // 10 of 100 values shifted past the other's
  EXPECT_NEAR(bkq::ks_distance(b, a), 0.1, 1e-12);
  EXPECT_EQ(bkq::ks_distance({1, 2}, {3, 4, 5}), 1.0);
  EXPECT_DOUBLE_EQ(bkq::ks_distance({1, 1, 2}, {1, 2, 2}), 1.0 / 3);  // ties counted together
  EXPECT_TRUE(std::isnan(bkq::ks_distance({}, a)));
  EXPECT_NEAR(bkq::ks_critical_5pct(100, 100), 1.358 * std::sqrt(0.02), 1e-12);
  EXPECT_DOUBLE_EQ(bkq::quantile({4, 1, 3, 2}, 0.5), 2.5);
}

TEST(CatalogCompare, RecurrenceOfPeriodicAndIdenticalTimes) {
  const bkq::Recurrence p = bkq::recurrence_of({1, 3, 5, 7, 9});
  EXPECT_EQ(p.count, 5u);
  EXPECT_EQ(p.intervals, 4u);
  EXPECT_DOUBLE_EQ(p.mean, 2.0);
  EXPECT_NEAR(p.cov, 0.0, 1e-12);
  const std::vector<double> t = {0.5, 1, 4, 4.5, 9, 13, 13.2};
  const bkq::Recurrence a = bkq::recurrence_of(t), b = bkq::recurrence_of(t);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.cov, b.cov);
  EXPECT_GT(a.cov, 0.5);
  EXPECT_GT(a.cov_err, 0.0);
  EXPECT_TRUE(std::isnan(bkq::recurrence_of({1, 2}).cov));  // one interval: no spread
}

// Runs pooled: the intervals lie within each run, never across two.
TEST(CatalogCompare, RecurrenceOfRunsPooledKeepsIntervalsWithinEachRun) {
  const bkq::Recurrence r = bkq::recurrence_of_runs({{1, 3, 5}, {100, 104}, {7}});
  EXPECT_EQ(r.count, 6u);
  EXPECT_EQ(r.intervals, 3u);
  EXPECT_DOUBLE_EQ(r.mean, 8.0 / 3.0);
  EXPECT_EQ(bkq::intervals_of_runs({{1, 3, 5}, {100, 104}}), (std::vector<double>{2, 2, 4}));
  const bkq::Recurrence one = bkq::recurrence_of_runs({{1, 3, 5, 7, 9}});
  EXPECT_EQ(one.mean, bkq::recurrence_of({1, 3, 5, 7, 9}).mean);
}

TEST(CatalogCompare, JsonNumbersAtDottedPaths) {
  const std::string t = R"({"a": {"b": 2.5, "c": null, "s": "x"}, "d": 1, "e": null})";
  EXPECT_EQ(bkq::json_number_at(t, "a.b", "t"), 2.5);
  EXPECT_EQ(bkq::json_number_at(t, "d", "t"), 1.0);
  EXPECT_FALSE(bkq::json_number_at(t, "a.c", "t"));  // null
  EXPECT_FALSE(bkq::json_number_at(t, "a.x", "t"));  // absent
  EXPECT_FALSE(bkq::json_number_at(t, "x.b", "t"));  // no such object
  EXPECT_FALSE(bkq::json_number_at(t, "e.b", "t"));  // a null object
  EXPECT_EQ(bkq::json_string_at(t, "a.s", "t"), std::string("x"));
  EXPECT_THROW(bkq::json_number_at(t, "d.b", "t"), bkq::Error);  // d is a number
  EXPECT_THROW(bkq::json_number_at(t, "a.s", "t"), bkq::Error);  // a string
}

// A run folder with a catalogue: event k at load k/1000, mu = k/1000 + shift (k = 0..999),
// with `large` every 50th event large (mu + 5).
fs::path make_run(const fs::path& dir, double shift, bool large = true) {
  fs::create_directories(dir);
  std::ofstream c(dir / "catalog.csv");
  c << "event,load,moment\n";
  c.precision(17);
  for (int k = 0; k < 1000; ++k)
    c << k + 1 << "," << k / 1000.0 << ","
      << std::exp(k / 1000.0 + shift + (k % 50 || !large ? 0 : 5)) << "\n";
  return dir;
}

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("bkq_test_compare_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// The table row of `run` (from "| run |" to the line's end), the n-th table (0-based).
std::string row(const std::string& out, const std::string& run, int n) {
  std::size_t at = 0;
  for (int i = 0; i <= n; ++i) {
    at = out.find("| " + run + " |", at + (i ? 1 : 0));
    if (at == std::string::npos) return "";
  }
  return out.substr(at, out.find('\n', at) - at);
}

TEST(CatalogCompare, IdenticalRunsGiveKsZeroAndTheSameRecurrence) {
  const fs::path d = scratch("same");
  make_run(d / "a", 0);
  make_run(d / "b", 0);
  const auto r = bkq::test::run_process(
      BKQUAKE_BINARY, {"compare", (d / "a").string(), (d / "b").string(), "--mu-large", "4"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string ma = row(r.out, "a", 0), mb = row(r.out, "b", 0);
  EXPECT_EQ(mb, "| b |" + ma.substr(5)) << r.out;  // the same numbers, KS 0
  EXPECT_NE(mb.find("| 0 |"), std::string::npos) << mb;
  const std::string ra = row(r.out, "a", 1), rb = row(r.out, "b", 1);
  EXPECT_NE(ra.find("| 20 ± 4.472 |"), std::string::npos) << r.out;  // 1000/50 large events
  EXPECT_EQ(rb, "| b |" + ra.substr(5)) << r.out;
  fs::remove_all(d);
}

TEST(CatalogCompare, AShiftedCatalogueGivesTheShiftsKsDistance) {
  const fs::path d = scratch("shift");
  make_run(d / "a", 0, false);
  make_run(d / "b", 0.1005, false);  // mu uniform on [0, 1): a shift s moves the CDF by s
  bkq::CompareRequest req;
  req.runs = {(d / "a").string(), (d / "b").string()};
  req.mu_large = 0.9;
  const bkq::CompareReport rep = bkq::compare_runs(req);
  // On the grid of 1000 values the distance is 101/1000 (just below 0.1005 + j/1000, a has
  // 101 + j values, b has j): the 100.5 shifted steps rounded up.
  EXPECT_NEAR(rep.runs[1].ks_mu, 0.101, 1e-9);
  EXPECT_EQ(rep.runs[0].ks_mu, 0.0);
  EXPECT_EQ(rep.runs[0].recurrence.count, 100u);  // mu >= 0.9: k = 900..999
  EXPECT_EQ(rep.runs[1].recurrence.count, 200u);  // mu >= 0.9: k = 800..999
  EXPECT_NEAR(rep.runs[1].recurrence.mean, 0.001, 1e-12);
  // A window keeps only its events: 0.5 < load <= 0.7 holds 200.
  req.from = 0.5;
  req.to = 0.7;
  EXPECT_EQ(bkq::compare_runs(req).runs[0].mu.size(), 200u);
  fs::remove_all(d);
}

TEST(CatalogCompare, ReadsTheOmoriFitOfSeismicityJson) {
  const fs::path d = scratch("omori");
  make_run(d / "a", 0);
  make_run(d / "b", 0);
  fs::create_directories(d / "a" / "seismicity");
  std::ofstream(d / "a" / "seismicity" / "seismicity.json")
      << "{\"mainshocks\": {\"rule\": \"events with mu >= 4 (--mainshock-mu)\", \"count\": 20},"
         " \"omori\": {\"sequences\": 20, \"excess\": true, \"K\": 3.5, \"K_err\": 0.5,"
         " \"c\": 0.001, \"c_err\": 0.0002, \"p\": 1.07, \"p_err\": 0.05, \"aftershocks\": 42},"
         " \"bath\": {\"window\": 0.03}}";
  const auto r = bkq::test::run_process(
      BKQUAKE_BINARY, {"compare", (d / "a").string(), (d / "b").string(), "--mu-large", "4"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(row(r.out, "a", 2), "| a | 20 | 1.07 ± 0.05 | 0.001 ± 0.0002 | 3.5 ± 0.5 | 42 | 0.03 |")
      << r.out;
  EXPECT_NE(row(r.out, "b", 2).find("no seismicity/seismicity.json"), std::string::npos) << r.out;
  fs::remove_all(d);
}

// A group (folders separated by commas) pools its runs: two copies of a run against the run
// give KS 0, twice its large events (10 a run, no spread), and its intervals (KS 0): none
// across the two copies. A shifted member moves the pooled distribution by half its shift.
TEST(CatalogCompare, AGroupPoolsItsRuns) {
  const fs::path d = scratch("group");
  make_run(d / "a", 0);
  make_run(d / "b", 0);
  make_run(d / "s", 0.1005);
  const std::string a = (d / "a").string(), b = (d / "b").string(), s = (d / "s").string();
  bkq::CompareRequest req;
  req.runs = {a, a + "," + b, a + "," + s};
  req.mu_large = 4;
  const bkq::CompareReport rep = bkq::compare_runs(req);
  const bkq::CompareRun& g = rep.runs[1];
  EXPECT_EQ(g.members.size(), 2u);
  EXPECT_EQ(g.mu.size(), 2000u);
  EXPECT_EQ(g.ks_mu, 0.0);
  EXPECT_EQ(g.recurrence.count, 40u);
  EXPECT_EQ(g.recurrence.intervals, 38u);  // 19 within each copy
  EXPECT_DOUBLE_EQ(g.recurrence.mean, rep.runs[0].recurrence.mean);
  EXPECT_EQ(g.ks_intervals, 0.0);
  EXPECT_DOUBLE_EQ(g.large_mean, 20.0);
  EXPECT_EQ(g.large_sd, 0.0);
  EXPECT_TRUE(std::isnan(rep.runs[0].large_sd));  // one run: no spread
  EXPECT_NEAR(rep.runs[2].ks_mu, 0.0505, 1e-3);   // half the members shifted by 0.1005
  const auto r =
      bkq::test::run_process(BKQUAKE_BINARY, {"compare", a, a + "," + b, "--mu-large", "4"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(row(r.out, "a,… (2 runs)", 1).find("| 40 ± 6.325 | 20 ± 0 |"), std::string::npos)
      << r.out;
  EXPECT_NE(row(r.out, "a,… (2 runs)", 2).find("a group"), std::string::npos) << r.out;
  fs::remove_all(d);
}

// A group of many relative folder names is longer than a file name may be: it is still read
// as a group (the check whether it is one folder must not throw).
TEST(CatalogCompare, AGroupLongerThanAFileNameIsAGroup) {
  const fs::path d = scratch("long");
  make_run(d / "a", 0);
  std::string group = "a";
  for (int i = 1; i < 150; ++i) group += ",a";
  ASSERT_GT(group.size(), 255u);
  const fs::path cwd = fs::current_path();
  fs::current_path(d);
  bkq::CompareRequest req;
  req.runs = {"a", group};
  req.mu_large = 4;
  std::size_t members = 0;
  double ks = -1;
  try {
    const bkq::CompareReport rep = bkq::compare_runs(req);
    members = rep.runs[1].members.size();
    ks = rep.runs[1].ks_mu;
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
  }
  fs::current_path(cwd);
  EXPECT_EQ(members, 150u);
  EXPECT_EQ(ks, 0.0);
  fs::remove_all(d);
}

TEST(CatalogCompare, BadInputIsOneLineNamingTheValue) {
  const fs::path d = scratch("bad");
  make_run(d / "a", 0);
  const std::string a = (d / "a").string(), missing = (d / "missing").string();
  const auto one_line = [](const bkq::test::ProcessResult& r, const std::string& what) {
    EXPECT_EQ(r.status, 2) << r.err;
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
  };
  one_line(bkq::test::run_process(BKQUAKE_BINARY, {"compare", a, missing}), missing);
  one_line(bkq::test::run_process(BKQUAKE_BINARY, {"compare", a}), "two or more");
  one_line(bkq::test::run_process(BKQUAKE_BINARY, {"compare", a, a + "," + missing}), missing);
  one_line(bkq::test::run_process(BKQUAKE_BINARY, {"compare", a, a + ",," + a}),
           "an empty folder name in a group");
  const std::string too_long(300, 'x');  // longer than a file name may be
  one_line(bkq::test::run_process(BKQUAKE_BINARY, {"compare", a, too_long}), "no such folder");
  one_line(bkq::test::run_process(BKQUAKE_BINARY, {"compare", a, a, "--from", "5"}),
           "no events with 5 < load");
  one_line(
      bkq::test::run_process(BKQUAKE_BINARY, {"compare", a, a, "--from", "0.5", "--to", "0.2"}),
      "--from = 0.5 is not below --to = 0.2");
  one_line(bkq::test::run_process(BKQUAKE_BINARY, {"compare", a, a, "--large-quantile", "1.5"}),
           "--large-quantile = 1.5");
  fs::remove_all(d);
}

}  // namespace
