// One slider integrated alone (engine/rsf_alone.hpp) against the cycle integrator's full aging
// law, its exits, and the loader's blocks alone (engine/rsf_loader.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/dormand_prince.hpp"
#include "engine/rsf_alone.hpp"
#include "engine/rsf_cycle.hpp"
#include "engine/rsf_loader.hpp"
#include "support/qdyn_stickslip.hpp"

namespace bkq {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// QDYN's block on the lattice's unloading stiffness 6e9 Pa/m: its steady sliding at
// V_inf = tau_dot/k_eff is unstable (sigma (b - a)/D_c = 7.5e9 Pa/m), so that from near it the
// block runs away.
rsf::Slider unstable_slider() {
  rsf::Slider s = test::qdyn_slider();
  s.k_eff = 6e9;
  return s;
}

// No exit but the speed `ln_v_target`.
rsf::AloneSlider::Limits open_limits(double ln_v_target) {
  rsf::AloneSlider::Limits lim;
  lim.ln_v_target = ln_v_target;
  lim.amount = kInf;
  lim.ln_omega_lo = -kInf;
  lim.ln_omega_hi = kInf;
  lim.ln_v_locked = -kInf;
  lim.horizon = 1000000;
  return lim;
}

// The cycle integrator on the same block (its own right-hand side, tolerance 1e-11) to time t:
// (slip, ln V, ln theta).
std::vector<double> full_law(const rsf::Slider& s, rsf::SliderState x, double t) {
  RsfCycle c(test::full_law_block(s), 1e-11, {std::exp(x.ln_v)}, {std::exp(x.ln_theta)});
  while (c.t() < t) c.step(t);
  return {c.slip(0), c.ln_v(0), c.ln_theta(0)};
}

// From half the steady-state speed at its state (V theta/D_c = 1/2) to the run-away: the
// forecast's state anywhere along it (at its steps and between them, by the dense output) is the
// full law's to its tolerance's order (ln V and ln theta within 1e-6, slip within 1e-6
// relative; the forecast runs at 1e-8), and its speed exit is where ln V reaches the target
// (the full law's ln V there within 1e-4: in the run-away ln V grows as -ln(t_inst - t), so a
// time within the tolerance moves it by more).
TEST(RsfAlone, FollowsTheFullAgingLawAndExitsAtTheSpeed) {
  const rsf::Slider s = unstable_slider();
  const double v_inf = s.stressing_rate / s.k_eff;
  const rsf::SliderState x{std::log(0.5 * v_inf), std::log(s.dc / v_inf)};
  rsf::AloneSlider alone(1e-8);
  std::vector<rsf::AloneSlider::Point> path;
  const double target = std::log(1e3 * v_inf);
  const auto f = alone.forecast(s, x, open_limits(target), path);
  ASSERT_EQ(f.exit, rsf::AloneSlider::Exit::Speed);
  ASSERT_GT(path.size(), 10u);
  EXPECT_NEAR(alone.at(s, path, f.dt).y[1], target, 1e-9);
  EXPECT_NEAR(full_law(s, x, f.dt)[1], target, 1e-4);
  for (const double share : {0.1, 0.37, 0.5, 0.81, 0.97}) {
    const double t = share * f.dt;
    const rsf::AloneSlider::Point p = alone.at(s, path, t);
    const std::vector<double> ref = full_law(s, x, t);
    EXPECT_NEAR(p.y[0] / ref[0], 1, 1e-6) << t;
    EXPECT_NEAR(p.y[1], ref[1], 1e-6) << t;
    EXPECT_NEAR(p.y[2], ref[2], 1e-6) << t;
  }
}

// A forecast started with a step size given (the loader's: the last forecast's proposal, h_next)
// and at the blocks-alone tolerance 1e-6 (rsf.alone_tolerance's auto) follows the same law: its
// states along the way are the full law's within 1e-4 and its speed exit lies within 1e-4
// (relative) of the one at 1e-8, in fewer steps; a first step far too large is rejected and
// shrunk, not taken.
TEST(RsfAlone, AGivenFirstStepAndTheLooserToleranceFollowTheSameLaw) {
  const rsf::Slider s = unstable_slider();
  const double v_inf = s.stressing_rate / s.k_eff;
  const rsf::SliderState x{std::log(0.5 * v_inf), std::log(s.dc / v_inf)};
  const double target = std::log(1e3 * v_inf);
  std::vector<rsf::AloneSlider::Point> fine_path, path;
  rsf::AloneSlider fine(1e-8);
  const auto ref = fine.forecast(s, x, open_limits(target), fine_path);
  EXPECT_GT(ref.h_next, 0);
  for (const double h_first : {0.0, 0.3 * s.dc / v_inf, 1e3 * s.dc / v_inf}) {
    SCOPED_TRACE(h_first);
    rsf::AloneSlider loose(1e-6);
    const auto f = loose.forecast(s, x, open_limits(target), path, h_first);
    ASSERT_EQ(f.exit, rsf::AloneSlider::Exit::Speed);
    EXPECT_NEAR(f.dt / ref.dt, 1, 1e-4);
    EXPECT_LT(loose.steps(), fine.steps());
    if (h_first > s.dc / v_inf) {
      EXPECT_LT(path[1].dt, h_first);  // rejected, shrunk
    }
    for (const double share : {0.1, 0.5, 0.9}) {
      const double t = share * f.dt;
      const rsf::AloneSlider::Point p = loose.at(s, path, t);
      const std::vector<double> full = full_law(s, x, t);
      EXPECT_NEAR(p.y[1], full[1], 1e-4) << t;
      EXPECT_NEAR(p.y[2], full[2], 1e-4) << t;
    }
  }
}

// The other exits: the slip reaching an amount (the state there has it), nucleation
// (V theta/D_c >= 10 at the exit's step end, below it the step before), the locked form's
// domain (V theta/D_c < 0.05 below the locked speed), and the horizon (so many steps).
TEST(RsfAlone, ExitsAtTheSlipThePhasesAndTheHorizon) {
  const rsf::Slider s = unstable_slider();
  const double v_inf = s.stressing_rate / s.k_eff, ln_dc = std::log(s.dc);
  const rsf::SliderState near{std::log(0.5 * v_inf), std::log(s.dc / v_inf)};
  rsf::AloneSlider alone(1e-8);
  std::vector<rsf::AloneSlider::Point> path;
  using Exit = rsf::AloneSlider::Exit;

  rsf::AloneSlider::Limits lim = open_limits(std::log(1e3 * v_inf));
  lim.amount = 2 * s.dc;
  auto f = alone.forecast(s, near, lim, path);
  ASSERT_EQ(f.exit, Exit::Slip);
  EXPECT_NEAR(alone.at(s, path, f.dt).y[0] / lim.amount, 1, 1e-9);
  EXPECT_NEAR(full_law(s, near, f.dt)[0] / lim.amount, 1, 1e-6);

  const auto ln_omega = [&](const rsf::AloneSlider::Point& p) { return p.y[1] + p.y[2] - ln_dc; };
  lim = open_limits(std::log(1e3 * v_inf));
  lim.ln_omega_lo = std::log(0.05);
  lim.ln_omega_hi = std::log(10.0);
  lim.ln_v_locked = std::log(3 * v_inf);
  f = alone.forecast(s, near, lim, path);
  ASSERT_EQ(f.exit, Exit::Phase);
  EXPECT_EQ(f.dt, path.back().dt);
  EXPECT_GE(ln_omega(path.back()), std::log(10.0));
  EXPECT_LT(ln_omega(path[path.size() - 2]), std::log(10.0));

  // Just after an event: fast and far below steady state (V theta/D_c = 0.01), healing.
  const rsf::SliderState after{std::log(30 * v_inf), std::log(0.01 * s.dc / (30 * v_inf))};
  f = alone.forecast(s, after, lim, path);
  ASSERT_EQ(f.exit, Exit::Phase);
  EXPECT_LT(ln_omega(path.back()), std::log(0.05));
  EXPECT_LT(path.back().y[1], lim.ln_v_locked);
  EXPECT_GE(path[path.size() - 2].y[1], lim.ln_v_locked);

  lim.horizon = 3;
  f = alone.forecast(s, near, lim, path);
  EXPECT_EQ(f.exit, Exit::Phase);
  EXPECT_EQ(path.size(), 4u);
  EXPECT_EQ(f.dt, path.back().dt);
}

// The error norms' running maximum (the cycle integrator's, the active blocks', a block
// alone's): a NaN term rejects the step, where std::max(e, NaN) returns e and would accept it.
TEST(RsfAlone, ANaNInTheErrorNormRejectsTheStep) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(dopri::worse(0.5, 0.25), 0.5);
  EXPECT_EQ(dopri::worse(0.25, 0.5), 0.5);
  EXPECT_FALSE(dopri::worse(0.5, nan) <= 1);
  EXPECT_FALSE(dopri::worse(dopri::worse(0.0, nan), 0.5) <= 1);
  EXPECT_EQ(std::max(0.5, nan), 0.5);  // what the norms did before
}

