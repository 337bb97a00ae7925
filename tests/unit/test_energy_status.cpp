// Energy diagnostics and node status: the windowed mean of a constant
// is that constant and of a sine over whole windows its offset; the settle time; and a
// continuous run with output.status and output.energy: node counts add up to N on every
// row and agree with the sliding column, energy.csv and the settle time are written.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "app/observers/energy.hpp"
#include "cli_helpers.hpp"
#include "io/energy_csv.hpp"
#include "io/schema.hpp"
#include "io/timeseries.hpp"

namespace bkq {
namespace {

std::vector<WindowedMeans::Row> run_means(double window, double dt, double t_end,
                                          double (*f)(double)) {
  WindowedMeans m(window);
  std::vector<WindowedMeans::Row> rows;
  double t = 0;
  for (long i = 0; t <= t_end + 1e-12; ++i, t = i * dt)
    for (const auto& r : m.add(t, f(t), 2 * f(t))) rows.push_back(r);
  for (const auto& r : m.finish(t_end)) rows.push_back(r);
  return rows;
}

TEST(EnergyWindows, MeanOfAConstantIsTheConstant) {
  const auto rows = run_means(10, 0.5, 100, [](double) { return 3.25; });
  ASSERT_EQ(rows.size(), 19u);  // centres 5, 10, ..., 95
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_DOUBLE_EQ(rows[k].t, 5.0 * (k + 1));
    EXPECT_EQ(rows[k].samples, 21);  // both ends included
    EXPECT_NEAR(rows[k].energy, 3.25, 1e-14);
    EXPECT_NEAR(rows[k].braking, 6.5, 1e-14);
    EXPECT_NEAR(rows[k].rate, 0.0, 1e-14);
    EXPECT_NEAR(rows[k].tau(), 0.0, 1e-14);
  }
  EXPECT_EQ(settle_time(rows, 1e-9), std::optional<double>(5.0));
}

TEST(EnergyWindows, MeanOfASineOverWholeWindowsIsItsOffset) {
  // Period 2 divides the window 10; the window's two end samples are the same phase, so the
  // mean is the offset plus that sample's share: sample the sine where it is zero at the ends.
  const auto rows = run_means(10, 0.01, 60, [](double t) { return 4.0 + std::sin(M_PI * t); });
  ASSERT_FALSE(rows.empty());
  for (const auto& r : rows) EXPECT_NEAR(r.energy, 4.0, 1e-10) << r.t;
}

TEST(EnergyWindows, SettleTimeIsTheFirstCentreAfterWhichTauStaysSmall) {
  auto row = [](double t, double tau) {
    WindowedMeans::Row r;
    r.t = t;
    r.energy = 1;
    r.rate = tau;
    return r;
  };
  const std::vector<WindowedMeans::Row> rows = {row(5, 0.5), row(10, 1e-4), row(15, 0.2),
                                                row(20, 1e-4), row(25, -5e-4)};
  EXPECT_EQ(settle_time(rows, 1e-3), std::optional<double>(20.0));
  EXPECT_FALSE(settle_time({row(5, 1e-4), row(10, 0.1)}, 1e-3).has_value());
}

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(test::read_file(path));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

TEST(NodeStatus, CountsAddUpToTheBlocksOnEveryRow) {
  test::TempDir dir;
  const auto r = test::run_bkquake(
      {"run", std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/thesis.ini", "--set",
       "model.blocks=30", "--set", "run.duration=300", "--set", "drive.step_interval=100", "--set",
       "drive.step_increment=0.05", "--set", "output.status=true", "--set", "output.energy=true",
       "--set", "output.energy_window=20", "--quiet", "--out", dir.file("r")});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto ts = read_csv(dir.file("r/timeseries.csv"));
  ASSERT_GT(ts.size(), 100u);
  EXPECT_EQ(ts[0].back(), "slip_backward");
  const std::size_t n = ts[0].size();
  int moving_rows = 0, backslip_rows = 0;
  for (std::size_t i = 1; i < ts.size(); ++i) {
    ASSERT_EQ(ts[i].size(), n);
    const int stuck = std::stoi(ts[i][n - 3]), fwd = std::stoi(ts[i][n - 2]),
              bwd = std::stoi(ts[i][n - 1]), sliding = std::stoi(ts[i][n - 4]);
    EXPECT_EQ(stuck + fwd + bwd, 30) << "row " << i;
    EXPECT_EQ(fwd + bwd, sliding) << "row " << i;
    moving_rows += sliding > 0;
    backslip_rows += bwd > 0;
  }
  EXPECT_GT(moving_rows, 0);
  const auto en = read_csv(dir.file("r/energy.csv"));
  EXPECT_EQ(en[0].size(), energy_schema().size());
  // Centres 10, 20, ..., 290: the samples lie on the grid up to t = 300 exactly, so the
  // window centred at 290 is complete (before samples were stamped on the grid, the last
  // one drifted to t = 299.5 and that window was left out).
  EXPECT_EQ(en.size(), 1 + 29u);
  const auto samples = read_csv(dir.file("r/energy_samples.csv"));
  EXPECT_EQ(samples.size(), ts.size());
  EXPECT_NE(test::read_file(dir.file("r/summary.json")).find("\"energy_settle_time\""),
            std::string::npos);
}

}  // namespace
}  // namespace bkq
