// The event engine's fast paths (the cluster path, integrate/cluster.hpp, and the fused
// step_held) are optimisations only: with them on and off the engine must produce the
// same events, counters and final state bit for bit, for every explicit scheme and for
// the switches that change the fixed-size code (friction law with and without
// backslip, no neighbour springs, periodic ends, a short chain whose events reach its free
// ends, where the general path takes over; the 1DOF damper never reaches it, since that
// model has one block and no neighbours). Each case also asserts that the cluster path
// really carried a good share of the steps and that clusters of more than one block were
// among them, so the comparison is not vacuous. Located transitions have no cluster kernel
// (not compiled: docs/developer/build-time.md) and take the general path.
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
  double min_share;        // least fraction of all steps taken on the cluster path; < 0: none
  double min_multi_share;  // least fraction taken there with more than one interior block
};

class ClusterPath : public ::testing::TestWithParam<const char*> {};

void expect_same_events(const std::string& scheme) {
  const std::vector<Case> cases = {
      {"carlson-langer, clst91", {{"model.blocks", "40"}}, 0.3, 0.05},
      {"periodic", {{"model.blocks", "40"}, {"model.boundary", "periodic"}}, 0.3, 0.05},
      {"thesis friction (backslip)",
       {{"model.blocks", "40"}, {"friction.law", "thesis"}},
       0.2,
       0.05},
      // No kernel is compiled without neighbour springs (kClusterKernel): the general path
      // takes every step, and the events are the same.
      {"no neighbour springs", {{"model.blocks", "10"}, {"model.l", "0"}}, -1.0, 0.0},
      // Most events of a short chain reach an end, where the general path takes over.
      {"short chain, free ends", {{"model.blocks", "5"}}, 0.1, 0.01},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name + ", " + scheme);
    Settings settings = c.settings;
    settings.push_back({"integrator.scheme", scheme});
    settings.push_back({"integrator.dt", "0.005"});
    Sim fast(settings), general(settings);
    // Event starts are integrated too, so that the one-block clusters they begin with run here.
    fast.engine.lone_slip_path = general.engine.lone_slip_path = false;
    general.engine.cluster_path = false;
    general.engine.held_ranges_path = false;
    ASSERT_NO_FATAL_FAILURE(test::expect_same_events(fast.engine, general.engine, 3000));
    const EngineCounters& ca = fast.engine.counters();
    EXPECT_EQ(general.engine.cluster_steps().all, 0);
    const EventEngine::ClusterSteps& cs = fast.engine.cluster_steps();
    const double steps = static_cast<double>(ca.steps);
    if (c.min_share < 0) {
      EXPECT_EQ(cs.all, 0);
      continue;
    }
    EXPECT_GT(static_cast<double>(cs.all), c.min_share * steps);
    EXPECT_GE(static_cast<double>(cs.multi_block), c.min_multi_share * steps);
  }
}

TEST_P(ClusterPath, SameEventsBitForBitAsTheGeneralPath) {
  expect_same_events(GetParam());
}

// Located transitions declare no cluster kernel, and the engine takes none for them.
TEST_P(ClusterPath, LocatedTransitionsTakeTheGeneralPath) {
  Sim located({{"model.blocks", "40"},
               {"integrator.scheme", GetParam()},
               {"integrator.transitions", "located"}});
  EXPECT_FALSE(located.stepper->traits().cluster_kernel);
  for (int i = 0; i < 500; ++i) located.engine.next_event();
  EXPECT_GT(located.engine.counters().steps, 0);
  EXPECT_EQ(located.engine.cluster_steps().all, 0);
}

INSTANTIATE_TEST_SUITE_P(Schemes, ClusterPath, ::testing::Values("rk2", "rk4", "verlet"));

}  // namespace
}  // namespace bkq
