// The stencil kernel path (engine/stencil_path.hpp, integrate/stencil_kernel.hpp) is an
// optimisation only: with it on and off the engine gives the same events, counters, energy
// books and final state bit for bit, for every explicit scheme, on a lattice with free and
// with periodic edges (nearest neighbours and a range stencil in the plane), and on chains
// coupled by range and power stencils with free and periodic ends, with a law with and
// without backslip. Each case also asserts that the path carried a good share of the steps
// and that the sites that broke loose and stuck during its runs were many, so the
// comparison is not vacuous.
#include <gtest/gtest.h>

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
  int events;
};

class StencilPath : public ::testing::TestWithParam<const char*> {};

TEST_P(StencilPath, SameEventsBitForBitAsTheGeneralPath) {
  const std::vector<Case> cases = {
      {"lattice, free edges", {{"model.blocks", "12"}, {"model.rows", "10"}}, 1500},
      {"lattice, periodic edges",
       {{"model.blocks", "10"},
        {"model.rows", "12"},
        {"model.boundary", "periodic"},
        {"model.boundary_y", "periodic"}},
       1500},
      {"lattice, periodic rows, free columns, thesis friction (backslip)",
       {{"model.blocks", "10"},
        {"model.rows", "10"},
        {"model.boundary", "periodic"},
        {"friction.law", "thesis"}},
       1500},
      {"lattice, range stencil R = 2",
       {{"model.blocks", "10"},
        {"model.rows", "10"},
        {"model.coupling", "range"},
        {"model.range", "2"}},
       800},
      {"chain, range R = 10, free ends",
       {{"model.blocks", "120"}, {"model.coupling", "range"}, {"model.range", "10"}},
       1500},
      {"chain, range R = 4, periodic",
       {{"model.blocks", "60"},
        {"model.coupling", "range"},
        {"model.range", "4"},
        {"model.boundary", "periodic"}},
       1500},
      {"chain, power R = 6, thesis friction",
       {{"model.blocks", "80"},
        {"model.coupling", "power"},
        {"model.range", "6"},
        {"friction.law", "thesis"}},
       1500},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name + ", " + GetParam());
    Settings settings = c.settings;
    settings.push_back({"integrator.scheme", GetParam()});
    settings.push_back({"integrator.dt", "0.005"});
    Sim fast(settings), general(settings);
    // Event starts are integrated too, so that the paths take them.
    fast.engine.lone_slip_path = general.engine.lone_slip_path = false;
    general.engine.stencil_path = false;
    std::int64_t releases = 0, stencil_calls = 0;
    fast.engine.observe_reports([&](const PathReport& r) {
      if (std::string(r.path) != "stencil") return;
      ++stencil_calls;
      releases += static_cast<std::int64_t>(r.released.size());
    });
    ASSERT_NO_FATAL_FAILURE(test::expect_same_events(fast.engine, general.engine, c.events));
    const EngineCounters& ca = fast.engine.counters();
    EXPECT_EQ(fast.engine.dissipated_total(), general.engine.dissipated_total());
    EXPECT_EQ(general.engine.stencil_steps(), 0);
    EXPECT_GT(static_cast<double>(fast.engine.stencil_steps()),
              0.5 * static_cast<double>(ca.steps));
    EXPECT_GT(stencil_calls, c.events);
    EXPECT_GT(releases, c.events / 10);
  }
}

// The kernel skips a stuck site's release test while a bound on its force (its last tested
// force and rounding, plus k |dx| of each partner's move since) stays below the threshold.
// Here every skipped test is taken anyway: none would have released its site, no force is
// above the bound, and the events equal the general path's; the skips are most of the
// tests, and many are close calls (the bound within a tenth of the margin of the threshold),
// so a bound that missed a partner's move or the rounding would be caught.
TEST_P(StencilPath, ItsSkippedReleaseTestsWouldHaveHeld) {
  const std::vector<Case> cases = {
      {"chain, range R = 10, free ends",
       {{"model.blocks", "200"}, {"model.coupling", "range"}, {"model.range", "10"}},
       2000},
      {"chain, power R = 30, periodic",
       {{"model.blocks", "200"},
        {"model.coupling", "power"},
        {"model.range", "30"},
        {"model.boundary", "periodic"}},
       2000},
      {"chain, range R = 6, thesis friction (no backslip)",
       {{"model.blocks", "100"},
        {"model.coupling", "range"},
        {"model.range", "6"},
        {"friction.law", "thesis"}},
       2000},
      {"lattice, periodic edges",
       {{"model.blocks", "12"},
        {"model.rows", "12"},
        {"model.boundary", "periodic"},
        {"model.boundary_y", "periodic"}},
       2000},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name + ", " + GetParam());
    Settings settings = c.settings;
    settings.push_back({"integrator.scheme", GetParam()});
    Sim fast(settings), general(settings);
    fast.engine.lone_slip_path = general.engine.lone_slip_path = false;
    general.engine.stencil_path = false;
    StencilRelaxation::SkipCheck check;
    fast.engine.stencil_kernel_path().check_skips(&check);
    ASSERT_NO_FATAL_FAILURE(test::expect_same_events(fast.engine, general.engine, c.events));
    const auto& path = fast.engine.stencil_kernel_path();
    EXPECT_EQ(check.broke, 0);
    EXPECT_EQ(check.over_bound, 0);
    EXPECT_GT(path.skipped_tests(), path.release_tests());
    EXPECT_GT(check.close, c.events / 4);
  }
}

INSTANTIATE_TEST_SUITE_P(Schemes, StencilPath, ::testing::Values("rk2", "rk4", "verlet"));

}  // namespace
}  // namespace bkq
