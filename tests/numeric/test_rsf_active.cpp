// The event-driven rate-and-state engine's active-block integration (engine/rsf_active.hpp)
// against its whole-grid integration, the growth of the active set and the slip a block
// passes on when it goes back to its closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "engine/rsf_active.hpp"
#include "engine/rsf_loader.hpp"
#include "support/qdyn_stickslip.hpp"

namespace bkq {
namespace {

// Asperities (QDYN's block) among barriers (a and b swapped), `width` blocks each, springs
// 2e9 Pa/m; `rows` rows with springs 1e9 Pa/m along and across.
RsfModel asperity_grid(int n, int width, int rows = 1) {
  RsfModel m = test::qdyn_stickslip(n);
  m.rows = rows;
  m.springs = rows == 1 ? LatticeStencil{{1, 0, 2e9}} : LatticeStencil{{1, 0, 1e9}, {0, 1, 1e9}};
  rsf::Params barrier = m.law[0].params();
  std::swap(barrier.a, barrier.b_rsf);
  for (int j = 0; j < n; ++j)
    if ((j % m.nx()) % (2 * width) >= width) m.law[j] = rsf::Law(barrier);
  return m;
}

// An engine from the asperities nucleating (V theta/D_c = 1000), the barriers at steady state,
// slip rates spread about 3e-8 m/s.
RsfEventEngine engine_from_start(const RsfModel& m) {
  const int n = m.n();
  std::vector<double> v0(n), theta(n);
  for (int j = 0; j < n; ++j) {
    v0[j] = 3e-8 * (1 + 0.8 * std::sin(1.3 * j));
    const rsf::Params& p = m.law[j].params();
    theta[j] = (p.a > p.b_rsf ? 1.0 : 1e3) * p.dc / v0[j];
  }
  return RsfEventEngine(m, 1e-8, 1e-3, 1e-4, 1e-6, v0, theta);
}

// The whole-grid and the active-block engine from the same state (the asperities nucleating,
// V theta/D_c = 1000, the barriers at steady state: where the closed forms hold): the first
// `count` events have the same trigger and blocks, hypocentre times within 1e-2 and moments
// within 2e-2 (when written: 3e-4 and 1.2e-2 at most on the chain; on the lattice 2e-4 and
// 3e-3 for the first event, 7.9e-3 and 8e-3 for the two after 350 s of closed-form creep in
// between, which the active path's held neighbours change). Skipping the activation of
// neighbours would make them single-block events; a barrier's step along steady state where
// it joins or where an event's slip reaches it would add blocks and an aftershock.
// With groups (set_groups), the same.
void expect_same_first_events(const RsfModel& m, int count, double v_alone = 0,
                              bool groups = false) {
  RsfEventEngine whole = engine_from_start(m);
  RsfEventEngine active = engine_from_start(m);
  active.set_active_blocks(true);
  active.set_groups(groups);
  if (v_alone > 0) active.set_alone_speed(v_alone);
  ASSERT_TRUE(active.active_blocks());
  int several = 0;
  for (int k = 0; k < count; ++k) {
    const auto a = whole.next(1e5), b = active.next(1e5);
    ASSERT_TRUE(a && b) << k;
    EXPECT_EQ(a->trigger, b->trigger) << k;
    EXPECT_EQ(a->blocks, b->blocks) << k;
    EXPECT_EQ(a->first_block, b->first_block) << k;
    EXPECT_EQ(a->last_block, b->last_block) << k;
    EXPECT_NEAR(b->hypocentre_time / a->hypocentre_time, 1, 1e-2) << k;
    EXPECT_NEAR(b->moment / a->moment, 1, 2e-2) << k;
    several += a->blocks > 1;
  }
  EXPECT_GT(several, 0);
  // Fewer blocks than N in a step on average: the point of it.
  EXPECT_GT(active.active_block_steps(), 0);
  EXPECT_LT(static_cast<double>(active.active_block_steps()) / active.steps(), 0.5 * m.n());
  // With blocks alone, some were (after their events).
  if (v_alone > 0) {
    EXPECT_GT(active.loader().alone_steps(), 0);
  }
}

TEST(RsfActive, SameFirstEventsAsTheWholeGridOnAChain) {
  expect_same_first_events(asperity_grid(20, 3), 4);
}

TEST(RsfActive, SameFirstEventsAsTheWholeGridOnALattice) {
  expect_same_first_events(asperity_grid(24, 3, 4), 3);
}

TEST(RsfActive, SameFirstEventsAsTheWholeGridWithBlocksAlone) {
  expect_same_first_events(asperity_grid(20, 3), 4, 1e-4);
  expect_same_first_events(asperity_grid(24, 3, 4), 3, 1e-4);
}

TEST(RsfActive, SameFirstEventsAsTheWholeGridInGroups) {
  expect_same_first_events(asperity_grid(20, 3), 4, 0, true);
  expect_same_first_events(asperity_grid(24, 3, 4), 3, 0, true);
  expect_same_first_events(asperity_grid(20, 3), 4, 1e-4, true);
}

// A chain of ten asperities nucleating at once from the same state: in groups, each asperity's
// nucleation takes its own steps, so the blocks integrated over the steps fall (by more than
// a third; about half when written), while the first eight events are the one integration's
// (trigger and blocks the same, hypocentre times within 1e-3 and moments within 2e-2: 4e-5 and
// 3e-3 at most when written; the next two, on asperities failing close in time, swap).
TEST(RsfActive, GroupsSharingNoSpringTakeTheirOwnSteps) {
  const RsfModel m = asperity_grid(60, 3);
  RsfEventEngine one = engine_from_start(m);
  RsfEventEngine apart = engine_from_start(m);
  one.set_active_blocks(true);
  apart.set_active_blocks(true);
  apart.set_groups(true);
  for (int k = 0; k < 8; ++k) {
    const auto a = one.next(1e5), b = apart.next(1e5);
    ASSERT_TRUE(a && b) << k;
    EXPECT_EQ(a->trigger, b->trigger) << k;
    EXPECT_EQ(a->blocks, b->blocks) << k;
    EXPECT_NEAR(b->hypocentre_time / a->hypocentre_time, 1, 1e-3) << k;
    EXPECT_NEAR(b->moment / a->moment, 1, 2e-2) << k;
  }
  EXPECT_LT(apart.active_block_steps(), 2 * one.active_block_steps() / 3);
}

// Events of groups that overlap in time are one event, as the whole grid's detector has them;
// apart in time they stay apart, in the order of their hypocentres.
TEST(RsfActive, OverlappingEventsOfGroupsAreOne) {
  const auto record = [](double t, double duration, int trigger, int first, int last, double moment,
                         double speed) {
    EventRecord e;
    e.hypocentre_time = t;
    e.peak_time = t + duration / 2;
    e.duration = duration;
    e.trigger = trigger;
    e.first_block = first;
    e.last_block = last;
    e.blocks = last - first + 1;
    e.moment = moment;
    e.magnitude = std::log(moment);
    e.max_speed = speed;
    return e;
  };
  const std::vector<EventRecord> out =
      join_overlapping({record(6, 1, 40, 40, 40, 5e-5, 0.01), record(2, 3, 30, 29, 31, 2e-4, 0.2),
                        record(1, 2, 5, 4, 5, 1e-4, 0.1)});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].trigger, 5);  // the first hypocentre's
  EXPECT_EQ(out[0].blocks, 5);
  EXPECT_EQ(out[0].first_block, 4);
  EXPECT_EQ(out[0].last_block, 31);
  EXPECT_DOUBLE_EQ(out[0].moment, 3e-4);
  EXPECT_DOUBLE_EQ(out[0].magnitude, std::log(3e-4));
  EXPECT_DOUBLE_EQ(out[0].duration, 4);  // from 1 to 5
  EXPECT_DOUBLE_EQ(out[0].max_speed, 0.2);
  EXPECT_DOUBLE_EQ(out[0].peak_time, 3.5);
  EXPECT_EQ(out[1].trigger, 40);
  EXPECT_DOUBLE_EQ(out[1].moment, 5e-5);
  // Touching (one ends where the next starts) is not overlapping.
  EXPECT_EQ(
      join_overlapping({record(1, 1, 1, 1, 1, 1e-4, 0.1), record(2, 1, 9, 9, 9, 1e-4, 0.1)}).size(),
      2u);
}

