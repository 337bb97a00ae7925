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
// The engine's work counters must be those of the direct integration. A built state puts
// a neighbour's force exactly on the line where the record would release it: the engine
// must then integrate that event directly. States shifted to a load of 1e5 check the
// rounding bound where positions are large; two long runs check that the replay leaves
// the statistics alone; and a moving pad never uses it. The first comparison is repeated
// with located transitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "../scene_sim.hpp"
#include "engine/lone_slip.hpp"
#include "integrate/rk4.hpp"
#include "stats/gutenberg_richter.hpp"

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

// `transitions`: integrator.transitions. Located, the record's stick is located inside its
// last step: the duration is then the located instant, equal to rounding.
void expect_same_events(const std::string& scheme, const std::string& transitions) {
  const bool located = transitions == "located";
  std::vector<Case> cases = {
      {"carlson-langer, clst91", {{"model.blocks", "40"}}},
      {"periodic", {{"model.blocks", "40"}, {"model.boundary", "periodic"}}},
      {"thesis friction (backslip)", {{"model.blocks", "40"}, {"friction.law", "thesis"}}},
      {"no neighbour springs", {{"model.blocks", "10"}, {"model.l", "0"}}, false},
      {"short chain, free ends", {{"model.blocks", "5"}}},
      {"periodic ring of 3", {{"model.blocks", "3"}, {"model.boundary", "periodic"}}},
      {"one block", {{"model.blocks", "1"}}, false},
      {"1dof (block damper)", {{"model.kind", "1dof"}, {"model.blocks", "1"}}, false},
      {"thesis parameterisation (m_u = 1/100)",
       {{"model.parameterisation", "thesis"}, {"model.blocks", "40"}, {"drive.mode", "events"}}},
  };
  // Lattices (model.rows > 1; they refuse located transitions): a record per stiffness
  // (interior, edge and corner sites), springs across strike weaker than along, periodic
  // edges, and the range kernel's twelve partners.
  if (!located) {
    cases.push_back({"lattice 8 x 6", {{"model.blocks", "8"}, {"model.rows", "6"}}});
    cases.push_back({"lattice periodic, l_y = 6",
                     {{"model.blocks", "7"},
                      {"model.rows", "5"},
                      {"model.boundary", "periodic"},
                      {"model.boundary_y", "periodic"},
                      {"model.l_y", "6"}}});
    cases.push_back({"lattice range 2, backslip",
                     {{"model.blocks", "8"},
                      {"model.rows", "7"},
                      {"model.coupling", "range"},
                      {"model.range", "2"},
                      {"friction.law", "thesis"}}});
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name + ", " + scheme);
    Settings settings = c.settings;
    settings.push_back({"integrator.scheme", scheme});
    settings.push_back({"integrator.dt", "0.005"});
    settings.push_back({"integrator.transitions", transitions});
    const Scene scene = make_scene(settings);
    Sim direct(scene);
    direct.engine.lone_slip_path = false;
    direct.run(300);  // past the start, where forces lie above the threshold
    auto stepper = direct.with_transitions(scene, make_stepper(scheme, direct.p.n));
    EventEngine::LoneSlipStarts seen;
    const int events = 1500;
    for (int i = 0; i < events; ++i) {
      EventEngine replay(direct.forces, *stepper, scene.real("integrator.dt"),
                         direct.engine.snapshot());
      const EventRecord a = replay.next_event(), b = direct.engine.next_event();
      SCOPED_TRACE("event " + std::to_string(b.event));
      ASSERT_EQ(a.trigger, b.trigger);
      ASSERT_EQ(a.load, b.load);
      ASSERT_EQ(a.blocks, b.blocks);
      ASSERT_EQ(a.first_block, b.first_block);
      ASSERT_EQ(a.last_block, b.last_block);
      if (located)
        ASSERT_NEAR(a.duration, b.duration, 1e-9 * b.duration);
      else
        ASSERT_EQ(a.duration, b.duration);
      const double scale = 1.0 + std::abs(b.load);
      // Rounding of positions of the size of the load; an event of many blocks amplifies the
      // start's rounding difference as it goes (up to 1.3e-9 of the moment seen, in a
      // 40-block event with backslip).
      const double tol = 1e-12 * scale + (b.blocks > 1 ? 1e-7 * b.moment : 0.0);
      ASSERT_NEAR(a.moment, b.moment, tol);
      ASSERT_NEAR(a.max_speed, b.max_speed, 1e-9 * b.max_speed);
      ASSERT_NEAR(a.energy_residual, b.energy_residual, 1e-6);
      // The work counted is the work the direct integration does.
      const EngineCounters &ca = replay.counters(), &cb = direct.engine.counters();
      ASSERT_EQ(ca.steps, cb.steps);
      ASSERT_EQ(ca.block_steps, cb.block_steps);
      ASSERT_EQ(ca.sliding_block_steps, cb.sliding_block_steps);
      ASSERT_EQ(ca.releases, cb.releases);
      const ChainState &sa = replay.state(), &sb = direct.engine.state();
      for (int j = 0; j < direct.p.n; ++j) {
        ASSERT_NEAR(sa.w[j], sb.w[j], tol) << "block " << j;
        ASSERT_EQ(sa.mobile[j], 0.0);
      }
      const EventEngine::LoneSlipStarts& l = replay.lone_slip_starts();
      seen.replayed += l.replayed;
      seen.finished += l.finished;
      seen.declined += l.declined;
      seen.immediate += l.immediate;
      seen.steps += l.steps;
    }
    EXPECT_EQ(seen.replayed + seen.declined + seen.immediate, events);
    if (!located) {
      EXPECT_EQ(seen.immediate, 0);
    }
    EXPECT_GT(seen.replayed, 0.9 * events);
    EXPECT_GT(seen.finished, 0);
    if (c.neighbours) {
      EXPECT_GT(seen.replayed - seen.finished, 0);
    } else {
      EXPECT_EQ(seen.finished, seen.replayed);
    }
  }
}

