// Located transitions for the explicit schemes (integrate/located.hpp) against closed forms
// and the adaptive reference:
//  - a single block (Carlson–Langer units m_u = k_p = F0 = 1, alpha = 0: kinetic friction
//    the constant 1 - sigma) released at the threshold moves as u(t) = -(1 - sigma) -
//    sigma cos t and sticks at t = pi after a slip of 2 sigma (test_adaptive.cpp). With
//    h = pi/(m + 1/2) the stick falls mid-step. Located, each scheme keeps its order in
//    the stick time and the final position: the error ratio between h and h/2 is at least
//    2^(order - 1/2);
//  - the same stick under velocity-weakening friction against the adaptive reference
//    (rk4 keeps order 4 in the stick time: the instant is polished on real steps);
//  - the same stick in the event engine's lone-slip record integrated with located
//    transitions (engine/lone_slip.hpp), whose stick instant becomes an event's duration;
//  - the event engine's durations of sampled Carlson–Langer events, of one block and of
//    several, against the adaptive reference;
//  - a located failure: two blocks coupled by k_c = 1, block 0 released at the threshold
//    pulls block 1 (0.005 below it) over the threshold inside a step, then both stick; the
//    state at t = 10 against the adaptive stepper at tolerance 1e-12 keeps the same order;
//  - invariants over whole events in both modes: after every step no sliding block moves
//    against its direction of sliding and no stuck block holds a force above the threshold;
//  - the energy balance of the event engine closes at least as well located as at the step
//    (median |energy residual| over events of a small chain);
//  - continuous driving: a block moves only while it slides, so between two instants with
//    every block stuck the blocks' displacements add up to the moments of the slip episodes
//    in between, in both modes (located, the blocks released inside a step count too);
//  - a rupture front through blocks at the threshold, cut once per block inside one step,
//    is not refused for the number of its cuts (the thesis scene at dt = 0.03);
//  - the cut counters: a stick inside a step is one cut over the step's whole range;
//  - the scene key: located for a scheme that resolves its transitions itself is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../scene_sim.hpp"
#include "core/error.hpp"
#include "engine/contacts.hpp"
#include "engine/continuous.hpp"
#include "engine/initial_state.hpp"
#include "engine/lone_slip.hpp"
#include "integrate/adaptive.hpp"
#include "integrate/located.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"
#include "support/located_cuts.hpp"

