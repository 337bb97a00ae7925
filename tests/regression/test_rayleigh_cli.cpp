// Rayleigh block damping through `bkquake run`: a damped continuous run finishes with a small
// energy residual (the damper's work is booked), event runs refuse the damping, and a dt
// above the damped stability limit is refused with the limit and the damped bound; each
// refusal one line, exit 2, nothing written.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "refusal.hpp"

namespace bkq {
namespace {

const std::string kThesis = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/thesis.ini";

TEST(RayleighCli, DampedContinuousRunBooksTheDamperWork) {
  test::TempDir dir;
  const auto r =
      test::run_bkquake({"run", kThesis, "--set", "model.blocks=20", "--set", "run.duration=40",
                         "--set", "integrator.scheme=rk4", "--set", "model.rayleigh_alpha=0.5",
                         "--set", "model.rayleigh_beta=0.01", "--out", dir.file("r")});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string summary = test::read_file(dir.file("r/summary.json"));
  const auto at = summary.find("\"energy_residual\": ");
  ASSERT_NE(at, std::string::npos) << summary;
  const double residual = std::stod(summary.substr(at + 19));
  EXPECT_LT(std::abs(residual), 1e-3) << summary;
  EXPECT_NE(test::read_file(dir.file("r/scene.ini")).find("rayleigh_alpha = 0.5"),
            std::string::npos);
}

TEST(RayleighCli, EventRunsAndTooLargeStepsAreRefused) {
  test::TempDir dir;
  const auto events =
      test::run_bkquake({"run", "--set", "model.rayleigh_beta=0.01", "--out", dir.file("e")});
  test::expect_refused(events, {"model.rayleigh_beta = 0.01", "continuous runs only"});
  EXPECT_TRUE(test::tree_bytes(dir.file("e")).empty());

  const auto dt = test::run_bkquake({"run", kThesis, "--set", "integrator.scheme=rk4", "--set",
                                     "integrator.dt=0.2", "--set", "model.rayleigh_beta=0.1",
                                     "--out", dir.file("d")});
  test::expect_refused(dt, {"integrator.dt: 0.2 is above the stability limit", "Rayleigh",
                            "rk4 accepts rate*dt <= 2.6"});
  EXPECT_TRUE(test::tree_bytes(dir.file("d")).empty());
}

}  // namespace
}  // namespace bkq
