// The event engine's fast paths with the pad moving (BK–Pad): the cluster path
// (integrate/cluster.hpp) and the fused held-range step (integrate/layouts.hpp) must
// give the same events, counters and final state bit for bit as the general step, for
// every explicit scheme (rk4 fuses held ranges; rk2 and verlet fall back to the general
// step there) and for the switches that change the code (backslip, periodic ends, the
// thesis' units, a short chain whose events reach its free ends). Each case also asserts
// that the fast paths carried a good share of the steps, so the comparison is not vacuous.
// Located transitions take the general path (no cluster kernel, no fused step).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "../same_events.hpp"
#include "../scene_sim.hpp"

namespace bkq {
namespace {

using test::Settings;
using test::Sim;

struct Case {
  std::string name;
  Settings settings;
  double min_cluster_share;  // least fraction of the steps taken on the cluster path
  double min_held_share;     // least fraction taken on the fused held path (rk4; 0: none asked)
};

class PadPaths : public ::testing::TestWithParam<const char*> {};

void expect_same_events(const std::string& scheme) {
  const std::vector<Case> cases = {
      {"carlson-langer, clst91", {{"model.blocks", "40"}}, 0.3, 0.02},
      {"periodic", {{"model.blocks", "40"}, {"model.boundary", "periodic"}}, 0.3, 0.02},
      {"thesis friction (backslip)",
       {{"model.blocks", "40"}, {"friction.law", "thesis"}},
       0.2,
       0.02},
      {"thesis units", {{"model.blocks", "40"}, {"model.parameterisation", "thesis"}}, 0.2, 0.02},
      {"short chain, free ends", {{"model.blocks", "5"}}, 0.1, 0.0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name + ", " + scheme);
    Settings settings = c.settings;
    settings.push_back({"model.kind", "bkp"});
    settings.push_back({"integrator.scheme", scheme});
    settings.push_back({"integrator.dt", "0.005"});
    Sim fast(settings), general(settings);
    general.engine.cluster_path = false;
    general.engine.held_ranges_path = false;
    ASSERT_NO_FATAL_FAILURE(test::expect_same_events(fast.engine, general.engine, 2000));
    const EngineCounters& ca = fast.engine.counters();
    EXPECT_EQ(std::bit_cast<std::uint64_t>(fast.engine.state().x),
              std::bit_cast<std::uint64_t>(general.engine.state().x));
    EXPECT_EQ(general.engine.pad_held_steps(), 0);
    EXPECT_EQ(general.engine.cluster_steps().all, 0);
    const EventEngine::ClusterSteps& cs = fast.engine.cluster_steps();
    EXPECT_GT(static_cast<double>(cs.all), c.min_cluster_share * static_cast<double>(ca.steps));
    EXPECT_GT(cs.multi_block, 0);
    if (scheme == "rk4" && c.min_held_share > 0) {
      EXPECT_GT(static_cast<double>(fast.engine.pad_held_steps()),
                c.min_held_share * static_cast<double>(ca.steps));
    }
  }
}

TEST_P(PadPaths, SameEventsBitForBitAsTheGeneralPath) {
  expect_same_events(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Schemes, PadPaths, ::testing::Values("rk2", "rk4", "verlet"));

}  // namespace
}  // namespace bkq
