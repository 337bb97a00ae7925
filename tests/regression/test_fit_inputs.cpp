// `bkquake fit` on everything that holds events: a catalogue, its histogram.csv, a run
// folder, a merged folder and a sweep folder give the same binned b where both apply (the
// histogram of a catalogue is all the binned fit reads); on an exact exponential the
// catalogue's and the histogram's b agree with each other and with the truth; --scan
// writes b_scan.csv under the folder's lock; `merge --mu-min/--mu-max` fixes the window;
// a sweep folder is refitted into sweep_fit.csv without rerunning.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "core/format.hpp"
#include "io/b_scan_csv.hpp"
#include "io/histogram_csv.hpp"
#include "io/run_folder.hpp"
#include "io/schema.hpp"
#include "io/sweep_file.hpp"
#include "stats/histogram.hpp"

namespace bkq {
namespace {

using test::run_bkquake;
using test::TempDir;

const std::string kSource = BKQUAKE_SOURCE_DIR;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// b_mle (and its errors) of `bkquake fit ARGS --json`, read back from the JSON's fit object.
struct Fitted {
  double b = NAN, err = NAN, sys = NAN, b_mw = NAN;
};
Fitted fit(const TempDir& dir, std::vector<std::string> args, const std::string& tag) {
  const std::string json = dir.file(tag + ".json");
  args.insert(args.begin(), "fit");
  args.push_back("--json");
  args.push_back(json);
  const auto r = run_bkquake(args);
  EXPECT_EQ(r.status, 0) << r.err;
  // The top-level keys of the fit object are unique in the file ("fit": {...}).
  const std::string text = slurp(json);
  const auto number = [&](const std::string& key) -> double {
    const auto at = text.find("\"" + key + "\":");
    if (at == std::string::npos) return NAN;
    return std::strtod(text.c_str() + at + key.size() + 3, nullptr);
  };
  return {number("b_mle"), number("b_mle_err"), number("b_mle_sys_err"), number("b_mw")};
}

TEST(FitInputs, CatalogueAndItsHistogramAgreeWithTheTruthOnAnExactExponential) {
  TempDir dir;
  std::mt19937_64 rng(21);
  std::exponential_distribution<double> exp_b(0.9);  // b = 0.9 above mu = -3
  MagnitudeHistogram h;
  std::string csv = "moment\n";
  for (int i = 0; i < 40000; ++i) {
    const double mu = -3.0 + exp_b(rng);
    h.add(mu);
    csv += format_real(std::exp(mu)) + "\n";
  }
  dir.write("catalog.csv", csv);
  write_histogram_csv(h, dir.file("hist.csv"));
  const Fitted c = fit(dir, {dir.file("catalog.csv"), "--mu-min", "-3"}, "c");
  const Fitted hh = fit(dir, {dir.file("hist.csv"), "--mu-min", "-3"}, "h");
  EXPECT_DOUBLE_EQ(c.b, hh.b);  // the same counts: the same binned b
  EXPECT_NEAR(c.b, 0.9, 2 * c.err);
  EXPECT_NEAR(hh.b, 0.9, 2 * hh.err);
  EXPECT_DOUBLE_EQ(c.b_mw, 1.5 * c.b);
  EXPECT_TRUE(std::isfinite(c.sys));
  // A histogram's bins are fixed: another width is refused, naming the option and the width.
  const auto r = run_bkquake({"fit", dir.file("hist.csv"), "--bin-width", "0.1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--bin-width 0.1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("width 0.2"), std::string::npos) << r.err;
}

TEST(FitInputs, FolderHistogramAndMergedFolderGiveTheCatalogueB) {
  TempDir dir;
  const std::string scene = kSource + "/data/scenes/carlson-langer.ini";
  for (const char* name : {"a", "b"}) {
    const auto r =
        run_bkquake({"run", scene, "--set", "run.events=3000", "--set", "run.transient_events=200",
                     "--set", std::string("run.seed=") + (name[0] == 'a' ? "5" : "6"), "--out",
                     dir.file(name), "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const std::vector<std::string> window = {"--mu-min", "-7.6", "--mu-max", "-2"};
  const auto with = [&](std::string input) {
    std::vector<std::string> a{std::move(input)};
    a.insert(a.end(), window.begin(), window.end());
    return a;
  };
  const Fitted cat = fit(dir, with(dir.file("a/catalog.csv")), "cat");
  const Fitted folder = fit(dir, with(dir.file("a")), "folder");
  const Fitted hist = fit(dir, with(dir.file("a/histogram.csv")), "hist");
  ASSERT_TRUE(std::isfinite(cat.b));
  EXPECT_DOUBLE_EQ(folder.b, cat.b);
  EXPECT_DOUBLE_EQ(hist.b, cat.b);
  EXPECT_DOUBLE_EQ(hist.sys, cat.sys);
  // The automatic window too: the catalogue and its histogram are the same counts.
  EXPECT_DOUBLE_EQ(fit(dir, {dir.file("a")}, "fa").b,
                   fit(dir, {dir.file("a/histogram.csv")}, "ha").b);

  // Merged with the window on the command line; the merged folder refits to the b of the
  // two catalogues concatenated.
  const auto m = run_bkquake({"merge", dir.file("a"), dir.file("b"), "--out", dir.file("m"),
                              "--mu-min", "-7.6", "--mu-max", "-2"});
  ASSERT_EQ(m.status, 0) << m.err;
  EXPECT_DOUBLE_EQ(read_json_number(dir.file("m/summary.json"), "mu_min").value_or(NAN), -7.6);
  const double merged_b = read_json_number(dir.file("m/summary.json"), "b_mle").value_or(NAN);
  std::string both = slurp(dir.file("a/catalog.csv"));
  const std::string second = slurp(dir.file("b/catalog.csv"));
  both += second.substr(second.find('\n') + 1);
  dir.write("both.csv", both);
  const Fitted all = fit(dir, with(dir.file("both.csv")), "all");
  const Fitted refit = fit(dir, with(dir.file("m")), "m");
  EXPECT_DOUBLE_EQ(refit.b, all.b);
  EXPECT_DOUBLE_EQ(merged_b, all.b);
  // A contradictory window is refused by merge with the one-line error.
  const auto bad = run_bkquake({"merge", dir.file("a"), dir.file("b"), "--out", dir.file("m2"),
                                "--mu-min", "1", "--mu-max", "0"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--mu-max must be greater than --mu-min"), std::string::npos) << bad.err;

  // --scan: b_scan.csv into the folder fitted, under its lock, the schema's header, and as
  // many accepted windows as the fit's systematic error was taken over.
  const auto s = run_bkquake({"fit", dir.file("a"), "--scan"});
  ASSERT_EQ(s.status, 0) << s.err;
  const std::string scan = slurp(dir.file("a/b_scan.csv"));
  EXPECT_EQ(scan.substr(0, scan.find('\n')), header_of(b_scan_schema()));
  EXPECT_GT(std::count(scan.begin(), scan.end(), '\n'), 20);
  EXPECT_NE(scan.find(",1\n"), std::string::npos);                    // some window is accepted
  EXPECT_FALSE(std::filesystem::exists(dir.file("a/bkquake.lock")));  // released
  // --out puts it elsewhere; the run's own files are untouched.
  const std::string before = slurp(dir.file("a/summary.json"));
  ASSERT_EQ(run_bkquake({"fit", dir.file("a"), "--scan", "--out", dir.file("scan")}).status, 0);
  EXPECT_TRUE(std::filesystem::exists(dir.file("scan/b_scan.csv")));
  EXPECT_EQ(slurp(dir.file("a/summary.json")), before);
}

TEST(FitInputs, ASweepFolderIsRefittedIntoSweepFit) {
  TempDir dir;
  dir.write("s.ini", R"([sweep]
replicas = 1
[vary]
friction.alpha = 2.5, 3
[set]
run.events = 2000
run.transient_events = 100
)");
  const auto r = run_bkquake({"sweep", dir.file("s.ini"), "--out", dir.file("sw")});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string sweep_csv = slurp(dir.file("sw/sweep.csv"));
  EXPECT_NE(sweep_csv.find("b_sys_err,b_mw"), std::string::npos);
  const auto f = run_bkquake({"fit", dir.file("sw"), "--mu-min", "-7.6", "--mu-max", "-2"});
  ASSERT_EQ(f.status, 0) << f.err;
  const std::string out = slurp(dir.file("sw/sweep_fit.csv"));
  std::istringstream lines(out);
  std::string header, row0, row1;
  std::getline(lines, header);
  std::getline(lines, row0);
  std::getline(lines, row1);
  EXPECT_EQ(header,
            "point,friction.alpha,events,b,b_err,b_sys_err,b_mw,mu_min,mu_max,tau_measure,tau,"
            "tau_err,tau_x_min,tau_x_max,tau_p,tau_error,error");
  // Point 0's b is the b of its merged histogram on the same window.
  const Fitted p0 = fit(
      dir, {dir.file("sw/points/p0000/histogram.csv"), "--mu-min", "-7.6", "--mu-max", "-2"}, "p0");
  std::vector<std::string> fields;
  std::stringstream row(row0);
  for (std::string x; std::getline(row, x, ',');) fields.push_back(x);
  ASSERT_GE(fields.size(), 9u) << row0;
  EXPECT_EQ(fields[0], "0");
  EXPECT_EQ(fields[1], "2.5");
  EXPECT_DOUBLE_EQ(std::strtod(fields[3].c_str(), nullptr), p0.b);
  EXPECT_DOUBLE_EQ(std::strtod(fields[7].c_str(), nullptr), -7.6);
  EXPECT_EQ(row1.substr(0, 2), "1,");
  // A chain's point has no tau unless a measure is asked for.
  EXPECT_EQ(row0.substr(row0.size() - 11), ",-2,,,,,,,,") << row0;

  // With --measure blocks: tau over the point's replica catalogue, the same as fitting that
  // catalogue itself (one replica).
  const auto m = run_bkquake({"fit", dir.file("sw"), "--measure", "blocks"});
  ASSERT_EQ(m.status, 0) << m.err;
  std::istringstream tau_lines(slurp(dir.file("sw/sweep_fit.csv")));
  std::getline(tau_lines, header);
  std::getline(tau_lines, row0);
  fields.clear();
  std::stringstream tau_row(row0);
  for (std::string x; std::getline(tau_row, x, ',');) fields.push_back(x);
  ASSERT_GE(fields.size(), 15u) << row0;
  EXPECT_EQ(fields[9], "blocks");
  const std::string json = dir.file("r.json");
  const auto one =
      run_bkquake({"fit", dir.file("sw/points/p0000/r00"), "--measure", "blocks", "--json", json});
  ASSERT_EQ(one.status, 0) << one.err;
  const std::string text = slurp(json);
  const auto at = text.find("\"value\":");
  ASSERT_NE(at, std::string::npos) << text;
  EXPECT_DOUBLE_EQ(std::strtod(fields[10].c_str(), nullptr),
                   std::strtod(text.c_str() + at + 8, nullptr))
      << row0;
  EXPECT_GT(std::strtod(fields[11].c_str(), nullptr), 0) << row0;
}

TEST(FitInputs, AnOfcSweepGetsTauOfTheTopplingsWithoutBeingAsked) {
  TempDir dir;
  dir.write("s.ini", "[sweep]\nscene = " + std::string(BKQUAKE_SOURCE_DIR) +
                         "/data/scenes/lattice/ofc-256-a020.ini\n"
                         "replicas = 1\ncollect = catalog, histogram, summary\n"
                         "[vary]\nofc.alpha = 0.2\n"
                         "[set]\nmodel.blocks = 16\nmodel.rows = 16\n"
                         "run.transient_events = 5000\nrun.events = 20000\n");
  const auto r = run_bkquake({"sweep", dir.file("s.ini"), "--out", dir.file("sw")});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto f = run_bkquake({"fit", dir.file("sw")});
  ASSERT_EQ(f.status, 0) << f.err;
  std::istringstream lines(slurp(dir.file("sw/sweep_fit.csv")));
  std::string header, row0;
  std::getline(lines, header);
  std::getline(lines, row0);
  std::vector<std::string> names, fields;
  std::stringstream h(header), row(row0);
  for (std::string x; std::getline(h, x, ',');) names.push_back(x);
  for (std::string x; std::getline(row, x, ',');) fields.push_back(x);
  ASSERT_GE(fields.size(), names.size()) << header << "\n" << row0;  // the error text has commas
  const auto column = [&](const std::string& name) {
    const auto at = std::find(names.begin(), names.end(), name);
    return at == names.end() ? std::string("missing") : fields[at - names.begin()];
  };
  EXPECT_EQ(column("tau_measure"), "topplings") << row0;
  // Either a tau with a positive error or none with its reason.
  if (column("tau").empty()) {
    EXPECT_FALSE(column("tau_error").empty()) << row0;
  } else {
    EXPECT_GT(std::strtod(column("tau").c_str(), nullptr), 1.0) << row0;
    EXPECT_GT(std::strtod(column("tau_err").c_str(), nullptr), 0.0) << row0;
  }
}

}  // namespace
}  // namespace bkq