// Three uncoupled QDYN blocks (k = 2e9 Pa/m: each nucleates on its own) in the loader with
// blocks alone below 1e-4 m/s: one near steady state is alone and its state is the forecast's;
// a sudden stress step multiplies its V by exp(dtau/(a sigma)) at theta kept; one locked and
// slow is in the locked form until V theta/D_c = 0.1, a change of phase that takes it alone;
// one near steady state above 1e-4 m/s is due at once.
TEST(RsfLoaderAlone, BlocksAloneTheirStepsAndTheirClocks) {
  RsfModel m = test::qdyn_stickslip(3);
  const double v_pl = m.v_pl;
  RsfLoader loader(m, 3 * v_pl, kInf);
  loader.integrate_alone(1e-4, 1e-8);
  const double dc = m.law[0].params().dc;
  loader.set(0, 0, {std::log(0.5 * v_pl), std::log(dc / v_pl)});
  loader.set(1, 0, {std::log(0.1 * v_pl), std::log(1e-3 * dc / (0.1 * v_pl))});
  loader.set(2, 0, {std::log(2e-4), std::log(dc / 2e-4)});
  EXPECT_TRUE(loader.alone(0));
  EXPECT_FALSE(loader.alone(1));
  EXPECT_TRUE(loader.alone(2));
  ASSERT_EQ(loader.next_block(), 2);
  EXPECT_EQ(loader.next_time(), 0);
  EXPECT_FALSE(loader.next_is_phase());
  EXPECT_FALSE(loader.next_is_quantum());
  loader.hold(2);

  // Block 0's state at a time inside its forecast: the alone integration's.
  rsf::AloneSlider ref(1e-8);
  std::vector<rsf::AloneSlider::Point> path;
  rsf::AloneSlider::Limits lim = open_limits(std::log(1e-4));
  lim.horizon = 16;
  ref.forecast(loader.slider(0), loader.x_ref(0), lim, path);
  const double t = 0.6 * path.back().dt;
  const rsf::SliderState x = loader.state_at(0, t);
  EXPECT_NEAR(x.ln_v, ref.at(loader.slider(0), path, t).y[1], 1e-12);
  const double dtau = 0.3 * m.law[0].params().a * m.sigma;
  loader.sudden_stress_step(0, t, dtau);
  EXPECT_TRUE(loader.alone(0));
  EXPECT_NEAR(loader.state_at(0, t).ln_v, x.ln_v + 0.3, 1e-12);
  EXPECT_EQ(loader.state_at(0, t).ln_theta, x.ln_theta);

  // Block 1 heals in the locked form; its clock is the change of phase at V theta/D_c = 0.1.
  loader.hold(0);
  ASSERT_EQ(loader.next_block(), 1);
  ASSERT_TRUE(loader.next_is_phase());
  const double t1 = loader.next_time();
  EXPECT_GT(t1, 0);
  loader.rephase();
  EXPECT_TRUE(loader.alone(1));
  EXPECT_NEAR(rsf::ln_omega(loader.slider(1), loader.state_at(1, t1)), std::log(0.1), 1e-9);
  EXPECT_GT(loader.next_time(), t1);
}