// A hand-back test for the direct runs below: a decade below V_h.
bool below_vh(const RsfActiveIntegration& a, int j) {
  return a.ln_v(j) < std::log(1e-4) - std::log(10.0);
}

// Two coupled blocks: block 0 reaches V_h first; block 1, nucleating slowly, would reach it on
// its own only long after the integration ends. Block 0's slip brings it to V_h: it joins
// (two activations) and the event has both blocks. Without the coupling it stays out.
TEST(RsfActive, TheActiveSetGrowsToANeighbourTheStressBringsToTheHandOverSpeed) {
  for (const double k_c : {2e9, 0.0}) {
    RsfModel m = test::qdyn_stickslip(2);
    m.springs = {{1, 0, k_c}};
    m.k_c = k_c;
    RsfLoader loader(m, 1e-4, HUGE_VAL);
    loader.set(0, 0, {std::log(5e-5), std::log(1e3 * 1e-5 / 5e-5)});
    loader.set(1, 0, {std::log(1e-6), std::log(1e3 * 1e-5 / 1e-6)});
    ASSERT_EQ(loader.next_block(), 0);
    const double t0 = loader.next_time();
    const double t1_alone =
        loader.state_at(1, t0).ln_v < std::log(1e-4)
            ? t0 + rsf::time_to_speed(loader.slider(1), loader.state_at(1, t0), std::log(1e-4))
            : t0;
    RsfActiveIntegration a(m, 1e-8, 1e-3);
    const double t_end = a.run(loader, 0, t0, 1e5, below_vh);
    ASSERT_FALSE(a.events().empty());
    if (k_c > 0) {
      EXPECT_LT(t_end, t1_alone);  // block 1 did not join on its own clock
      EXPECT_EQ(a.activations(), 2);
      EXPECT_EQ(a.events()[0].blocks, 2);
      EXPECT_GT(a.slot_steps(), a.accepted());  // two blocks in some steps
    } else {
      EXPECT_EQ(a.activations(), 1);
      EXPECT_EQ(a.events()[0].blocks, 1);
      EXPECT_EQ(a.slot_steps(), a.accepted());
    }
    for (int j = 0; j < 2; ++j) EXPECT_FALSE(loader.held(j));
  }
}