namespace bkq {
namespace {

constexpr double kSigma = 0.01;
constexpr double kStuckAt = -1.0 + 2.0 * kSigma;  // where the single block sticks, at t = pi

double observed_order(double err_coarse, double err_fine, double h_coarse, double h_fine) {
  return std::log(err_coarse / err_fine) / std::log(h_coarse / h_fine);
}

std::unique_ptr<Stepper> located(const std::string& scheme, int n) {
  return with_located_transitions(make_stepper(scheme, n), n);
}

struct Driven {
  ChainState st;
  double stick_time = std::nan("");
  int steps = 0;
};

// What the event engine does after each step (the contact pass with the stepper's rule),
// with every block in the ranges and the substrate frozen, up to time T; after each step
// `check(st)` (the invariants).
template <class Check>
Driven drive(const ChainForces& forces, Stepper& stepper, ChainState st, double dt, double T,
             Check&& check) {
  const int n = forces.n();
  const std::vector<Range> ranges{{0, n}};
  const Substrate frozen = Substrate::frozen(st.s);
  const bool crossing = stepper.stick_rule() == StickRule::Crossing;
  std::vector<double> wd_old(n);
  Driven run;
  while (st.t < T - 1e-12) {
    wd_old = st.wd;
    stepper.step(forces, frozen, st, std::min(dt, T - st.t), ranges);
    const double anchor = st.s + (forces.params().pad_moves() ? st.x : 0.0);
    const ContactScan scan =
        settle_contacts(forces, st, wd_old.data(), anchor, ranges, crossing, [](int) {});
    ++run.steps;
    check(st);
    if (scan.sliding == 0 && std::isnan(run.stick_time)) {
      const double at = stepper.located_stick_time();
      run.stick_time = std::isnan(at) ? st.t : at;
    }
  }
  run.st = st;
  return run;
}
Driven drive(const ChainForces& forces, Stepper& stepper, ChainState st, double dt, double T) {
  return drive(forces, stepper, std::move(st), dt, T, [](const ChainState&) {});
}

ModelParams single_block(FrictionLaw law) {
  ModelParams p;
  p.kind = ModelKind::BK;
  p.n = 1;
  p.m_u = 1;
  p.k_p = 1;
  p.k_c = 0;
  p.F0 = 1;
  p.law = law;
  p.sigma = kSigma;
  p.v_c = HUGE_VAL;
  return p;
}

ChainState released_at_threshold() {
  ChainState st;
  st.resize(1);
  st.w[0] = -1.0;
  st.mobile[0] = 1.0;
  return st;
}

TEST(LocatedOrder, StickOfALoneBlockKeepsTheSchemesOrder) {
  const std::vector<double> hs = {M_PI / 10.5, M_PI / 20.5, M_PI / 40.5};  // stick mid-step
  for (FrictionLaw law : {law_id<law::Clst91>, law_id<law::Thesis>}) {
    const ChainForces forces(single_block(law));
    for (const char* scheme : {"rk2", "rk4", "verlet"}) {
      const std::string tag = std::string(to_string(law)) + " " + scheme;
      std::vector<double> time_err, pos_err, step_time_err;
      int order = 0;
      for (double h : hs) {
        auto s = located(scheme, 1);
        order = s->order();
        const Driven run = drive(forces, *s, released_at_threshold(), h, 4.0);
        ASSERT_EQ(run.st.mobile[0], 0.0) << tag;
        ASSERT_EQ(run.st.wd[0], 0.0) << tag;
        time_err.push_back(std::abs(run.stick_time - M_PI));
        pos_err.push_back(std::abs(run.st.w[0] - kStuckAt));
        auto plain = make_stepper(scheme, 1);
        step_time_err.push_back(
            std::abs(drive(forces, *plain, released_at_threshold(), h, 4.0).stick_time - M_PI));
      }
      for (size_t k = 0; k + 1 < hs.size(); ++k) {
        const double want = order - 0.5;
        EXPECT_GE(observed_order(time_err[k], time_err[k + 1], hs[k], hs[k + 1]), want)
            << tag << " stick time, errors " << time_err[k] << ", " << time_err[k + 1];
        EXPECT_GE(observed_order(pos_err[k], pos_err[k + 1], hs[k], hs[k + 1]), want)
            << tag << " position, errors " << pos_err[k] << ", " << pos_err[k + 1];
        // The same scheme at the step sticks at the first step end after pi (order 1).
        EXPECT_NEAR(step_time_err[k], hs[k] / 2, 1e-9) << tag;
      }
      EXPECT_LT(time_err.back(), 0.1 * step_time_err.back()) << tag;
    }
  }
}

// The lone-slip record with located transitions: the recorded stick instant and final
// displacement of the block released at the threshold (stiffness 1: stick at t = pi after a
// slip of 2 sigma) keep each scheme's order; at the step the record's stick is the first
// step end after pi.
TEST(LocatedOrder, LoneSlipRecordKeepsTheSchemesOrder) {
  const std::vector<double> hs = {M_PI / 10.5, M_PI / 20.5, M_PI / 40.5};
  const ModelParams p = single_block(law_id<law::Clst91>);
  for (const char* scheme : {"rk2", "rk4", "verlet"}) {
    std::vector<double> time_err, slip_err;
    const auto stepper = make_stepper(scheme, 1);
    const int order = stepper->order();
    for (double h : hs) {
      const LoneSlip rec = integrate_lone_slip(p, 1.0, *stepper, h, 1000, true);
      ASSERT_TRUE(rec.usable) << scheme << ": " << rec.why_not;
      ASSERT_EQ(rec.steps.back().sliding, 0) << scheme;
      time_err.push_back(std::abs(rec.stick_time - M_PI));
      slip_err.push_back(std::abs(rec.steps.back().d - 2.0 * kSigma));
      const LoneSlip at_step = integrate_lone_slip(p, 1.0, *stepper, h, 1000, false);
      EXPECT_TRUE(std::isnan(at_step.stick_time)) << scheme;
      EXPECT_NEAR(at_step.steps.back().t - M_PI, h / 2, 1e-9) << scheme;
    }
    for (size_t k = 0; k + 1 < hs.size(); ++k) {
      EXPECT_GE(observed_order(time_err[k], time_err[k + 1], hs[k], hs[k + 1]), order - 0.5)
          << scheme << " stick time, errors " << time_err[k] << ", " << time_err[k + 1];
      EXPECT_GE(observed_order(slip_err[k], slip_err[k + 1], hs[k], hs[k + 1]), order - 0.5)
          << scheme << " slip, errors " << slip_err[k] << ", " << slip_err[k + 1];
    }
  }
}

// The lone block again with velocity-weakening friction (clst91, v_c = 0.2): the friction
// has a kink at zero velocity, and the step that crosses it integrates past it; the stick
// time polished on real steps keeps rk4's order (on the dense output alone it did not:
// 2.3 over the accuracy study's ladder). Against the adaptive stepper at tolerance 1e-12.
TEST(LocatedOrder, StickUnderVelocityWeakeningKeepsTheOrderOfRk4) {
  ModelParams p = single_block(law_id<law::Clst91>);
  p.v_c = 0.2;
  const ChainForces forces(p);
  Adaptive reference(1, 1e-12);
  const Driven ref = drive(forces, reference, released_at_threshold(), 1e-3, 4.0);
  ASSERT_EQ(ref.st.mobile[0], 0.0);
  const std::vector<double> hs = {0.1 * 1.0137, 0.05 * 1.0137, 0.025 * 1.0137};
  std::vector<double> err;
  for (double h : hs) {
    auto s = located("rk4", 1);
    err.push_back(
        std::abs(drive(forces, *s, released_at_threshold(), h, 4.0).stick_time - ref.stick_time));
  }
  for (size_t k = 0; k + 1 < hs.size(); ++k)
    EXPECT_GE(observed_order(err[k], err[k + 1], hs[k], hs[k + 1]), 3.5)
        << "errors " << err[k] << ", " << err[k + 1];
}

// The event engine's duration (EventRecord::duration: from the trigger to the instant the
// last sliding block sticks) with located transitions keeps each scheme's order, for events
// of one block (the stick located in the lone-slip record) and of several (the last stick
// located on the general path). The built-in
// Carlson–Langer scene with 30 blocks: pre-event states sampled from a run, each event
// relaxed at dt and dt/2 against the adaptive stepper at tolerance 1e-12 (macro step
// 1e-3, as `bkquake accuracy` does); the median error over the sampled events of each
// kind (16 of each) falls by at least 2^(order - 1/2) from dt to dt/2, and so does the median
// relative error of the moments of the events of several blocks. The pairs sit in
// each scheme's asymptotic range: the local slopes rise towards the order as dt falls
// (here rk4 on events of several blocks: 3.19, 3.66, 3.80, 3.92 from dt = 0.04 to 0.0025),
// so a coarser pair would test the ladder, not the bookkeeping.
TEST(LocatedOrder, EventDurationKeepsTheSchemesOrder) {
  test::Sim sim(test::Settings{{"model.blocks", "30"}});
  sim.run(600);
  std::vector<EngineSnapshot> states;
  std::vector<EventRecord> refs;
  Adaptive reference(sim.p.n, 1e-12);
  int single = 0, multi = 0;
  while (single < 16 || multi < 16) {
    const EngineSnapshot s = sim.engine.snapshot();
    EventEngine e(sim.forces, reference, 1e-3, s);
    const EventRecord r = e.next_event();
    sim.engine.next_event();
    if ((r.blocks == 1 ? single : multi) >= 16) continue;
    ++(r.blocks == 1 ? single : multi);
    states.push_back(s);
    refs.push_back(r);
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  const std::vector<std::pair<const char*, std::vector<double>>> ladders = {
      {"rk2", {0.01, 0.005}}, {"rk4", {0.01, 0.005}}, {"verlet", {0.02, 0.01}}};
  for (const auto& [scheme, hs] : ladders) {
    const int order = make_stepper(scheme, sim.p.n)->order();
    std::vector<double> err_single, err_multi, err_moment;  // per dt: the median error
    for (double h : hs) {
      auto s = located(scheme, sim.p.n);
      std::vector<double> e1, em, mm;
      for (std::size_t k = 0; k < states.size(); ++k) {
        EventEngine e(sim.forces, *s, h, states[k]);
        const EventRecord r = e.next_event();
        ASSERT_EQ(r.blocks, refs[k].blocks) << scheme << " dt " << h << " event " << k;
        (r.blocks == 1 ? e1 : em).push_back(std::abs(r.duration - refs[k].duration));
        if (r.blocks > 1) mm.push_back(std::abs(r.moment - refs[k].moment) / refs[k].moment);
      }
      err_single.push_back(median(e1));
      err_multi.push_back(median(em));
      err_moment.push_back(median(mm));
    }
    EXPECT_GE(observed_order(err_single[0], err_single[1], hs[0], hs[1]), order - 0.5)
        << scheme << " one-block events, median errors " << err_single[0] << ", " << err_single[1];
    EXPECT_GE(observed_order(err_multi[0], err_multi[1], hs[0], hs[1]), order - 0.5)
        << scheme << " events of several blocks, median errors " << err_multi[0] << ", "
        << err_multi[1];
    // Their moments too: the sticks before the last one are located without the polish
    // (their instants enter the state only quadratically), and the order holds.
    EXPECT_GE(observed_order(err_moment[0], err_moment[1], hs[0], hs[1]), order - 0.5)
        << scheme << " moments of events of several blocks, median errors " << err_moment[0] << ", "
        << err_moment[1];
  }
}

// Two blocks (test_adaptive.cpp): block 0 released at the threshold, block 1 stuck 0.005
// below it and pulled over it inside a step; then both stick.
ModelParams two_blocks() {
  ModelParams p = single_block(law_id<law::Clst91>);
  p.n = 2;
  p.k_c = 1;
  return p;
}

ChainState two_blocks_start() {
  ChainState st;
  st.resize(2);
  const double w0 = -2.995 / 3.0;
  st.w = {w0, 1.0 + 2.0 * w0};
  st.mobile = {1.0, 0.0};
  return st;
}

TEST(LocatedOrder, FailureInsideAStepKeepsTheSchemesOrder) {
  const ChainForces forces(two_blocks());
  Adaptive reference(2, 1e-12);
  const Driven ref = drive(forces, reference, two_blocks_start(), 10.0, 10.0);
  ASSERT_EQ(reference.releases_in_step().size(), 1u);  // in its one macro step
  ASSERT_EQ(ref.st.mobile[1], 0.0);
  ASSERT_GT(ref.st.w[1], two_blocks_start().w[1] + 1e-3);  // block 1 slipped
  auto error = [&](const ChainState& st) {
    return std::max(std::abs(st.w[0] - ref.st.w[0]), std::abs(st.w[1] - ref.st.w[1]));
  };
  // Steps whose grid does not meet the release time, nor the sticks.
  const std::vector<double> hs = {0.1 * 1.0137, 0.05 * 1.0137, 0.025 * 1.0137};
  for (const char* scheme : {"rk2", "rk4", "verlet"}) {
    std::vector<double> err;
    int order = 0;
    std::int64_t transitions = 0;
    for (double h : hs) {
      auto s = located(scheme, 2);
      order = s->order();
      err.push_back(error(drive(forces, *s, two_blocks_start(), h, 10.0).st));
      transitions = dynamic_cast<LocatedTransitions&>(*s).located_transitions();
    }
    EXPECT_EQ(transitions, 3) << scheme;  // block 1 released, both stick
    for (size_t k = 0; k + 1 < hs.size(); ++k)
      EXPECT_GE(observed_order(err[k], err[k + 1], hs[k], hs[k + 1]), order - 0.5)
          << scheme << " errors " << err[k] << ", " << err[k + 1];
  }
}

// After every step: sliding blocks move with their direction (or rest), stuck blocks hold.
void expect_invariants(const ChainForces& forces, const ChainState& st, const std::string& tag) {
  const double anchor = st.s + (forces.params().pad_moves() ? st.x : 0.0);
  for (int j = 0; j < forces.n(); ++j) {
    if (st.mobile[j] != 0.0) {
      ASSERT_GE(st.dir[j] * st.wd[j], 0.0) << tag << " block " << j << " t " << st.t;
    } else {
      ASSERT_TRUE(forces.friction().holds(forces.spring_force(st.w.data(), j, anchor)))
          << tag << " block " << j << " t " << st.t;
    }
  }
}

TEST(LocatedInvariants, NoBlockEndsAStepSlidingBackwardsOrStuckAboveTheThreshold) {
  // A 12-block chain of the thesis law (backslip) and of clst91, every block near the
  // threshold, one released: the event spreads, blocks stick and fail repeatedly.
  for (FrictionLaw law : {law_id<law::Clst91>, law_id<law::Thesis>}) {
    ModelParams p;
    p.kind = ModelKind::BK;
    p.n = 12;
    p.k_c = 20;
    p.law = law;
    p.sigma = 0.05;
    p.v_c = 0.5;
    const ChainForces forces(p);
    ChainState start;
    start.resize(p.n);
    // Every block at force 0.97, block 5 at the threshold (k_p + 2 k_c = 41) and released.
    for (int j = 0; j < p.n; ++j) start.w[j] = -0.97;
    start.w[5] = -0.97 - 0.03 / 41.0;
    start.mobile[5] = 1.0;
    for (const char* scheme : {"rk2", "rk4", "verlet"})
      for (bool loc : {false, true}) {
        auto s = loc ? located(scheme, p.n) : make_stepper(scheme, p.n);
        const std::string tag =
            std::string(to_string(law)) + " " + scheme + (loc ? " located" : " step");
        int checked = 0;
        const Driven run = drive(forces, *s, start, 0.02, 30.0, [&](const ChainState& st) {
          if (::testing::Test::HasFatalFailure()) return;
          expect_invariants(forces, st, tag);
          ++checked;
        });
        EXPECT_EQ(checked, run.steps) << tag;
        EXPECT_GT(run.steps, 100) << tag;
        if (loc) {
          EXPECT_GT(dynamic_cast<LocatedTransitions&>(*s).located_transitions(), 2) << tag;
        }
      }
  }
}

double median_abs_residual(const std::string& scheme, const std::string& transitions) {
  test::Sim sim({{"model.blocks", "40"},
                 {"integrator.scheme", scheme},
                 {"integrator.transitions", transitions},
                 {"integrator.dt", "0.02"}});
  std::vector<double> r;
  for (int i = 0; i < 600; ++i) r.push_back(std::abs(sim.engine.next_event().energy_residual));
  std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
  return r[r.size() / 2];
}

TEST(LocatedEnergy, BalanceClosesAtLeastAsWellAsAtTheStep) {
  for (const char* scheme : {"rk2", "rk4", "verlet"}) {
    const double step = median_abs_residual(scheme, "step");
    const double loc = median_abs_residual(scheme, "located");
    EXPECT_LE(loc, step) << scheme << ": located " << loc << ", step " << step;
  }
}

// A continuous run of a 20-block chain (speed 0.01): the sum of the episodes' moments
// against the blocks' displacement from the start to the end of the last episode. Located,
// before the driver took the stepper's releases, the episodes left out every block a slip
// reached inside a step (here about half of the slip: 44.7 of 93).
TEST(LocatedContinuous, EpisodeMomentsAddUpToTheBlocksSlip) {
  const Scene scene = test::make_scene({{"model.blocks", "20"}, {"drive.mode", "continuous"}});
  const ModelParams p = model_from_scene(scene);
  const ChainForces forces(p);
  for (bool loc : {false, true}) {
    for (const char* scheme : {"rk2", "rk4", "verlet", "adaptive"}) {
      // The adaptive scheme locates its own releases: one row, under "located".
      if (std::string(scheme) == "adaptive" && !loc) continue;
      const std::string tag = std::string(scheme) + (loc ? " located" : " step");
      auto stepper = std::string(scheme) == "adaptive" ? make_stepper(scheme, p.n)
                     : loc                             ? located(scheme, p.n)
                                                       : make_stepper(scheme, p.n);
      ContinuousDriver driver(forces, *stepper, Substrate::constant(0.01),
                              initial_state(forces, 7, 0.5, false), 0.01);
      const std::vector<double> w0 = driver.state().w;
      std::vector<double> w_end = w0;
      double moments = 0;
      int episodes = 0, blocks = 0;
      while (driver.state().t < 300.0) {
        driver.step();
        if (const auto e = driver.finished_episode()) {
          moments += e->moment;
          blocks += e->blocks;
          ++episodes;
          w_end = driver.state().w;
        }
      }
      double slip = 0;
      for (int j = 0; j < p.n; ++j) slip += w_end[j] - w0[j];
      ASSERT_GT(episodes, 20) << tag;
      EXPECT_GT(blocks, episodes) << tag;  // some episodes reach several blocks
      EXPECT_NEAR(moments, slip, 1e-9 * slip) << tag << ": " << episodes << " episodes";
    }
  }
}

// The thesis scene (BK-Pad, thesis units and friction) event by event at rk4, dt = 0.03: in
// its first events a rupture runs through a row of blocks at the threshold within one step,
// each release a cut. The bound on cuts once counted only the blocks the step began with
// (3 here: 40 cuts) and refused the event; the blocks that join the step count now.
TEST(LocatedCuts, ARuptureFrontInsideOneStepIsNotRefused) {
  test::Sim sim({{"model.kind", "bkp"},
                 {"model.parameterisation", "thesis"},
                 {"model.pad_mass", "100"},
                 {"model.caliper_stiffness", "100"},
                 {"model.damping_ratio", "0.0833333333333333"},
                 {"model.s_m", "1"},
                 {"model.s_p", "1"},
                 {"model.s_c", "0.01"},
                 {"friction.law", "thesis"},
                 {"friction.sigma", "0.01"},
                 {"friction.vc", "1"},
                 {"integrator.scheme", "rk4"},
                 {"integrator.dt", "0.03"},
                 {"integrator.transitions", "located"},
                 {"run.initial_disorder", "0.75"}});
  int largest = 0;
  for (int i = 0; i < 20; ++i) largest = std::max(largest, sim.engine.next_event().blocks);
  EXPECT_GT(largest, 10);  // the front ran through many blocks
  EXPECT_GT(dynamic_cast<const LocatedTransitions&>(*sim.stepper).located_transitions(), 40);
}

// The counters of the lower bound (bench/located_bound.cpp): a stick inside a step is one
// cut, over every block of the step's ranges (the whole-range cut), whether or not they
// move; its sliding stretch is the block and the stuck blocks that end it on either side;
// a step without a transition cuts nothing.
TEST(LocatedCuts, AStickInsideAStepIsOneCutOverTheWholeRange) {
  ModelParams p = single_block(law_id<law::Clst91>);
  p.n = 5;  // uncoupled (k_c = 0): the others stay stuck, below the threshold
  const ChainForces forces(p);
  for (const char* scheme : {"rk2", "rk4", "verlet"}) {
    ChainState st;
    st.resize(5);
    st.w[2] = -1.0;  // the middle block, released at the threshold, sticks at t = pi
    st.mobile[2] = 1.0;
    auto s = located(scheme, 5);
    auto& wrapper = dynamic_cast<LocatedTransitions&>(*s);
    LocatedCutCounts counts;
    wrapper.watch_cuts(&counts);
    const Driven run = drive(forces, *s, st, M_PI / 10.5, 4.0);
    ASSERT_EQ(run.st.mobile[2], 0.0) << scheme;
    EXPECT_EQ(counts.cuts, 1) << scheme;
    EXPECT_EQ(counts.cut_blocks, 5) << scheme;
    EXPECT_EQ(counts.stretch_blocks, 3) << scheme;
    EXPECT_EQ(wrapper.located_transitions(), 1) << scheme;
  }
}

TEST(LocatedKey, RefusedForSchemesThatResolveTransitionsThemselves) {
  for (const char* scheme : {"theta", "adaptive"}) {
    try {
      test::make_scene({{"integrator.scheme", scheme}, {"integrator.transitions", "located"}});
      ADD_FAILURE() << scheme << ": accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("integrator.transitions"), std::string::npos)
          << e.what();
    }
    EXPECT_THROW(with_located_transitions(make_stepper(scheme, 4), 4), Error) << scheme;
  }
  const Scene scene = test::make_scene({{"integrator.transitions", "located"}});
  EXPECT_EQ(stepper_of(settings_from_scene(scene).integrator, 10)->stick_rule(),
            StickRule::Located);
  EXPECT_EQ(stepper_of(settings_from_scene(Scene()).integrator, 10)->stick_rule(),
            StickRule::Crossing);
  // The default leaves the hash of every scene as it was before the key.
  Scene with_step;
  with_step.set("integrator.transitions", "step");
  EXPECT_EQ(with_step.hash(), Scene().hash());
  EXPECT_NE(scene.hash(), Scene().hash());
}

}  // namespace
}  // namespace bkq