TEST_P(LoneSlipReplay, SameEventsAsDirectIntegrationFromTheSameStates) {
  expect_same_events(GetParam(), "step");
}

// Located transitions: the record replayed up to the step before a neighbour's failure,
// which the general path then locates; an event the record finishes ends at its located stick.
TEST_P(LoneSlipReplay, LocatedSameEventsAsDirectIntegrationFromTheSameStates) {
  expect_same_events(GetParam(), "located");
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
  const LoneSlip table = integrate_lone_slip(p, p.k_p + 2.0 * p.k_c, Rk4(1), dt, 1'000'000);
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

// A long run's positions grow with its load, and with them the rounding of the direct
// steps and the replay's bound on it. The states of a direct run, shifted by a load of
// 1e5 (every w and s: the same chain, about 5x10^7 events into a 100-block run), must
// still give the same events both ways, and the replay must still take almost every
// start. Moments and speeds then differ by the rounding of positions near 1e5, which
// velocity weakening amplifies in large events; the yardstick is what the shift itself
// does to the direct integration (the unshifted run against the shifted one): the replay
// may not move any event further than the shift moves some event.
TEST(LoneSlipReplay, SameEventsAndStillReplayedAtALargeLoad) {
  for (const char* law : {"clst91", "thesis"}) {
    SCOPED_TRACE(law);
    const Scene scene = make_scene({{"model.blocks", "40"}, {"friction.law", law}});
    Sim direct(scene);
    direct.engine.lone_slip_path = false;
    direct.run(300);
    const double dt = scene.real("integrator.dt"), shift = 1e5;
    auto s1 = make_stepper("rk4", direct.p.n), s2 = make_stepper("rk4", direct.p.n);
    std::int64_t replayed = 0, declined = 0;
    double replay_moment = 0, replay_speed = 0, shift_moment = 0,
           shift_speed = 0;  // largest relative differences
    auto rel = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
    const int events = 1000;
    for (int i = 0; i < events; ++i) {
      EngineSnapshot snap = direct.engine.snapshot();
      const EventRecord unshifted = direct.engine.next_event();
      for (double& w : snap.state.w) w += shift;
      snap.state.s += shift;
      EventEngine replay(direct.forces, *s1, dt, snap), shifted(direct.forces, *s2, dt, snap);
      shifted.lone_slip_path = false;
      const EventRecord a = replay.next_event(), b = shifted.next_event();
      SCOPED_TRACE("event " + std::to_string(b.event));
      ASSERT_EQ(a.trigger, b.trigger);
      ASSERT_EQ(a.blocks, b.blocks);
      ASSERT_EQ(a.duration, b.duration);
      ASSERT_EQ(replay.counters().sliding_block_steps, shifted.counters().sliding_block_steps);
      ASSERT_NEAR(a.moment, b.moment, 1e-3 * b.moment);
      replay_moment = std::max(replay_moment, rel(a.moment, b.moment));
      replay_speed = std::max(replay_speed, rel(a.max_speed, b.max_speed));
      if (unshifted.blocks == b.blocks) {
        shift_moment = std::max(shift_moment, rel(unshifted.moment, b.moment));
        shift_speed = std::max(shift_speed, rel(unshifted.max_speed, b.max_speed));
      }
      replayed += replay.lone_slip_starts().replayed;
      declined += replay.lone_slip_starts().declined;
    }
    EXPECT_LE(replay_moment, shift_moment);
    EXPECT_LE(replay_speed, shift_speed);
    EXPECT_EQ(replayed + declined, events);
    EXPECT_GT(replayed, 0.95 * events);
    std::printf(
        "[ %s ] replayed %lld of %d starts; largest relative differences: replay %.2g (moment), "
        "%.2g (speed); shift %.2g, %.2g\n",
        law, static_cast<long long>(replayed), events, replay_moment, replay_speed, shift_moment,
        shift_speed);
  }
}

// Long runs with and without the replay part ways event by event (rounding, amplified by
// the chaos of the chain), so what must agree is their statistics: the Gutenberg-Richter
// slope on the scaling window, the mean magnitude and the share of large events, within
// their sampling errors (10^5 events of the default 100-block scene each).
TEST(LoneSlipReplay, LeavesTheStatisticsOfALongRunAlone) {
  struct Stats {
    GrFit fit;
    double mean_mu = 0, mean_err = 0, large = 0;
  };
  auto run = [](bool replay) {
    Sim sim(Settings{});
    sim.engine.lone_slip_path = replay;
    sim.run(1000);
    std::vector<double> mu;
    Stats out;
    const int events = 100000;
    for (int i = 0; i < events; ++i) {
      const EventRecord e = sim.engine.next_event();
      mu.push_back(e.magnitude);
      out.mean_mu += e.magnitude / events;
      out.large += e.blocks >= 30 ? 1.0 : 0.0;
    }
    double var = 0;
    for (double m : mu) var += (m - out.mean_mu) * (m - out.mean_mu) / (events - 1);
    out.mean_err = std::sqrt(var / events);
    out.fit = fit_magnitudes(mu, 0.2, -6.6, 1.6);
    return out;
  };
  const Stats direct = run(false), replayed = run(true);
  const double b_err = std::hypot(direct.fit.b_mle_err, replayed.fit.b_mle_err);
  EXPECT_NEAR(replayed.fit.b_mle, direct.fit.b_mle, 3.0 * b_err);
  EXPECT_GT(direct.large, 100.0);  // Poisson counts: 3 standard deviations of the difference
  EXPECT_NEAR(replayed.large, direct.large, 3.0 * std::sqrt(direct.large + replayed.large));
  EXPECT_NEAR(replayed.mean_mu, direct.mean_mu,
              3.0 * std::hypot(direct.mean_err, replayed.mean_err));
}

// The replay is for a held pad: with a moving one (bkp) every start is integrated.
TEST(LoneSlipReplay, NeverUsedWithAMovingPad) {
  Sim sim(Settings{{"model.blocks", "20"}, {"model.kind", "bkp"}});
  sim.run(200);
  EXPECT_EQ(sim.engine.lone_slip_starts().replayed, 0);
  EXPECT_EQ(sim.engine.lone_slip_starts().declined, 0);
}

}  // namespace
}  // namespace bkq
