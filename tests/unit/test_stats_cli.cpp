// The fit and merge commands end to end through the program: a synthetic catalogue is
// fitted (text and JSON), bad input exits 2 with a one-line message naming the file, and
// merge refuses runs with different bin widths; the app functions behind them run without
// the program.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "app/fit.hpp"
#include "app/merge.hpp"
#include "core/error.hpp"

namespace {

namespace fs = std::filesystem;

struct Result {
  int rc;
  std::string out;
};

Result run(const std::string& args, const fs::path& dir) {
  const fs::path log = dir / "cli.log";
  const std::string cmd = std::string(BKQUAKE_BINARY) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream f(log);
  std::stringstream ss;
  ss << f.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("bkq_test_stats_cli_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(StatsCli, FitsASyntheticCatalogue) {
  const fs::path dir = fresh_dir("fit");
  {
    std::ofstream c(dir / "catalog.csv");
    c << "event,blocks,first_block,last_block,moment\n";
    std::mt19937_64 rng(11);
    for (int i = 1; i <= 5000; ++i) {
      const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
      const double mu = -std::log1p(-u);  // b = 1 above mu = 0
      c << i << ",3,10,12," << std::exp(mu) << "\n";
    }
    std::ofstream(dir / "scene.ini") << "[model]\nblocks = 50\nboundary = free\n";
  }
  const Result r = run(
      "fit " + (dir / "catalog.csv").string() + " --mu-min 0 --json " + (dir / "fit.json").string(),
      dir);
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("binned MLE"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("localised         5000"), std::string::npos) << r.out;
  std::ifstream j(dir / "fit.json");
  std::stringstream js;
  js << j.rdbuf();
  EXPECT_NE(js.str().find("\"b_mle\": "), std::string::npos);
  EXPECT_NE(js.str().find("\"classes\""), std::string::npos);
}

TEST(StatsCli, OneEventExitsTwoNamingTheFile) {
  const fs::path dir = fresh_dir("one");
  std::ofstream(dir / "catalog.csv") << "event,moment\n1,0.5\n";
  const Result r = run("fit " + (dir / "catalog.csv").string(), dir);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.out.find("catalog.csv: need at least 2 events to fit, found 1"), std::string::npos)
      << r.out;
}

TEST(StatsCli, MergeRefusesDifferentBinWidths) {
  const fs::path dir = fresh_dir("merge");
  for (const auto& [name, w] : {std::pair{"a", "0.2"}, {"b", "0.1"}}) {
    fs::create_directories(dir / name);
    std::ofstream(dir / name / "summary.json")
        << "{\"events\": 1, \"blocks\": 10, \"total_load\": 1.5, \"bin_width\": " << w << "}\n";
    std::ofstream(dir / name / "histogram.csv")
        << "mu_low,mu_high,count,D,R\n0," << w << ",1,1,1\n";
    std::ofstream(dir / name / "scene.ini")
        << "[run]\nseed = " << (name[0] == 'a' ? 1 : 2) << "\n[stats]\nbin_width = " << w << "\n";
  }
  const Result r = run("merge " + (dir / "a").string() + " " + (dir / "b").string() + " --out " +
                           (dir / "m").string(),
                       dir);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.out.find("stats.bin_width = 0.1 (not 0.2)"), std::string::npos) << r.out;
}

TEST(StatsCli, FitAndMergeAreAppFunctionsTheCliOnlyCalls) {
  // The same work without the program: app/fit.hpp and app/merge.hpp take a request and a
  // stream, so a study or a sweep can call them directly.
  const fs::path dir = fresh_dir("app");
  {
    std::ofstream c(dir / "catalog.csv");
    c << "event,moment\n";
    for (int i = 1; i <= 200; ++i) c << i << "," << std::exp(0.01 * i) << "\n";
  }
  bkq::FitRequest request;
  request.catalog = dir / "catalog.csv";
  request.json = dir / "fit.json";
  std::ostringstream out;
  bkq::fit_catalog(request, out);
  EXPECT_NE(out.str().find("events            200"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("note: event classes skipped"), std::string::npos) << out.str();
  EXPECT_TRUE(fs::exists(dir / "fit.json"));
  EXPECT_THROW(bkq::merge_runs({{(dir / "nowhere").string()}, dir / "m"}, out), bkq::Error);
}

}  // namespace
