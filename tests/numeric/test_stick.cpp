// The stick rule (Crossing, stepper.hpp / contacts.hpp) on the one problem where slip and
// re-stick have a closed form: a single block (Carlson–Langer units m_u = k_p = F0 = 1,
// pad fixed, no neighbours) under clst91 friction with alpha = 0 (v_c infinite, so the
// kinetic friction is the constant 1 - sigma), released from the static threshold with
// the substrate frozen. Relative to its anchor it then oscillates about the kinetic
// balance point:
//   u(t) = -(1 - sigma) - sigma cos t,
// its velocity returns to zero at t = pi after a slip of 2 sigma, and there the spring
// force 1 - 2 sigma is below the threshold, so it must stick for good.
//
// The engine re-sticks the block at the first step t_k >= pi at which the velocity is
// <= 0 (no backslip), keeping the position the stepper reached. So
//   duration = t_k in [pi, pi + dt),
//   moment   = u(t_k) - u(0) = sigma (1 - cos t_k) = 2 sigma - (sigma/2)(t_k - pi)^2 + ...
// The moment error is bounded by (sigma/2) dt^2 (relative dt^2/4) plus the stepper's own
// error; it is not a smooth function of dt (t_k - pi jumps with the step grid), so instead
// of one log2 ratio we check the dt^2 bound at several dt and that the moment equals the
// closed form at the step where the block stuck. Measured (rk4; rk2 and verlet agree to
// 2 digits), relative moment errors and t_k - pi:
//   dt = 0.004: 1.45e-06 (2.4e-3)   dt = 0.002: 4.15e-08 (4.1e-4)
//   dt = 0.001: 4.15e-08 (4.1e-4)   dt = 0.0005: 4.15e-08 (4.1e-4)
// (bound dt^2/4: 4e-6, 1e-6, 2.5e-7, 6.3e-8). The step grids of 0.002, 0.001 and 0.0005
// all first pass pi at 3.142, so the error stalls there: "observed orders" 5.1, 0.0, 0.0 —
// the error is set by where the grid meets pi, bounded by dt^2/4, i.e. second order in
// envelope, better than the first order the Crossing rule promises in general.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "engine/event_engine.hpp"
#include "integrate/stepper.hpp"
#include "model/chain.hpp"
#include "model/stick.hpp"