// After an event: a block locked far below steady state (V theta/D_c = 1e-3) and slow is in the
// locked form; a sudden stress step that takes it above 3 V_pl there takes it alone (the locked
// form leaves its creep and unloading out); healing brings it back below 3 V_pl, a change of
// phase at a step's end that returns it to the locked form.
TEST(RsfLoaderAlone, ALockedBlockAboveThreeVplIsAloneUntilItHeals) {
  RsfModel m = test::qdyn_stickslip(1);
  const double v_pl = m.v_pl, dc = m.law[0].params().dc, a_sigma = m.law[0].params().a * m.sigma;
  RsfLoader loader(m, 3 * v_pl, kInf);
  loader.integrate_alone(1e-4, 1e-8);
  loader.set(0, 0, {std::log(0.5 * v_pl), std::log(1e-3 * dc / (0.5 * v_pl))});
  EXPECT_FALSE(loader.alone(0));
  loader.sudden_stress_step(0, 0.0, 2 * a_sigma);  // V times e^2: about 3.7 V_pl
  ASSERT_TRUE(loader.alone(0));
  const rsf::SliderState x = loader.state_at(0, 0.0);
  ASSERT_GT(x.ln_v, std::log(3 * v_pl));
  ASSERT_LT(rsf::ln_omega(loader.slider(0), x), std::log(0.05));
  // Its clocks are its forecast's until the change of phase.
  while (!loader.next_is_phase()) {
    ASSERT_TRUE(loader.alone(0));
    ASSERT_FALSE(loader.next_is_quantum());  // no quanta (q = inf)
    ASSERT_GT(loader.next_time(), 0.0);
    loader.rephase();
  }
  const double t = loader.next_time();
  loader.rephase();
  EXPECT_FALSE(loader.alone(0));
  const rsf::SliderState y = loader.state_at(0, t);
  EXPECT_LT(y.ln_v, std::log(3 * v_pl));
  EXPECT_LT(rsf::ln_omega(loader.slider(0), y), std::log(0.05));
  EXPECT_GT(loader.next_time(), t);
}

}  // namespace
}  // namespace bkq
