// Block-steps per second of each stepper on a 1000-block continuous run (issue: the
// foundation's benchmark). Thesis Table 3.1 chain (BK–Pad, thesis friction) driven at
// v = 0.1, where a good fraction of blocks slide at any time. Google Benchmark reports
// `block_steps` as a rate (block-steps/s).
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

void BM_Continuous(benchmark::State& state, const char* scheme) {
  const int n = static_cast<int>(state.range(0));
  const bkq::ModelParams p = thesis_chain(n);
  const bkq::ChainForces forces(p);
  auto stepper = bkq::make_stepper(scheme, n);
  bkq::ContinuousDriver driver(forces, *stepper, bkq::Substrate::constant(0.1),
                               bkq::initial_state(forces, 1, 0.75, false), 0.005);
  for (int i = 0; i < 2000; ++i) driver.step();  // past the start-up transient
  std::int64_t steps = 0;
  for (auto _ : state) {
    driver.step();
    ++steps;
  }
  state.counters["block_steps"] =
      benchmark::Counter(static_cast<double>(steps) * n, benchmark::Counter::kIsRate);
  state.counters["sliding_fraction"] = static_cast<double>(driver.sliding()) / n;
}

BENCHMARK_CAPTURE(BM_Continuous, rk2, "rk2")->Arg(1000);
BENCHMARK_CAPTURE(BM_Continuous, rk4, "rk4")->Arg(1000);
BENCHMARK_CAPTURE(BM_Continuous, verlet, "verlet")->Arg(1000);

}  // namespace

BENCHMARK_MAIN();