namespace bkq {
namespace {

constexpr double kSigma = 0.01;

ModelParams single_block() {
  ModelParams p;
  p.kind = ModelKind::BK;
  p.n = 1;
  p.m_u = 1;
  p.k_p = 1;
  p.k_c = 0;
  p.F0 = 1;
  p.law = law_id<law::Clst91>;
  p.sigma = kSigma;
  p.v_c = HUGE_VAL;  // alpha = 0: flat kinetic friction 1 - sigma
  return p;
}

struct SlipResult {
  EventRecord e;
  double excess_after = 0;
  bool stuck_after = false;
};

SlipResult slip_once(const char* scheme, double dt) {
  const ModelParams p = single_block();
  const ChainForces forces(p);
  auto stepper = make_stepper(scheme, p.n);
  ChainState st;
  st.resize(1);
  st.w[0] = -1.0;  // substrate at 0: spring force k_p (0 - w) = 1, exactly the threshold
  EventEngine engine(forces, *stepper, dt, st);
  SlipResult r;
  r.e = engine.next_event();
  r.excess_after = engine.worst_stuck_excess();
  r.stuck_after = engine.state().mobile[0] == 0.0 && engine.state().wd[0] == 0.0;
  EXPECT_EQ(r.e.load, 0.0) << "the block starts at the threshold: no loading needed";
  return r;
}

TEST(StickRule, SingleBlockSlipsTwoSigmaInHalfAPeriod) {
  const double dt = 0.001;
  const SlipResult r = slip_once("rk4", dt);
  EXPECT_EQ(r.e.blocks, 1);
  EXPECT_EQ(r.e.trigger, 0);
  EXPECT_NEAR(r.e.moment, 2 * kSigma, 1e-3 * 2 * kSigma);
  // Re-stuck at the first step at or after t = pi.
  EXPECT_GE(r.e.duration, M_PI - 1e-9);
  EXPECT_LT(r.e.duration, M_PI + dt + 1e-9);
  EXPECT_NEAR(r.e.duration, M_PI, 2 * dt);
  // The largest slip speed is sigma (at t = pi/2).
  EXPECT_LE(r.e.max_speed, kSigma * (1 + 1e-9));
  EXPECT_GE(r.e.max_speed, kSigma * (1 - dt * dt / 8) - 1e-12);
  // Stuck for good: spring force 1 - 2 sigma holds.
  EXPECT_TRUE(r.stuck_after);
  EXPECT_NEAR(r.excess_after, -2 * kSigma, 1e-6);
}

TEST(StickRule, MomentIsTheClosedFormAtTheStickingStepForEveryStepper) {
  for (const char* scheme : {"rk2", "rk4", "verlet"}) {
    for (double dt : {0.004, 0.002, 0.001, 0.0005}) {
      const SlipResult r = slip_once(scheme, dt);
      const double tk = r.e.duration;
      // Stuck at a step time: an integer number of steps after the trigger.
      EXPECT_NEAR(tk / dt, std::round(tk / dt), 1e-6) << scheme << " dt=" << dt;
      EXPECT_GE(tk, M_PI - 1e-9) << scheme << " dt=" << dt;
      EXPECT_LT(tk, M_PI + dt + 1e-9) << scheme << " dt=" << dt;
      // The position at that step is u(t_k) up to the stepper's smooth-phase error
      // (rk2/verlet: ~ sigma T dt^2, far below the dt^2/4 bound below).
      EXPECT_NEAR(r.e.moment, kSigma * (1 - std::cos(tk)), 2e-2 * kSigma * dt * dt)
          << scheme << " dt=" << dt;
      // Envelope: relative moment error below dt^2/4 (+ a little for the stepper).
      const double rel = std::abs(r.e.moment - 2 * kSigma) / (2 * kSigma);
      EXPECT_LE(rel, 0.25 * dt * dt * 1.05 + 1e-12) << scheme << " dt=" << dt;
      EXPECT_TRUE(r.stuck_after) << scheme;
    }
  }
}

// With the thesis law (backslip allowed) the velocity changes sign at t = pi; the spring
// force 1 - 2 sigma is within [-F0, F0], so the block must stick there as well.
//
// Within a step the direction of sliding is frozen (stepper.hpp, Crossing), so friction
// keeps opposing the forward motion while the velocity passes through zero and the rule
// sees the crossing. (Before that, RK stages flipped the sign of friction at y < 0 and the
// block crept on: rk4 at dt = 0.004 slid 0.67 instead of 0.02.)
TEST(StickRule, BackslipLawSticksAtTheTurningPoint) {
  for (const char* scheme : {"rk2", "rk4", "verlet"}) {
    for (double dt : {0.004, 0.002, 0.001, 0.0005}) {
      ModelParams p = single_block();
      p.law = law_id<law::Thesis>;
      const ChainForces forces(p);
      auto stepper = make_stepper(scheme, 1);
      ChainState st;
      st.resize(1);
      st.w[0] = -1.0;
      EventEngine engine(forces, *stepper, dt, st);
      engine.max_steps_per_event = 100'000;  // pi/dt steps are enough
      EventRecord e;
      ASSERT_NO_THROW(e = engine.next_event()) << scheme << " dt=" << dt;
      EXPECT_EQ(e.blocks, 1);
      EXPECT_NEAR(e.moment, 2 * kSigma, 0.25 * dt * dt * 2 * kSigma * 1.05)
          << scheme << " dt=" << dt;
      EXPECT_NEAR(e.duration, M_PI, 2 * dt) << scheme << " dt=" << dt;
      EXPECT_EQ(engine.state().mobile[0], 0.0);
    }
  }
}

// The rule itself (model/stick.hpp), case by case, for a law with backslip (thesis) and
// one without (clst91); threshold F0 = 1.
Friction law_with(FrictionLaw law) {
  ModelParams p = single_block();
  p.law = law;
  return friction_of(p);
}

TEST(StickRuleUnit, CrossingIsASignChangeOrZeroWithBackslipAndNonPositiveWithout) {
  EXPECT_TRUE(stick::crossed(true, 1.0, -1.0));
  EXPECT_TRUE(stick::crossed(true, -1.0, 1.0));
  EXPECT_TRUE(stick::crossed(true, 1.0, 0.0));
  EXPECT_FALSE(stick::crossed(true, 1.0, 0.5));
  EXPECT_FALSE(stick::crossed(true, -1.0, -0.5));
  EXPECT_TRUE(stick::crossed(false, 1.0, -1.0));
  EXPECT_TRUE(stick::crossed(false, 1.0, 0.0));
  EXPECT_TRUE(stick::crossed(false, -1.0, -0.5));  // no backslip: any y1 <= 0
  EXPECT_FALSE(stick::crossed(false, -1.0, 0.5));
}

TEST(StickRuleUnit, SlidingBlockThatCrossesSticksIfFrictionHolds) {
  for (FrictionLaw law : {law_id<law::Thesis>, law_id<law::Clst91>}) {
    const Friction fr = law_with(law);
    const stick::Outcome o = stick::settle(fr, true, 1.0, 1.0, 0.5, -0.25, 0.9);
    EXPECT_EQ(o.y, 0.0);
    EXPECT_EQ(o.mobile, 0.0);
    EXPECT_FALSE(o.slides);
    EXPECT_FALSE(o.breaks);
    EXPECT_EQ(o.dir, 1.0);
  }
}

TEST(StickRuleUnit, SlidingBlockThatCrossesUnderTooLargeAForceSlidesOn) {
  // Backslip: it slides the other way, with its velocity and a new direction.
  const stick::Outcome back =
      stick::settle(law_with(law_id<law::Thesis>), true, 1.0, 1.0, 0.5, -0.25, -1.5);
  EXPECT_EQ(back.y, -0.25);
  EXPECT_EQ(back.mobile, 1.0);
  EXPECT_EQ(back.dir, -1.0);
  EXPECT_TRUE(back.slides);
  // No backslip: it stays at zero velocity, still sliding, its direction unchanged.
  const stick::Outcome none =
      stick::settle(law_with(law_id<law::Clst91>), true, 1.0, 1.0, 0.5, -0.25, 1.5);
  EXPECT_EQ(none.y, 0.0);
  EXPECT_EQ(none.mobile, 1.0);
  EXPECT_EQ(none.dir, 1.0);
  EXPECT_TRUE(none.slides);
}

TEST(StickRuleUnit, SlidingBlockThatDoesNotCrossSlidesOnTheWayItMoves) {
  const Friction fr = law_with(law_id<law::Thesis>);
  const stick::Outcome o = stick::settle(fr, true, 1.0, 1.0, -0.5, -0.25, 0.0);
  EXPECT_EQ(o.y, -0.25);
  EXPECT_EQ(o.dir, -1.0);
  EXPECT_TRUE(o.slides);
  EXPECT_FALSE(stick::needs_force(fr, true, 1.0, -0.5, -0.25));
  // Without the crossing rule (a stepper that resolves transitions) nothing sticks.
  const stick::Outcome free = stick::settle(fr, false, 1.0, 1.0, 0.5, -0.25, 0.0);
  EXPECT_EQ(free.y, -0.25);
  EXPECT_TRUE(free.slides);
}

TEST(StickRuleUnit, StuckBlockBreaksLooseOnlyBeyondTheThreshold) {
  const Friction thesis = law_with(law_id<law::Thesis>), clst91 = law_with(law_id<law::Clst91>);
  EXPECT_TRUE(stick::settle(thesis, true, 0.0, 1.0, 0.0, 0.0, 1.5).breaks);
  EXPECT_TRUE(stick::settle(thesis, true, 0.0, 1.0, 0.0, 0.0, -1.5).breaks);
  EXPECT_FALSE(stick::settle(thesis, true, 0.0, 1.0, 0.0, 0.0, 1.0).breaks);  // at it: holds
  EXPECT_TRUE(stick::settle(clst91, true, 0.0, 1.0, 0.0, 0.0, 1.5).breaks);
  EXPECT_FALSE(stick::settle(clst91, true, 0.0, 1.0, 0.0, 0.0, -1.5).breaks);
  const stick::Outcome o = stick::settle(thesis, true, 0.0, 1.0, 0.0, 0.0, -1.5);
  EXPECT_EQ(o.mobile, 0.0);  // the caller releases it
  EXPECT_FALSE(o.slides);
  EXPECT_EQ(stick::release_direction(-1.5), -1.0);
  EXPECT_TRUE(stick::needs_force(thesis, true, 0.0, 0.0, 0.0));
}

// settle_one (branches, releases the block itself) against settle (branch-free, leaves the
// release to the caller) over a grid: stick flag, direction, velocities of both signs and
// zero at both ends of the step, spring forces below, at and above the threshold both
// ways, laws with and without backslip. settle_one asks for the force only where
// needs_force() says the rule looks at it.
TEST(StickRuleUnit, SettleOneIsSettleWithTheReleaseApplied) {
  const double kY[] = {-0.5, -0.0, 0.0, 0.25};
  // Threshold F0 = 1: below, at and above it, both ways, and zero.
  const double kF[] = {-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5};
  int cases = 0;
  for (FrictionLaw law : {law_id<law::Thesis>, law_id<law::Clst91>}) {
    const Friction fr = law_with(law);
    for (bool crossing_rule : {true, false})
      for (double mobile : {0.0, 1.0})
        for (double dir : {-1.0, 1.0})
          for (double y0 : kY)
            for (double y1 : kY)
              for (double f : kF) {
                const stick::Outcome a = stick::settle(fr, crossing_rule, mobile, dir, y0, y1, f);
                bool asked = false;
                const stick::Outcome b =
                    stick::settle_one(fr, crossing_rule, mobile, dir, y0, y1, [&] {
                      asked = true;
                      return f;
                    });
                // What settle leaves to the caller: a block that breaks loose slides the
                // way its spring pulls.
                stick::Outcome want = a;
                if (a.breaks) {
                  want.mobile = 1.0;
                  want.dir = stick::release_direction(f);
                }
                const std::string where =
                    std::string(fr.backslip ? "backslip" : "no backslip") +
                    " rule=" + std::to_string(crossing_rule) + " mobile=" + std::to_string(mobile) +
                    " dir=" + std::to_string(dir) + " y0=" + std::to_string(y0) +
                    " y1=" + std::to_string(y1) + " f=" + std::to_string(f);
                EXPECT_EQ(std::bit_cast<std::uint64_t>(b.y), std::bit_cast<std::uint64_t>(want.y))
                    << where;
                EXPECT_EQ(b.mobile, want.mobile) << where;
                EXPECT_EQ(b.dir, want.dir) << where;
                EXPECT_EQ(b.slides, want.slides) << where;
                EXPECT_EQ(b.breaks, want.breaks) << where;
                EXPECT_EQ(asked, stick::needs_force(fr, crossing_rule, mobile, y0, y1)) << where;
                ++cases;
              }
  }
  EXPECT_EQ(cases, 2 * 2 * 2 * 2 * 4 * 4 * 7);
}

}  // namespace
}  // namespace bkq
