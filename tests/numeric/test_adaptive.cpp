// The event-located adaptive stepper (integrate/adaptive.hpp) against closed forms:
//  - smooth phases: a frictionless chain with pulling and neighbour springs (normal modes)
//    and the pad's free decay (thesis eq. 3.14); the error follows the tolerance (chain,
//    max over t <= 10: 4.4e-6, 4.2e-8, 3.9e-10, 4.0e-12 at tolerance 1e-6 .. 1e-12);
//  - across transitions: a single block (Carlson–Langer units m_u = k_p = F0 = 1, alpha = 0
//    so kinetic friction is the constant 1 - sigma) released at the threshold oscillates
//    about the kinetic balance point, u(t) = -(1 - sigma) - sigma cos t, and sticks at
//    t = pi after a slip of 2 sigma (see test_stick.cpp). Run with a fixed internal step
//    h and the transition located on the dense output, DP5 keeps its order ~5 in h across
//    the stick; rk2 and rk4 under the Crossing rule (the engine's contact pass after each
//    step) stick at the first step after pi: the stick time is off by up to h (order 1)
//    and the slip by (sigma/2) delta_t^2 (order 2). With h = pi/(m + 1/2) the stick falls
//    mid-step, so the Crossing error is exactly h/2, not a function of the grid's phase.
//    Measured (clst91 and thesis identical), errors in stick time / final position:
//      h        DP5 located          rk4 Crossing        rk2 Crossing
//      0.2992   1.0e-6  / 1.8e-8     1.5e-1 / 1.1e-4     1.5e-1 / 8.6e-5
//      0.1532   1.9e-8  / 7.0e-10    7.7e-2 / 2.9e-5     7.7e-2 / 2.5e-5
//      0.0776   3.2e-10 / 2.4e-11    3.9e-2 / 7.5e-6     3.9e-2 / 7.0e-6
//    observed orders: DP5 5.9, 6.0 / 4.9, 5.0; rk2, rk4 1.0, 1.0 / 2.0, 1.9 (with the
//    transition located on the dense output alone, before it was polished on real steps:
//    DP5 5.4, 5.3 for the stick time, 1.6e-6 .. 1.1e-9).
//    A located release (two blocks: the trigger pulls its stuck neighbour over the
//    threshold) keeps DP5's order too (4.6, 5.0 against a tolerance-1e-12 reference).
//  - a 10-block Carlson–Langer event (all blocks slip, 19 transitions) agrees with rk4,
//    whose moment converges to it at first order in dt (relative differences 1.4e-5,
//    2.5e-6, 9.4e-7 at dt = 4e-3, 1e-3, 2.5e-4; with a pad 8.0e-6, 1.6e-6, 5.3e-7);
//  - at tolerance 1e-10 the single block's slip is 2 sigma to 1e-10 and its stick time pi
//    to 2e-9 (in one call for the whole slip: the velocity's global error divided by the
//    deceleration sigma; 9e-14 in macro steps of 0.01); a block that overshoots its
//    threshold flips (thesis law) or sticks (clst91) exactly;
//  - the first event of a 2-block chain (k_c = 100, omega ~ 10) as the engine runs it does
//    not depend on the macro step dt, which caps the internal steps: at tolerance 1e-10,
//    moment and duration at dt = 1e-3 and 1e-4 agree to 2e-14 and 7e-14 (one block slips)
//    and 4e-15 and 2e-14 (both slip: a release and two sticks); located on the dense output
//    alone they differed by 8.5e-11 and 1.0e-7 (1e-13 and 1.2e-10). At dt = 1e-2 the
//    internal steps are ~1e-2 and what remains is DP5's global error there: 9.5e-10 and
//    2.7e-9 against dt = 1e-3 (1.6e-11 and 1.1e-9), shrinking with the tolerance (1.2e-10
//    and 2.8e-10 at 1e-12, 2e-12 and 3e-12 at 1e-14); on the dense output alone the
//    duration was off by 6.8e-8.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../scene_sim.hpp"
#include "core/error.hpp"
#include "engine/contacts.hpp"
#include "integrate/adaptive.hpp"
#include "integrate/rk2.hpp"
#include "integrate/rk4.hpp"
#include "model/chain.hpp"
#include "model/damped_oscillator.hpp"
#include "model/substrate.hpp"