// Three coupled blocks, the middle one nucleating and the outer ones locked far below V_h, no
// creep quanta: the middle block's event is integrated alone and its slip delta reaches each
// neighbour as stress steps summing to k_c delta (during the event, each time it has built up
// to 0.05 a sigma, and the rest when it goes back) (its slip rate times
// exp(k_c delta/(a sigma)) against the same loader without the event). Their sum is
// 2 k_c delta, the stress its slip put on them (2.3 % less if its creep before the event were
// counted in, 2 k_c delta more if the stress were passed twice).
// k_c = 3e9 Pa/m makes the middle block's steady sliding stable on its springs (sigma (b - a)/D_c
// = 7.5e9 < k + 2 k_c), so that the loader does not take it straight back near V theta/D_c = 1
// where this test's hand-back (a decade below V_h) lets it go.
TEST(RsfActive, ABlockHandedBackPassesItsSlipOnAsStress) {
  RsfModel m = test::qdyn_stickslip(3);
  const double k_c = 3e9;
  m.springs = {{1, 0, k_c}};
  RsfLoader loader(m, 1e-4, HUGE_VAL);
  // Locked even after the whole step (V theta/D_c ~ 0.02), so that theta is kept throughout.
  for (const int j : {0, 2}) loader.set(j, 0, {std::log(1e-13), std::log(1e2)});
  loader.set(1, 0, {std::log(5e-5), std::log(1e3 * 1e-5 / 5e-5)});
  ASSERT_EQ(loader.next_block(), 1);
  const RsfLoader before = loader;
  RsfActiveIntegration a(m, 1e-8, 1e-3);
  const double t0 = loader.next_time();
  const double t_end = a.run(loader, 1, t0, 1e5, below_vh);
  ASSERT_EQ(a.activations(), 1);
  ASSERT_EQ(a.events().size(), 1u);
  // Its position moved by its creep before t0 (not passed on: no quanta) and the slip since.
  const double slip = loader.position(1) - before.unsynced(1, t0);
  EXPECT_GT(before.unsynced(1, t0), 0);
  EXPECT_GT(slip, 1e-5);
  EXPECT_EQ(loader.position(0), 0);
  double passed = 0;
  for (const int j : {0, 2}) {
    const rsf::SliderState x = loader.state_at(j, t_end), x0 = before.state_at(j, t_end);
    EXPECT_NEAR(x.ln_theta, x0.ln_theta, 1e-12);  // kept, to the rounding of its restarts
    passed += m.law[j].params().a * m.sigma * (x.ln_v - x0.ln_v);
  }
  EXPECT_NEAR(passed, 2 * k_c * slip, 1e-9 * k_c * slip);
  // The event's moment is that slip, from the event's start on (less than all of it).
  EXPECT_GT(a.events()[0].moment, 0.5 * slip);
  EXPECT_LE(a.events()[0].moment, slip);
}

}  // namespace
}  // namespace bkq
