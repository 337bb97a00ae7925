// The event engine's replay of event starts (engine/lone_slip.hpp) against direct
// integration. From the same state between events, an engine that takes each event's
// start from the lone slip's record and one that integrates every step must find the
// same event: the same trigger, blocks, extent and duration (the step count), and the
// moment, largest speed, energy residual and final positions equal to rounding. The
// states are taken from the direct engine's own run, event after event, for every
// explicit scheme and the switches that change the record (backslip, periodic ends,
// free ends, no neighbour springs). Each case also asserts that the replay carried
// almost every event, and that among them were events it finished (no neighbour broke
// loose) and events it handed on to the integration, so the comparison is not vacuous.
// A built state puts a neighbour's force exactly on the line where the record would
// release it: the engine must then integrate that event directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../scene_sim.hpp"
#include "engine/lone_slip.hpp"

namespace bkq {
namespace {

using test::make_scene;
using test::Settings;
using test::Sim;

struct Case {
  std::string name;
  Settings settings;
  bool neighbours = true;  // neighbours can break loose during a replayed start
};

class LoneSlipReplay : public ::testing::TestWithParam<const char*> {};

TEST_P(LoneSlipReplay, SameEventsAsDirectIntegrationFromTheSameStates) {
  const std::string scheme = GetParam();
  const std::vector<Case> cases = {
      {"carlson-langer, clst91", {{"model.blocks", "40"}}},
      {"periodic", {{"model.blocks", "40"}, {"model.boundary", "periodic"}}},
      {"thesis friction (backslip)", {{"model.blocks", "40"}, {"friction.law", "thesis"}}},
      {"no neighbour springs", {{"model.blocks", "10"}, {"model.l", "0"}}, false},
      {"short chain, free ends", {{"model.blocks", "5"}}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name + ", " + scheme);
    Settings settings = c.settings;
    settings.push_back({"integrator.scheme", scheme});
    settings.push_back({"integrator.dt", "0.005"});
    const Scene scene = make_scene(settings);
    Sim direct(scene);
    direct.engine.lone_slip_path = false;
    direct.run(300);  // past the start, where forces lie above the threshold
    auto stepper = make_stepper(scheme, direct.p.n);
    EventEngine::LoneSlipStarts seen;
    const int events = 1500;
    for (int i = 0; i < events; ++i) {
      EventEngine replay(direct.forces, *stepper, scene.real("integrator.dt"), direct.engine.snapshot());
      const EventRecord a = replay.next_event(), b = direct.engine.next_event();
      SCOPED_TRACE("event " + std::to_string(b.event));
      ASSERT_EQ(a.trigger, b.trigger);
      ASSERT_EQ(a.load, b.load);
      ASSERT_EQ(a.blocks, b.blocks);
      ASSERT_EQ(a.first_block, b.first_block);
      ASSERT_EQ(a.last_block, b.last_block);
      ASSERT_EQ(a.duration, b.duration);
      const double scale = 1.0 + std::abs(b.load);
      // Rounding of positions of the size of the load; an event of many blocks amplifies the
      // start's rounding difference as it goes (up to 1.3e-9 of the moment seen, in a
      // 40-block event with backslip).
      const double tol = 1e-12 * scale + (b.blocks > 1 ? 1e-7 * b.moment : 0.0);
      ASSERT_NEAR(a.moment, b.moment, tol);
      ASSERT_NEAR(a.max_speed, b.max_speed, 1e-9 * b.max_speed);
      ASSERT_NEAR(a.energy_residual, b.energy_residual, 1e-6);
      const ChainState &sa = replay.state(), &sb = direct.engine.state();
      for (int j = 0; j < direct.p.n; ++j) {
        ASSERT_NEAR(sa.w[j], sb.w[j], tol) << "block " << j;
        ASSERT_EQ(sa.mobile[j], 0.0);
      }
      const EventEngine::LoneSlipStarts& l = replay.lone_slip_starts();
      seen.replayed += l.replayed;
      seen.finished += l.finished;
      seen.declined += l.declined;
      seen.steps += l.steps;
    }
    EXPECT_EQ(seen.replayed + seen.declined, events);
    EXPECT_GT(seen.replayed, 0.9 * events);
    EXPECT_GT(seen.finished, 0);
    if (c.neighbours) {
      EXPECT_GT(seen.replayed - seen.finished, 0);
    } else {
      EXPECT_EQ(seen.finished, seen.replayed);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Schemes, LoneSlipReplay, ::testing::Values("rk2", "rk4", "verlet"));

// Five blocks at rest, s = 0, with spring forces f: block 2 carries the largest (0) and
// triggers, block 3's lies `gap` below it, the others 1 below. After loading, block 3 sits
// gap below the threshold, and the start raises it by k_c D (D the record's final
// displacement): it breaks loose during the start if gap < k_c D.
EngineSnapshot neighbour_at(const Sim& sim, double gap) {
  // f = -A w with A = k_p I + k_c (the free chain's graph Laplacian): solve A w = -f by
  // Gaussian elimination (A is tridiagonal and diagonally dominant).
  const int n = 5;
  const double kp = sim.p.k_p, kc = sim.p.k_c;
  const std::vector<double> f = {-1.0, -1.0, 0.0, -gap, -1.0};
  std::vector<double> diag(n), rhs(n), w(n);
  for (int j = 0; j < n; ++j) {
    diag[j] = kp + kc * ((j > 0) + (j < n - 1));
    rhs[j] = -f[j];
  }
  for (int j = 1; j < n; ++j) {  // eliminate the sub-diagonal (-k_c)
    const double m = -kc / diag[j - 1];
    diag[j] -= m * -kc;
    rhs[j] -= m * rhs[j - 1];
  }
  for (int j = n - 1; j >= 0; --j) w[j] = (rhs[j] + (j < n - 1 ? kc * w[j + 1] : 0.0)) / diag[j];
  EngineSnapshot snap = sim.engine.snapshot();
  ChainState& st = snap.state;
  st.w = w;
  std::fill(st.wd.begin(), st.wd.end(), 0.0);
  std::fill(st.mobile.begin(), st.mobile.end(), 0.0);
  st.s = 0;
  return snap;
}

TEST(LoneSlipReplay, DeclinesANeighbourOnTheLineAndReplaysOneClearOfIt) {
  const Scene scene = make_scene({{"model.blocks", "5"}});
  Sim sim(scene);
  const double dt = scene.real("integrator.dt");
  const ModelParams& p = sim.p;
  const LoneSlip table = integrate_lone_slip(p, p.k_p + 2.0 * p.k_c, "rk4", dt, 1'000'000);
  ASSERT_TRUE(table.usable) << table.why_not;
  const double reach = p.k_c * table.steps.back().d_max;  // how far the start raises a neighbour

  struct Probe {
    double gap;
    std::int64_t replayed, declined;
    int neighbour_slips;  // 1 yes, 0 no, -1 either (on the line rounding decides)
  };
  // On the line, within rounding of it, clearly inside and clearly outside.
  for (const Probe& probe : {Probe{reach, 0, 1, -1}, Probe{reach * (1 + 1e-13), 0, 1, -1},
                             Probe{0.5 * reach, 1, 0, 1}, Probe{2.0 * reach, 1, 0, 0}}) {
    SCOPED_TRACE("gap " + std::to_string(probe.gap / reach) + " of the reach");
    const EngineSnapshot snap = neighbour_at(sim, probe.gap);
    auto s1 = make_stepper("rk4", p.n), s2 = make_stepper("rk4", p.n);
    EventEngine replay(sim.forces, *s1, dt, snap), direct(sim.forces, *s2, dt, snap);
    direct.lone_slip_path = false;
    const EventRecord a = replay.next_event(), b = direct.next_event();
    EXPECT_EQ(a.trigger, 2);
    EXPECT_EQ(replay.lone_slip_starts().replayed, probe.replayed);
    EXPECT_EQ(replay.lone_slip_starts().declined, probe.declined);
    if (probe.neighbour_slips >= 0) {
      EXPECT_EQ(b.blocks > 1, probe.neighbour_slips == 1);
    }
    EXPECT_EQ(a.blocks, b.blocks);
    EXPECT_EQ(a.duration, b.duration);
    EXPECT_NEAR(a.moment, b.moment, 1e-12);
    if (probe.declined) {
      EXPECT_EQ(a.moment, b.moment);  // integrated directly: the same steps
    }
  }
}

}  // namespace
}  // namespace bkq
