// Event-driven engine throughput on the carlson-langer scene (l = 10, alpha = 2.5,
// sigma = 0.01, clst91, RK4 at dt = 0.01) at N = 100, 1000 and 10^4: events per second,
// block-steps and sliding-block-steps per second, and nanoseconds per sliding-block-step
// (the engine's work should scale with the event, not the chain). BM_Straightforward
// runs the straightforward engine (tests/support/reference_events.hpp: every block, every step)
// from the same state, so that the speed-up is a ratio measured in one run: issue 3's
// goals are 10x such an engine at N = 100 (3.5e5 against 3.5e4 events/s) and 30x at
// N = 1000 (1.3e5 against 4.4e3). The bk_located and bkp_located rows run the same scene
// with integrator.transitions = located at the same dt, beside the step rows, so that both
// modes' speed-ups over BM_Straightforward (at the step, dt = 0.01) come from one run.
#include <benchmark/benchmark.h>

#include "carlson_langer_events.hpp"
#include "support/reference_events.hpp"

namespace {

void BM_Events(benchmark::State& state, const char* kind, bool replay_starts,
               bool located = false) {
  bkq::bench::CarlsonLangerEvents setup(static_cast<int>(state.range(0)), kind, replay_starts,
                                        located);
  bkq::EventEngine& engine = setup.engine;
  const bkq::EngineCounters c0 = engine.counters();
  const bkq::EventEngine::LoneSlipStarts l0 = engine.lone_slip_starts();
  for (auto _ : state) benchmark::DoNotOptimize(engine.next_event());
  const bkq::EngineCounters& c = engine.counters();
  const double events = static_cast<double>(c.events - c0.events);
  const double sliding = static_cast<double>(c.sliding_block_steps - c0.sliding_block_steps);
  state.counters["events"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
  state.counters["block_steps"] = benchmark::Counter(
      static_cast<double>(c.block_steps - c0.block_steps), benchmark::Counter::kIsRate);
  state.counters["sliding_block_steps"] = benchmark::Counter(sliding, benchmark::Counter::kIsRate);
  state.counters["ns_per_sliding_block_step"] =
      benchmark::Counter(sliding * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["sliding_share"] = sliding / static_cast<double>(c.block_steps - c0.block_steps);
  // Of the steps, those taken from the lone slip's record rather than integrated.
  state.counters["replayed_step_share"] =
      static_cast<double>(engine.lone_slip_starts().steps - l0.steps) /
      static_cast<double>(c.steps - c0.steps);
  state.counters["declined_starts"] =
      static_cast<double>(engine.lone_slip_starts().declined - l0.declined);
}

// The straightforward engine from the state the event engine reached past its transient.
void BM_Straightforward(benchmark::State& state) {
  bkq::bench::CarlsonLangerEvents setup(static_cast<int>(state.range(0)));
  bkq::ReferenceEventEngine reference(setup.forces, *setup.stepper, setup.kDt,
                                      setup.engine.state());
  std::int64_t events = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(reference.next_event());
    ++events;
  }
  const double sliding = static_cast<double>(reference.sliding_block_steps);
  state.counters["events"] =
      benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
  state.counters["block_steps"] =
      benchmark::Counter(static_cast<double>(reference.block_steps), benchmark::Counter::kIsRate);
  state.counters["sliding_block_steps"] = benchmark::Counter(sliding, benchmark::Counter::kIsRate);
  state.counters["sliding_share"] = sliding / static_cast<double>(reference.block_steps);
}

BENCHMARK_CAPTURE(BM_Events, bk, "bk", true)->Arg(100)->Arg(1000)->Arg(10000)->MinTime(1.0);
// Every step integrated, event starts included (EventEngine::lone_slip_path off).
BENCHMARK_CAPTURE(BM_Events, bk_direct, "bk", false)->Arg(100)->Arg(1000)->Arg(10000)->MinTime(1.0);
BENCHMARK_CAPTURE(BM_Events, bkp, "bkp", true)->Arg(100)->Arg(1000)->MinTime(1.0);
// Transitions located inside the step (integrator.transitions = located), the same dt.
BENCHMARK_CAPTURE(BM_Events, bk_located, "bk", true, true)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_Events, bkp_located, "bkp", true, true)->Arg(100)->Arg(1000)->MinTime(1.0);
BENCHMARK(BM_Straightforward)->Arg(100)->Arg(1000)->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