namespace bkq {
namespace {

constexpr double kSigma = 0.01;

double observed_order(double err_coarse, double err_fine, double h_coarse, double h_fine) {
  return std::log(err_coarse / err_fine) / std::log(h_coarse / h_fine);
}

// ---- a driver that does what the engine does after each step ----

struct Driven {
  ChainState st;
  double stick_time = std::nan("");  // when every block was stuck again (located, for Adaptive)
  std::vector<int> slipped;          // blocks that slid at some point
};

// Advances `st` with the substrate frozen, every block in the ranges, in macro steps dt
// (the first one `first` long when given) up to time T, or until every block is stuck
// when until_stuck; after each step the engine's contact pass with the stepper's rule.
Driven drive(const ChainForces& forces, Stepper& stepper, ChainState st, double dt, double T,
             bool until_stuck, double first = 0.0) {
  const int n = forces.n();
  const std::vector<Range> ranges{{0, n}};
  const Substrate frozen = Substrate::frozen(st.s);
  const bool crossing = stepper.stick_rule() == StickRule::Crossing;
  auto* adaptive = dynamic_cast<Adaptive*>(&stepper);
  std::vector<double> wd_old(n);
  Driven run;
  run.slipped.assign(n, 0);
  for (int j = 0; j < n; ++j) run.slipped[j] = st.mobile[j] != 0.0;
  while (st.t < T - 1e-12) {
    wd_old = st.wd;
    const double h = first > 0.0 ? first : std::min(dt, T - st.t);
    first = 0.0;
    stepper.step(forces, frozen, st, h, ranges);
    const double anchor = st.s + (forces.params().pad_moves() ? st.x : 0.0);
    const ContactScan scan =
        settle_contacts(forces, st, wd_old.data(), anchor, ranges, crossing, [](int) {});
    if (adaptive)
      for (const Adaptive::Release& r : adaptive->releases()) run.slipped[r.block] = 1;
    for (int j = 0; j < n; ++j) run.slipped[j] |= st.mobile[j] != 0.0;
    if (scan.sliding == 0 && std::isnan(run.stick_time)) {
      run.stick_time = adaptive ? adaptive->last_stick_time() : st.t;
      if (until_stuck) break;
    }
  }
  run.st = st;
  return run;
}

// ---- the single block of the file comment ----

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
  p.v_c = HUGE_VAL;  // alpha = 0: flat kinetic friction 1 - sigma
  return p;
}

// Substrate at 0, spring force k_p (0 - w) = 1: exactly the threshold; released.
ChainState released_at_threshold() {
  ChainState st;
  st.resize(1);
  st.w[0] = -1.0;
  st.mobile[0] = 1.0;
  return st;
}

constexpr double kStuckAt = -1.0 + 2.0 * kSigma;  // where it sticks, at t = pi

struct SingleBlockErrors {
  double stick_time, position;
};

SingleBlockErrors single_block_errors(FrictionLaw law, Stepper& stepper, double dt) {
  const ChainForces forces(single_block(law));
  const Driven run = drive(forces, stepper, released_at_threshold(), dt, 4.0, false);
  EXPECT_EQ(run.st.mobile[0], 0.0) << stepper.name() << " dt=" << dt;
  EXPECT_EQ(run.st.wd[0], 0.0) << stepper.name() << " dt=" << dt;
  return {std::abs(run.stick_time - M_PI), std::abs(run.st.w[0] - kStuckAt)};
}

// ---- 1. smooth phases ----

// Free chain with pulling springs: normal modes phi_k(j) = cos(pi k (j + 1/2)/n) with
// omega_k^2 = k_p/m + 4 (k_c/m) sin^2(pi k/(2n)) (the pulling springs add k_p/m to each).
struct ChainModes {
  int n;
  std::vector<double> a, b, om;
  ChainModes(const ModelParams& p, const std::vector<double>& u0, const std::vector<double>& v0)
      : n(p.n), a(p.n), b(p.n), om(p.n) {
    for (int k = 0; k < n; ++k) {
      const double s = std::sin(M_PI * k / (2.0 * n));
      om[k] = std::sqrt(p.k_p / p.m_u + 4.0 * p.k_c / p.m_u * s * s);
      const double norm = k == 0 ? n : n / 2.0;
      for (int j = 0; j < n; ++j) {
        a[k] += u0[j] * phi(k, j) / norm;
        b[k] += v0[j] * phi(k, j) / norm;
      }
    }
  }
  double phi(int k, int j) const { return std::cos(M_PI * k * (j + 0.5) / n); }
  double u(int j, double t) const {
    double x = 0;
    for (int k = 0; k < n; ++k)
      x += (a[k] * std::cos(om[k] * t) + b[k] * std::sin(om[k] * t) / om[k]) * phi(k, j);
    return x;
  }
};

struct SmoothRun {
  double error = 0;
  std::int64_t steps = 0, transitions = 0;
};

SmoothRun harmonic_chain(double tolerance) {
  ModelParams p;
  p.kind = ModelKind::BK;
  p.n = 5;
  p.m_u = 1.5;
  p.k_p = 1;
  p.k_c = 6;
  p.law = law_id<law::None>;
  const ChainForces forces(p);
  std::mt19937_64 rng(20240917);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  ChainState st;
  st.resize(p.n);
  for (double& w : st.w) w = uni(rng);
  for (double& v : st.wd) v = 0.3 * uni(rng);
  st.mobile.assign(p.n, 1.0);
  const ChainModes exact(p, st.w, st.wd);
  Adaptive stepper(p.n, tolerance);
  const std::vector<Range> ranges{{0, p.n}};
  const Substrate frozen = Substrate::frozen(0.0);
  SmoothRun r;
  for (int i = 0; i < 10; ++i) {  // macro steps of 1: the stepper chooses its own
    stepper.step(forces, frozen, st, 1.0, ranges);
    EXPECT_EQ(st.t, i + 1.0);  // lands exactly on the macro step's end
    for (int j = 0; j < p.n; ++j) r.error = std::max(r.error, std::abs(st.w[j] - exact.u(j, st.t)));
  }
  r.steps = stepper.accepted_steps();
  r.transitions = stepper.located_transitions();
  return r;
}

TEST(AdaptiveSmooth, HarmonicChainErrorFollowsTheTolerance) {
  std::vector<SmoothRun> runs;
  for (double tol : {1e-6, 1e-8, 1e-10, 1e-12}) runs.push_back(harmonic_chain(tol));
  for (size_t k = 0; k + 1 < runs.size(); ++k) {
    // Tolerance / 100: the global error of a 5th-order pair shrinks by about 100^(5/6).
    EXPECT_LT(runs[k + 1].error, runs[k].error / 10) << "tolerance step " << k;
    EXPECT_GT(runs[k + 1].steps, runs[k].steps);
  }
  EXPECT_LT(runs.back().error, 1e-9);
  for (const SmoothRun& r : runs) EXPECT_EQ(r.transitions, 0);  // frictionless: nothing to locate
}

TEST(AdaptiveSmooth, PadFreeDecayFollowsThesisEq314) {
  // Thesis §3.3 test 3: m_x = 100, K = k_p0 + N k_p = 200, c_p = 20, every block held.
  ModelParams p;
  p.kind = ModelKind::BKP;
  p.n = 100;
  p.k_p0 = 100;
  p.m_x = 100;
  p.c_p = 20;
  p.law = law_id<law::Thesis>;
  p.sigma = 0.01;
  p.v_c = 1;
  const ChainForces forces(p);
  const DampedOscillator exact(100.0, 20.0, 200.0, 0.5, 0.0);
  ChainState st;
  st.resize(p.n);
  st.x = 0.5;
  st.recompute_sum_w();
  Adaptive stepper(p.n, 1e-10);
  const std::vector<Range> ranges{{0, p.n}};
  double err = 0;
  for (int i = 0; i < 20; ++i) {
    stepper.step(forces, Substrate::frozen(0.0), st, 0.5, ranges);
    err = std::max(err, std::abs(st.x - exact.position(st.t)));
  }
  EXPECT_LT(err, 1e-8);
  for (int j = 0; j < p.n; ++j) {
    ASSERT_EQ(st.w[j], 0.0);  // |f| = k_p |x| <= 0.5 holds every block
    ASSERT_EQ(st.mobile[j], 0.0);
  }
  EXPECT_EQ(stepper.located_transitions(), 0);
}

// ---- 2. order across transitions, fixed internal steps ----

TEST(AdaptiveOrder, LocatedStickKeepsOrderFiveWhereTheCrossingRuleDropsToOne) {
  const std::vector<double> hs = {M_PI / 10.5, M_PI / 20.5, M_PI / 40.5};  // stick mid-step
  for (FrictionLaw law : {law_id<law::Clst91>, law_id<law::Thesis>}) {
    const std::string tag = to_string(law);
    std::vector<SingleBlockErrors> dp5, rk4, rk2;
    for (double h : hs) {
      Adaptive a(1, 1e-8);
      a.set_fixed_step(h);
      dp5.push_back(single_block_errors(law, a, h));
      Rk4 b(1);
      rk4.push_back(single_block_errors(law, b, h));
      Rk2 c(1);
      rk2.push_back(single_block_errors(law, c, h));
    }
    for (size_t k = 0; k + 1 < hs.size(); ++k) {
      const double q_time =
          observed_order(dp5[k].stick_time, dp5[k + 1].stick_time, hs[k], hs[k + 1]);
      const double q_pos = observed_order(dp5[k].position, dp5[k + 1].position, hs[k], hs[k + 1]);
      EXPECT_GE(q_time, 5.0) << tag << " DP5 stick time, h = " << hs[k + 1];
      EXPECT_GE(q_pos, 3.5) << tag << " DP5 position, h = " << hs[k + 1];
      for (const auto* crossing : {&rk4, &rk2}) {
        const char* name = crossing == &rk4 ? "rk4" : "rk2";
        const auto& e = *crossing;
        EXPECT_LT(observed_order(e[k].stick_time, e[k + 1].stick_time, hs[k], hs[k + 1]), 1.5)
            << tag << " " << name;
        EXPECT_LT(observed_order(e[k].position, e[k + 1].position, hs[k], hs[k + 1]), 2.5)
            << tag << " " << name;
        EXPECT_NEAR(e[k].stick_time, hs[k] / 2, 1e-9)
            << tag << " " << name;  // the first step after pi
      }
    }
    EXPECT_LT(dp5.back().stick_time, 1e-9) << tag;
    EXPECT_LT(dp5.back().position, 1e-10) << tag;
  }
}

// Two blocks coupled by k_c = 1: block 0 released at the threshold, block 1 stuck 0.005
// below it; block 0's slip pulls block 1 over the threshold (a located release), then both
// stick. No closed form: the reference is the adaptive stepper at tolerance 1e-12.
ModelParams two_blocks() {
  ModelParams p = single_block(law_id<law::Clst91>);
  p.n = 2;
  p.k_c = 1;
  return p;
}

ChainState two_blocks_start() {
  // f_0 = (w_1 - w_0) - w_0 = 1 and f_1 = (w_0 - w_1) - w_1 = 0.995.
  ChainState st;
  st.resize(2);
  const double w0 = -2.995 / 3.0;
  st.w = {w0, 1.0 + 2.0 * w0};
  st.mobile = {1.0, 0.0};
  return st;
}

double two_blocks_error(const ChainState& st, const ChainState& ref) {
  return std::max(std::abs(st.w[0] - ref.w[0]), std::abs(st.w[1] - ref.w[1]));
}

TEST(AdaptiveOrder, LocatedReleaseKeepsHighOrder) {
  const ChainForces forces(two_blocks());
  Adaptive reference(2, 1e-12);
  const Driven ref = drive(forces, reference, two_blocks_start(), 10.0, 10.0, false);
  ASSERT_EQ(ref.slipped, (std::vector<int>{1, 1}));
  ASSERT_EQ(reference.located_transitions(), 3);  // block 1 released, both stick
  ASSERT_EQ(reference.releases().size(), 1u);
  EXPECT_EQ(reference.releases()[0].block, 1);
  EXPECT_EQ(reference.releases()[0].w, two_blocks_start().w[1]);  // released where it was held

  const std::vector<double> hs = {0.2, 0.1, 0.05};
  std::vector<double> dp5;
  for (double h : hs) {
    Adaptive a(2, 1e-8);
    a.set_fixed_step(h);
    dp5.push_back(
        two_blocks_error(drive(forces, a, two_blocks_start(), h, 10.0, false).st, ref.st));
  }
  for (size_t k = 0; k + 1 < hs.size(); ++k)
    EXPECT_GE(observed_order(dp5[k], dp5[k + 1], hs[k], hs[k + 1]), 3.5)
        << "errors " << dp5[0] << ", " << dp5[1] << ", " << dp5[2];
  // rk4 releases block 1 at the end of the step in which it crossed: its error depends on
  // where the grid meets the crossing, so average over four grid phases.
  double rk4 = 0;
  for (double phase : {0.0, 0.25, 0.5, 0.75}) {
    Rk4 b(2);
    rk4 += two_blocks_error(
               drive(forces, b, two_blocks_start(), hs.back(), 10.0, false, phase * hs.back()).st,
               ref.st) /
           4;
  }
  EXPECT_GT(rk4, 1e4 * dp5.back()) << "rk4 " << rk4 << ", DP5 " << dp5.back();
}

// ---- 3. a multi-block event against rk4 ----

struct EventResult {
  double moment = 0, duration = 0;
  int blocks = 0;
  double sum_w_drift = 0;
};

// A 10-block Carlson–Langer chain (l = 10, alpha = 2.5, sigma = 0.01, clst91), nearly
// uniform so that the trigger's slip pulls every block along; the most loaded block is put
// at the threshold and released, the substrate frozen, run until every block is stuck.
EventResult ten_block_event(Stepper& stepper, double dt, bool pad) {
  ModelParams p;
  p.kind = pad ? ModelKind::BKP : ModelKind::BK;
  p.n = 10;
  p.k_c = 100;
  p.law = law_id<law::Clst91>;
  p.sigma = 0.01;
  p.v_c = 0.2;
  if (pad) {
    p.m_x = 10;
    p.k_p0 = 10;
    p.c_p = 2;
  }
  const ChainForces forces(p);
  ChainState st;
  st.resize(p.n);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (double& w : st.w) w = 1e-5 * uni(rng);
  st.recompute_sum_w();
  int trigger = 0;
  for (int j = 1; j < p.n; ++j)
    if (forces.local_force(st.w.data(), j) > forces.local_force(st.w.data(), trigger)) trigger = j;
  // Load so the trigger sits at the threshold (with the pad at its balance).
  const double rate = p.loading_rate(), g = forces.local_force(st.w.data(), trigger);
  st.s = 0;
  if (pad) st.x = forces.pad_equilibrium(st.sum_w, 0.0);
  st.s = (1.0 - g - p.k_p * (pad ? st.x : 0.0)) / rate;
  if (pad) st.x = forces.pad_equilibrium(st.sum_w, st.s);
  st.mobile[trigger] = 1.0;
  const std::vector<double> w0 = st.w;
  const Driven run = drive(forces, stepper, st, dt, 100.0, true);
  EventResult r;
  for (int j = 0; j < p.n; ++j) {
    r.moment += run.st.w[j] - w0[j];
    r.blocks += run.slipped[j];
  }
  r.duration = run.stick_time;
  ChainState copy = run.st;
  r.sum_w_drift = std::abs(copy.sum_w - copy.recompute_sum_w());
  return r;
}

TEST(AdaptiveAgreement, TenBlockEventMatchesRk4ToItsFirstOrderTransitionError) {
  for (bool pad : {false, true}) {
    Adaptive adaptive(10, 1e-10);
    const EventResult a = ten_block_event(adaptive, 0.5, pad);
    EXPECT_EQ(a.blocks, 10) << "pad " << pad;
    EXPECT_GT(adaptive.rejected_steps(), 0) << "pad " << pad;  // the controller is at work
    if (pad) {
      EXPECT_LT(a.sum_w_drift, 1e-12);
    }
    std::vector<double> diff;
    for (double dt : {4e-3, 1e-3, 2.5e-4}) {
      Rk4 rk4(10);
      const EventResult b = ten_block_event(rk4, dt, pad);
      EXPECT_EQ(b.blocks, a.blocks) << "pad " << pad << " dt " << dt;
      diff.push_back(std::abs(b.moment - a.moment) / a.moment);
      // First order: the transitions are late by up to a step each.
      EXPECT_LT(diff.back(), 0.01 * dt)
          << "pad " << pad << " dt " << dt << ": moments " << b.moment << " vs " << a.moment;
      EXPECT_GE(b.duration, a.duration - 1e-9) << "pad " << pad << " dt " << dt;
      EXPECT_LT(b.duration, a.duration + 3 * dt) << "pad " << pad << " dt " << dt;
    }
    EXPECT_LT(diff[2], diff[0] / 4) << "pad " << pad << ": rk4 converges to the adaptive moment";
  }
}

// ---- 4. accuracy at tolerance 1e-10 ----

TEST(AdaptiveAccuracy, SingleBlockSlipsTwoSigmaAndSticksAtPi) {
  for (FrictionLaw law : {law_id<law::Clst91>, law_id<law::Thesis>}) {
    for (double dt : {0.01, 4.0}) {  // the engine's macro step, or one call for the whole slip
      Adaptive a(1, 1e-10);
      const SingleBlockErrors e = single_block_errors(law, a, dt);
      EXPECT_LT(e.position, 1e-9) << to_string(law) << " dt " << dt;  // slip 2 sigma
      EXPECT_LT(e.stick_time, 5e-9) << to_string(law) << " dt " << dt;
      EXPECT_EQ(a.located_transitions(), 1) << to_string(law) << " dt " << dt;
      EXPECT_GE(a.polishing_steps(), 1) << to_string(law) << " dt " << dt;
      EXPECT_LE(a.polishing_steps(), 4) << to_string(law) << " dt " << dt;
    }
  }
}

// A block thrown forwards at speed V from w = 0 (force 0) decelerates under the spring and
// kinetic friction: w = -(1 - sigma)(1 - cos t) + V sin t, turning at t1 = atan2(V, 1 - sigma)
// at w1 = sqrt((1 - sigma)^2 + V^2) - (1 - sigma). For V = 3 its force -w1 is beyond -F0:
// the thesis law cannot hold it and it slides back, about 1 - sigma, to 2 (1 - sigma) - w1
// where it sticks at t1 + pi; clst91 holds any force below F0, so it sticks at the turn.
TEST(AdaptiveAccuracy, OvershootingBlockTurnsBackOrSticksAtTheTurningPoint) {
  const double V = 3.0, kin = 1.0 - kSigma;
  const double t1 = std::atan2(V, kin), w1 = std::hypot(kin, V) - kin;
  ASSERT_GT(w1, 1.0);
  for (FrictionLaw law : {law_id<law::Thesis>, law_id<law::Clst91>}) {
    const ChainForces forces(single_block(law));
    ChainState st;
    st.resize(1);
    st.wd[0] = V;
    st.mobile[0] = 1.0;
    Adaptive a(1, 1e-10);
    const Driven run = drive(forces, a, st, 0.5, 8.0, false);
    const bool backslip = law == law_id<law::Thesis>;
    EXPECT_NEAR(run.st.w[0], backslip ? 2.0 * kin - w1 : w1, 1e-9) << to_string(law);
    EXPECT_NEAR(run.stick_time, backslip ? t1 + M_PI : t1, 1e-8) << to_string(law);
    EXPECT_EQ(a.located_transitions(), backslip ? 2 : 1) << to_string(law);
    EXPECT_EQ(run.st.mobile[0], 0.0);
  }
}

// ---- 5. independence of the macro step ----

// The first event of a 2-block Carlson–Langer chain (k_c = 100) from the seeded initial
// state, set up as `bkquake run` does, at tolerance 1e-10 in macro steps dt.
EventRecord two_block_event(const std::string& seed, const std::string& dt) {
  test::Settings settings{{"model.blocks", "2"},
                          {"integrator.scheme", "adaptive"},
                          {"integrator.tolerance", "1e-10"},
                          {"integrator.dt", dt}};
  if (!seed.empty()) settings.push_back({"run.seed", seed});
  test::Sim sim(settings);
  return sim.engine.next_event();
}

double relative(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}

TEST(AdaptiveAccuracy, EventDoesNotDependOnTheMacroStep) {
  // The default seed: one block slips and sticks; seed 1: both slip (a release, two sticks).
  for (const std::string seed : {"", "1"}) {
    const EventRecord coarse = two_block_event(seed, "0.01");
    const EventRecord mid = two_block_event(seed, "0.001");
    const EventRecord fine = two_block_event(seed, "0.0001");
    ASSERT_EQ(fine.blocks, seed.empty() ? 1 : 2) << "seed '" << seed << "'";
    ASSERT_EQ(mid.blocks, fine.blocks);
    ASSERT_EQ(coarse.blocks, fine.blocks);
    // Internal steps <= 1e-3: the transitions are located to rounding level.
    EXPECT_LT(relative(mid.moment, fine.moment), 1e-12) << "seed '" << seed << "'";
    EXPECT_LT(relative(mid.duration, fine.duration), 1e-12) << "seed '" << seed << "'";
    // Internal steps ~1e-2: DP5's global error at tolerance 1e-10.
    EXPECT_LT(relative(coarse.moment, mid.moment), 2e-9) << "seed '" << seed << "'";
    EXPECT_LT(relative(coarse.duration, mid.duration), 5e-9) << "seed '" << seed << "'";
  }
}

// ---- ranges, the pad's sum and the guards ----

TEST(AdaptiveRanges, BlocksOutsideTheRangesAreHeldAndSumWFollowsThePad) {
  ModelParams p;
  p.kind = ModelKind::BKP;
  p.n = 8;
  p.k_c = 4;
  p.m_x = 5;
  p.k_p0 = 8;
  p.c_p = 1;
  p.law = law_id<law::Clst91>;
  p.sigma = 0.01;
  p.v_c = 0.2;
  const ChainForces forces(p);
  ChainState st;
  st.resize(p.n);
  for (int j = 0; j < p.n; ++j) st.w[j] = 0.01 * j * j;
  st.recompute_sum_w();
  st.x = forces.pad_equilibrium(st.sum_w, 0.0);
  st.s = 1.0 - forces.spring_force(st.w.data(), 3, st.x);  // block 3 at the threshold
  st.mobile[3] = 1.0;
  const ChainState start = st;
  Adaptive a(p.n, 1e-10);
  const std::vector<Range> ranges{{2, 6}};
  a.step(forces, Substrate::frozen(st.s), st, 0.7, ranges);
  EXPECT_EQ(st.t, 0.7);
  for (int j : {0, 1, 6, 7}) {
    EXPECT_EQ(st.w[j], start.w[j]) << j;
    EXPECT_EQ(st.wd[j], 0.0) << j;
  }
  EXPECT_GT(st.w[3], start.w[3]);
  EXPECT_NE(st.x, start.x);
  const double sum = st.sum_w;
  EXPECT_NEAR(sum, st.recompute_sum_w(), 1e-13);
}

TEST(AdaptiveGuards, ToleranceOutOfRangeIsAnErrorNamingTheKey) {
  for (double tol : {0.0, -1e-8, 1.0, std::nan("")}) {
    try {
      Adaptive a(1, tol);
      ADD_FAILURE() << "tolerance " << tol << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("integrator.tolerance"), std::string::npos) << e.what();
    }
  }
  Adaptive a(1, 1e-8);
  EXPECT_THROW(a.set_fixed_step(-0.1), Error);
  EXPECT_THROW(a.set_fixed_step(HUGE_VAL), Error);
}

TEST(AdaptiveGuards, MinimumStepThrowsWithAClearMessage) {
  const ChainForces forces(single_block(law_id<law::Thesis>));
  ChainState st = released_at_threshold();
  st.wd[0] = std::nan("");  // no step size can meet the tolerance
  Adaptive a(1, 1e-8);
  const std::vector<Range> ranges{{0, 1}};
  try {
    a.step(forces, Substrate::frozen(0.0), st, 0.1, ranges);
    ADD_FAILURE() << "a non-finite state was integrated";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("step size"), std::string::npos) << msg;
    EXPECT_NE(msg.find("below the minimum"), std::string::npos) << msg;
    EXPECT_NE(msg.find("integrator.tolerance"), std::string::npos) << msg;
  }
  EXPECT_GT(a.rejected_steps(), 10);
}

}  // namespace
}  // namespace bkq
