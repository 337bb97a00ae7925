// The analysis agrees with the simulation: a continuous run started at
// the sliding equilibrium plus a small perturbation along one mode (run.start =
// equilibrium, app/stability.hpp) grows or decays at Re lambda of that mode (within 5 %)
// and oscillates at its frequency (within 2 %), measured on the mode's coordinate before
// the nonlinearity matters; unstable and stable cases, without and with Rayleigh block
// damping. Also fit_growth on signals of known rate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/stability.hpp"
#include "engine/continuous.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "stats/stability.hpp"

namespace bkq {
namespace {

TEST(GrowthFit, RecoversRateAndFrequencyOfADampedCosine) {
  for (double s : {-0.05, 0.0, 0.3})
    for (double w : {0.7, 2.0}) {
      std::vector<double> t, y;
      for (int i = 0; i <= 40000; ++i) {
        t.push_back(i * 0.001);
        y.push_back(1e-6 * std::exp(s * t.back()) * std::cos(w * t.back() + 0.4));
      }
      const GrowthFit f = fit_growth(t, y);
      EXPECT_NEAR(f.growth, s, 1e-6) << s << " " << w;
      EXPECT_NEAR(f.frequency, w / (2 * M_PI), 1e-6) << s << " " << w;
    }
}

struct Measured {
  Eigenmode mode;
  GrowthFit fit;
  double max_rel_speed = 0;  // largest |u'_j| / v over the run
};

// Runs the scene from the equilibrium plus `family,index` and fits the modal coordinate.
Measured run_mode(const std::vector<std::pair<const char*, const char*>>& keys, double duration) {
  Scene scene;
  for (const auto& [k, v] : keys) scene.set(k, v);
  scene.set("drive.mode", "continuous");
  scene.set("run.start", "equilibrium");
  scene.validate();
  const Settings settings = settings_from_scene(scene);
  const ModelParams& p = settings.model;
  const double v = settings.drive.speed;
  const ChainForces forces(p);
  const auto stepper = stepper_of(settings.integrator, p.n);
  const SlidingEquilibrium eq = sliding_equilibrium(p, v);
  const auto [mode, shape] = find_mode(
      p, eq.friction.slope, ModeSelect{*settings.run.start.mode, settings.run.start.mode_index});
  ContinuousDriver driver(forces, *stepper, substrate_of(settings.drive),
                          equilibrium_start(forces, settings), settings.integrator.dt);
  // Coordinate along the (real) block shape, or the pad for the pad's modes.
  const bool pad = p.pad_moves() && mode.index == 0;
  std::vector<double> t, y;
  Measured out{mode, {}, 0};
  const auto steps = static_cast<long>(std::llround(duration / settings.integrator.dt));
  for (long i = 0; i <= steps; ++i) {
    const ChainState& st = driver.state();
    double c = 0;
    if (pad) {
      c = st.x - eq.x;
    } else {
      for (int j = 0; j < p.n; ++j) c += shape[j].real() * (driver.displacement(j) - eq.u[j]);
    }
    for (int j = 0; j < p.n; ++j)
      out.max_rel_speed = std::max(out.max_rel_speed, std::abs(st.wd[j] - v) / v);
    EXPECT_EQ(driver.sliding(), p.n) << "a block stuck at t = " << st.t;
    t.push_back(st.t);
    y.push_back(c);
    if (i < steps) driver.step();
  }
  out.fit = fit_growth(t, y);
  std::printf("%s:%d  growth %.6g (Re lambda %.6g)  frequency %.6g (%.6g)  max |u'|/v %.3g\n",
              to_string(mode.family), mode.index, out.fit.growth, mode.growth(), out.fit.frequency,
              mode.frequency(), out.max_rel_speed);
  return out;
}

TEST(AnalysisAgreesWithSimulation, UnstableChainModeGrowsAtReLambda) {
  const Measured m = run_mode({{"model.kind", "bkp"},
                               {"model.parameterisation", "thesis"},
                               {"friction.law", "thesis"},
                               {"model.blocks", "10"},
                               {"drive.speed", "0.1"},
                               {"run.start_mode", "chain"},
                               {"run.start_mode_index", "2"},
                               {"run.start_amplitude", "1e-8"},
                               {"integrator.scheme", "rk4"},
                               {"integrator.dt", "0.005"},
                               {"run.duration", "25"}},
                              25);
  ASSERT_TRUE(m.mode.unstable());
  EXPECT_LE(m.max_rel_speed, 1e-3);
  EXPECT_GE(m.fit.extrema, 4);
  EXPECT_NEAR(m.fit.growth, m.mode.growth(), 0.05 * m.mode.growth());
  EXPECT_NEAR(m.fit.frequency, m.mode.frequency(), 0.02 * m.mode.frequency());
}

TEST(AnalysisAgreesWithSimulation, StablePadModeDecaysAtReLambda) {
  const Measured m = run_mode({{"model.kind", "bkp"},
                               {"model.parameterisation", "thesis"},
                               {"friction.law", "thesis"},
                               {"model.blocks", "10"},
                               {"drive.speed", "0.3"},
                               {"run.start_mode", "pad"},
                               {"run.start_amplitude", "1e-4"},
                               {"integrator.scheme", "rk4"},
                               {"integrator.dt", "0.01"},
                               {"run.duration", "60"}},
                              60);
  ASSERT_FALSE(m.mode.unstable());
  EXPECT_LE(m.max_rel_speed, 1e-3);
  EXPECT_GE(m.fit.extrema, 10);
  EXPECT_NEAR(m.fit.growth, m.mode.growth(), 0.05 * std::abs(m.mode.growth()));
  EXPECT_NEAR(m.fit.frequency, m.mode.frequency(), 0.02 * m.mode.frequency());
}

// With Rayleigh block damping above the chain mode's threshold (alpha_M + beta_K k_q/m_u >
// -phi'(v)) the mode decays at its Re lambda; every scheme's damped force terms (the explicit
// kernels, theta's implicit rows, adaptive) give the same rate.
TEST(AnalysisAgreesWithSimulation, DampedChainModeDecaysAtReLambdaWithEveryScheme) {
  for (const char* scheme : {"rk4", "rk2", "verlet", "theta", "adaptive"}) {
    const Measured m = run_mode({{"model.kind", "bkp"},
                                 {"model.parameterisation", "thesis"},
                                 {"friction.law", "thesis"},
                                 {"model.blocks", "10"},
                                 {"drive.speed", "0.1"},
                                 {"model.rayleigh_alpha", "0.85"},
                                 {"model.rayleigh_beta", "0.05"},
                                 {"run.start_mode", "chain"},
                                 {"run.start_mode_index", "2"},
                                 {"run.start_amplitude", "1e-4"},
                                 {"integrator.scheme", scheme},
                                 {"integrator.dt", "0.01"},
                                 {"run.duration", "60"}},
                                60);
    ASSERT_FALSE(m.mode.unstable()) << scheme;
    EXPECT_LE(m.max_rel_speed, 1e-3) << scheme;
    EXPECT_GE(m.fit.extrema, 10) << scheme;
    EXPECT_NEAR(m.fit.growth, m.mode.growth(), 0.05 * std::abs(m.mode.growth())) << scheme;
    EXPECT_NEAR(m.fit.frequency, m.mode.frequency(), 0.02 * m.mode.frequency()) << scheme;
  }
}

// With the dashpots of model.viscosity (Myers & Langer 1993) composed with the Rayleigh
// damping, a chain mode decays at the analysis's rate (c_q gains eta mu_q / m_u), on a free
// chain and on a range-coupled ring.
TEST(AnalysisAgreesWithSimulation, ViscousChainModeDecaysAtReLambda) {
  for (const char* ring : {"free", "periodic"}) {
    // Damping rates near 0.15 on both, so that the mode stays above rounding over the run.
    const char* eta = std::string(ring) == "free" ? "4" : "1.5";
    std::vector<std::pair<const char*, const char*>> keys = {
        {"model.kind", "bkp"},           {"model.parameterisation", "thesis"},
        {"friction.law", "thesis"},      {"model.blocks", "12"},
        {"model.boundary", ring},        {"drive.speed", "0.1"},
        {"model.rayleigh_alpha", "0.6"}, {"model.viscosity", eta},
        {"run.start_mode", "chain"},     {"run.start_mode_index", "4"},
        {"run.start_amplitude", "1e-4"}, {"integrator.scheme", "rk4"},
        {"integrator.dt", "0.01"},       {"run.duration", "60"}};
    if (std::string(ring) == "periodic") {
      keys.push_back({"model.coupling", "range"});
      keys.push_back({"model.range", "2"});
    }
    const Measured m = run_mode(keys, 60);
    ASSERT_FALSE(m.mode.unstable()) << ring;
    EXPECT_GE(m.fit.extrema, 10) << ring;
    EXPECT_NEAR(m.fit.growth, m.mode.growth(), 0.05 * std::abs(m.mode.growth())) << ring;
    EXPECT_NEAR(m.fit.frequency, m.mode.frequency(), 0.02 * m.mode.frequency()) << ring;
  }
  // The dashpots are in the analysis: the mode's damping moved by eta mu_q / m_u.
  Scene s;
  s.set("model.blocks", "12");
  s.set("model.viscosity", "4");
  const ModelParams p = model_from_scene(s);
  ModelParams none = p;
  none.viscosity = 0;
  EXPECT_NEAR(chain_mode_damping(p, 4) - chain_mode_damping(none, 4),
              4.0 * laplacian_eigenvalue(p, 4) / p.m_u, 1e-12);
}

// A ring coupled to the blocks within R = 3 (model/coupling.hpp): the modal reduction's
// k_q = k_p + sum_r k_r 4 sin^2(pi q r/N) and the stencil's force kernel (with its Rayleigh
// term) give the same decay rate and frequency.
TEST(AnalysisAgreesWithSimulation, DampedChainModeOfARangeCoupledRing) {
  const Measured m = run_mode({{"model.kind", "bkp"},
                               {"model.parameterisation", "thesis"},
                               {"friction.law", "thesis"},
                               {"model.blocks", "12"},
                               {"model.boundary", "periodic"},
                               {"model.coupling", "range"},
                               {"model.range", "3"},
                               {"drive.speed", "0.1"},
                               {"model.rayleigh_alpha", "0.85"},
                               {"model.rayleigh_beta", "0.05"},
                               {"run.start_mode", "chain"},
                               {"run.start_mode_index", "2"},
                               {"run.start_amplitude", "1e-4"},
                               {"integrator.scheme", "rk4"},
                               {"integrator.dt", "0.01"},
                               {"run.duration", "60"}},
                              60);
  ASSERT_FALSE(m.mode.unstable());
  EXPECT_GE(m.fit.extrema, 10);
  EXPECT_NEAR(m.fit.growth, m.mode.growth(), 0.05 * std::abs(m.mode.growth()));
  EXPECT_NEAR(m.fit.frequency, m.mode.frequency(), 0.02 * m.mode.frequency());
  // The stencil moved the mode: mu_2 is 1 for the nearest-neighbour ring, 8/3 at R = 3.
  auto ring = [](bool range) {
    Scene s;
    s.set("model.blocks", "12");
    s.set("model.boundary", "periodic");
    if (range) {
      s.set("model.coupling", "range");
      s.set("model.range", "3");
    }
    return model_from_scene(s);
  };
  EXPECT_NEAR(laplacian_eigenvalue(ring(false), 2), 1.0, 1e-12);
  EXPECT_NEAR(laplacian_eigenvalue(ring(true), 2), 8.0 / 3.0, 1e-12);
}

// Below the threshold the damped chain mode still grows, at its (smaller) Re lambda; and
// the bkp chain:0 root, which moves the pad (the pad row of beta_K K), decays at its rate.
TEST(AnalysisAgreesWithSimulation, DampedModesBelowAndAboveThresholdAndThePadRow) {
  const Measured grows = run_mode({{"model.kind", "bkp"},
                                   {"model.parameterisation", "thesis"},
                                   {"friction.law", "thesis"},
                                   {"model.blocks", "10"},
                                   {"drive.speed", "0.1"},
                                   {"model.rayleigh_alpha", "0.3"},
                                   {"model.rayleigh_beta", "0.02"},
                                   {"run.start_mode", "chain"},
                                   {"run.start_mode_index", "2"},
                                   {"run.start_amplitude", "1e-8"},
                                   {"integrator.scheme", "rk4"},
                                   {"integrator.dt", "0.005"},
                                   {"run.duration", "30"}},
                                  30);
  ASSERT_TRUE(grows.mode.unstable());
  EXPECT_LE(grows.max_rel_speed, 1e-3);
  EXPECT_NEAR(grows.fit.growth, grows.mode.growth(), 0.05 * grows.mode.growth());
  EXPECT_NEAR(grows.fit.frequency, grows.mode.frequency(), 0.02 * grows.mode.frequency());

  const Measured pad_row = run_mode({{"model.kind", "bkp"},
                                     {"model.parameterisation", "thesis"},
                                     {"friction.law", "thesis"},
                                     {"model.blocks", "10"},
                                     {"drive.speed", "0.1"},
                                     {"model.rayleigh_alpha", "0.6"},
                                     {"model.rayleigh_beta", "0.1"},
                                     {"run.start_mode", "chain"},
                                     {"run.start_mode_index", "0"},
                                     {"run.start_amplitude", "1e-4"},
                                     {"integrator.scheme", "rk4"},
                                     {"integrator.dt", "0.01"},
                                     {"run.duration", "80"}},
                                    80);
  ASSERT_FALSE(pad_row.mode.unstable());
  EXPECT_LE(pad_row.max_rel_speed, 1e-3);
  EXPECT_GE(pad_row.fit.extrema, 10);
  EXPECT_NEAR(pad_row.fit.growth, pad_row.mode.growth(), 0.05 * std::abs(pad_row.mode.growth()));
  EXPECT_NEAR(pad_row.fit.frequency, pad_row.mode.frequency(), 0.02 * pad_row.mode.frequency());
}

}  // namespace
}  // namespace bkq
