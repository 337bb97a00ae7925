// Block-steps per second of each stepper on a 1000-block continuous run. Thesis Table 3.1
// chain (BK–Pad, thesis friction) driven at v = 0.1, where a good fraction of blocks slide
// at any time. Every iteration runs the same window of steps from the same state (taken
// after the start-up transient), so two builds, or two schemes, time the same work
// whatever the number of iterations. Google Benchmark reports `block_steps` as a rate
// (block-steps per CPU second) and `sliding_fraction` as the window's mean.
//
// Compare with another revision by building this file there and alternating the two
// programs: bench/compare_steppers.sh.
#include <benchmark/benchmark.h>

#include "engine/continuous.hpp"
#include "engine/initial_state.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"

namespace {

bkq::ModelParams thesis_chain(int n) {
  bkq::Scene scene;
  scene.set("model.parameterisation", "thesis");
  scene.set("model.kind", "bkp");
  scene.set("friction.law", "thesis");
  scene.set("model.blocks", std::to_string(n));
  scene.validate();
  return bkq::model_from_scene(scene);
}

constexpr int kTransient = 20000;  // steps before the timed window
constexpr int kWindow = 400;       // steps per iteration

void BM_Continuous(benchmark::State& state, const char* scheme) {
  const int n = static_cast<int>(state.range(0));
  const double dt = 0.005;
  const bkq::ModelParams p = thesis_chain(n);
  const bkq::ChainForces forces(p);
  const bkq::Substrate substrate = bkq::Substrate::constant(0.1);
  auto stepper = bkq::make_stepper(scheme, n);
  bkq::ContinuousSnapshot start;
  {
    bkq::ContinuousDriver driver(forces, *stepper, substrate,
                                 bkq::initial_state(forces, 1, 0.75, false), dt);
    for (int i = 0; i < kTransient; ++i) driver.step();
    start = driver.snapshot();
  }
  std::int64_t steps = 0;
  double sliding = 0;
  for (auto _ : state) {
    bkq::ContinuousDriver driver(forces, *stepper, substrate, start, dt);
    for (int i = 0; i < kWindow; ++i) {
      driver.step();
      sliding += driver.sliding();
    }
    steps += kWindow;
  }
  state.counters["block_steps"] =
      benchmark::Counter(static_cast<double>(steps) * n, benchmark::Counter::kIsRate);
  state.counters["sliding_fraction"] = sliding / (static_cast<double>(steps) * n);
}

BENCHMARK_CAPTURE(BM_Continuous, rk2, "rk2")->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Continuous, rk4, "rk4")->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Continuous, verlet, "verlet")
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
