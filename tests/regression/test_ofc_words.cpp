// An OFC run describes itself in the automaton's words: summary.json's scene says the
// built-in default was changed to ofc (not "carlson-langer, event-driven"), the printout
// names the load the uniform drive of the sites (not a substrate displacement), and no
// event's moment is below its topplings, since each toppling releases at least the threshold
// (the drive stops the trigger one rounding step short of it, which once made the smallest
// magnitude -4.44e-16).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.hpp"

namespace bkq {
namespace {

using test::read_file;
using test::run_bkquake;

// The values of the named columns of every row of a CSV file with a header.
std::vector<std::vector<double>> columns(const std::string& path,
                                         const std::vector<std::string>& names) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::istringstream h(line);
    for (std::string c; std::getline(h, c, ',');) header.push_back(c);
  }
  std::vector<std::size_t> at;
  for (const auto& n : names) {
    const auto it = std::find(header.begin(), header.end(), n);
    EXPECT_NE(it, header.end()) << n << " is not a column of " << path;
    at.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  std::vector<std::vector<double>> out(names.size());
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream r(line);
    for (std::string c; std::getline(r, c, ',');) cells.push_back(c);
    for (std::size_t k = 0; k < at.size(); ++k)
      out[k].push_back(at[k] < cells.size() ? std::stod(cells[at[k]]) : NAN);
  }
  return out;
}

TEST(OfcWords, TheRunSaysOfcAndNoMagnitudeIsBelowOneToppling) {
  test::TempDir tmp;
  const std::string out = tmp.file("ofc");
  const auto r = run_bkquake({"run", "--set", "model.kind=ofc", "--set", "model.blocks=24", "--set",
                              "model.rows=24", "--set", "run.events=5000", "--set",
                              "run.transient_events=2000", "--out", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("total drive (stress per site)"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("substrate"), std::string::npos) << r.out;
  const std::string summary = read_file(out + "/summary.json");
  EXPECT_NE(
      summary.find("\"scene\": \"built-in default with --set overrides (ofc, event-driven)\""),
      std::string::npos)
      << summary;
  const auto c = columns(out + "/catalog.csv", {"moment", "magnitude", "topplings"});
  ASSERT_EQ(c[0].size(), 5000u);
  int single = 0;
  for (std::size_t i = 0; i < c[0].size(); ++i) {
    EXPECT_GE(c[0][i], c[2][i]) << "event " << i + 1 << ": moment below its topplings";
    EXPECT_GE(c[1][i], 0.0) << "event " << i + 1;
    single += c[2][i] == 1;
  }
  EXPECT_GT(single, 0);  // the one-toppling events, whose magnitude this is about, occur
}

TEST(OfcWords, AChainRunStillSpeaksOfTheSubstrate) {
  test::TempDir tmp;
  const std::string out = tmp.file("bk");
  const auto r = run_bkquake(
      {"run", "--set", "run.events=500", "--set", "run.transient_events=100", "--out", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("total substrate displacement"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace bkq
