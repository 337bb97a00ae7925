// Continuous runs: their slip episodes are events, so a continuous run writes the same
// magnitude histogram (histogram.csv) and Gutenberg-Richter fit in summary.json as an
// event run, through the same observers, and the two modes compare directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "io/histogram_csv.hpp"

namespace bkq {
namespace {

using test::read_file;
using test::run_bkquake;

// A 30-block Carlson-Langer chain pulled at speed 0.05: a few hundred slip episodes in
// well under a second.
const std::vector<std::string> kContinuous = {
    "--set",  "drive.mode=continuous", "--set", "model.blocks=30",
    "--set",  "run.duration=1500",     "--set", "drive.speed=0.05",
    "--set",  "integrator.scheme=rk4", "--set", "output.every=5",
    "--quiet"};

std::vector<std::string> run_args(const std::vector<std::string>& scene,
                                  const std::vector<std::string>& more) {
  std::vector<std::string> a = {"run"};
  a.insert(a.end(), scene.begin(), scene.end());
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// The values of the column `name` of a CSV file without comment lines.
std::vector<double> column_of(const std::string& path, const std::string& name) {
  std::istringstream in(read_file(path));
  std::string line;
  int column = -1;
  std::vector<double> values;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (column < 0) {
      const auto it = std::find(cells.begin(), cells.end(), name);
      if (it == cells.end()) return values;
      column = static_cast<int>(it - cells.begin());
      continue;
    }
    values.push_back(std::strtod(cells.at(static_cast<std::size_t>(column)).c_str(), nullptr));
  }
  return values;
}

TEST(ContinuousRun, WritesTheHistogramAndTheFitOfItsEpisodes) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const auto r = run_bkquake(run_args(kContinuous, {"--out", out}));
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(out + "/histogram.csv"));

  // Every episode with a positive moment is in the histogram, each in its bin.
  const std::vector<double> moments = column_of(out + "/catalog.csv", "moment");
  ASSERT_GT(moments.size(), 50u);
  const MagnitudeHistogram h = read_histogram_csv(out + "/histogram.csv", 1.0, 30);
  MagnitudeHistogram from_catalog(h.bin_width());
  for (double m : moments)
    if (m > 0) from_catalog.add(std::log(m));
  EXPECT_EQ(h.events(), from_catalog.events());
  EXPECT_EQ(h.state().counts, from_catalog.state().counts);

  const std::string summary = read_file(out + "/summary.json");
  for (const char* field : {"\"b_mle\"", "\"b_mle_err\"", "\"fit_window\"", "\"bin_width\"",
                            "\"nonpositive_moments\"", "\"moment_sum\""})
    EXPECT_NE(summary.find(field), std::string::npos) << field << " missing in\n" << summary;
  EXPECT_NE(r.out.find("b = "), std::string::npos) << r.out;
}

}  // namespace
}  // namespace bkq
