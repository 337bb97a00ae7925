// integrator.theta: on a frictionless (friction.law = none), undamped
// (zeta = 0, no Rayleigh damping) BK-Pad chain the theta-method at theta = 1/2 conserves
// the energy at any dt (the trapezoidal rule), while theta > 1/2 dissipates it, every step
// and more the larger theta; the stability limit under weakening friction scales as 1/theta.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "integrate/stepper.hpp"
#include "integrate/theta.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"

namespace bkq {
namespace {

Settings frictionless_chain(const char* theta) {
  Scene s;
  s.set("model.kind", "bkp");
  s.set("model.parameterisation", "thesis");
  s.set("model.blocks", "20");
  s.set("model.damping_ratio", "0");
  s.set("friction.law", "none");
  s.set("drive.mode", "continuous");
  s.set("integrator.scheme", "theta");
  s.set("integrator.theta", theta);
  s.set("integrator.dt", "0.05");
  s.validate();
  return settings_from_scene(s);
}

// Energies after each of `steps` steps from a random displacement, substrate frozen.
std::vector<double> energies(const char* theta, int steps) {
  const Settings set = frictionless_chain(theta);
  const ChainForces forces(set.model);
  auto stepper = stepper_of(set.integrator, set.model.n);
  ChainState st;
  st.resize(set.model.n);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (double& w : st.w) w = u(rng);
  st.mobile.assign(set.model.n, 1.0);
  st.x = 0.3;
  st.recompute_sum_w();
  const std::vector<Range> all{{0, set.model.n}};
  const Substrate frozen = Substrate::frozen(0.0);
  std::vector<double> e{forces.spring_energy(st) + forces.kinetic_energy(st, 0.0)};
  for (int i = 0; i < steps; ++i) {
    stepper->step(forces, frozen, st, set.integrator.dt, all);
    e.push_back(forces.spring_energy(st) + forces.kinetic_energy(st, 0.0));
  }
  return e;
}

TEST(ThetaKey, HalfConservesAndOneDissipatesTheEnergyOfAFrictionlessChain) {
  const int steps = 2000;
  const auto half = energies("0.5", steps);
  for (double e : half) EXPECT_NEAR(e, half[0], 1e-11 * half[0]);
  for (const char* theta : {"0.75", "1"}) {
    const auto e = energies(theta, steps);
    for (int i = 1; i <= steps; ++i)
      ASSERT_LE(e[i], e[i - 1] * (1 + 1e-14)) << theta << " step " << i;
    EXPECT_LT(e.back(), 0.5 * e[0]) << theta;
  }
  EXPECT_LT(energies("1", steps).back(), energies("0.75", steps).back());
}

TEST(ThetaKey, ScalesTheWeakeningLimitAndIsRefusedOutsideItsRange) {
  ModelParams p;
  p.law = law_id<law::Thesis>;
  p.F0 = 1;
  p.v_c = 1;
  Theta t(1);
  const double half = t.time_step_limit(p).dt;
  t.set_theta(1.0);
  EXPECT_NEAR(t.time_step_limit(p).dt, 0.5 * half, 1e-12);
  EXPECT_EQ(t.order(), 1);
  Scene s;
  s.set("integrator.scheme", "theta");
  EXPECT_THROW(s.set("integrator.theta", "0.4"), Error);
  EXPECT_THROW(s.set("integrator.theta", "1.1"), Error);
  Scene rk4;
  rk4.set("integrator.theta", "0.7");
  EXPECT_THROW(rk4.validate(), Error);  // applies only with integrator.scheme = theta
}

}  // namespace
}  // namespace bkq
