// Events per second with coupling beyond nearest neighbours: the carlson-langer scene (l = 10,
// alpha = 2.5, sigma = 0.01, clst91, rk4 at dt = 0.01) at N blocks with model.coupling =
// nearest, range R for each R asked for, and the power kernel (p = 3) at the largest R. For
// each, after a transient of T events, the event engine (which integrates only the blocks
// within R of a sliding block) and the straightforward engine (tests/support/reference_events.hpp:
// every block of the chain stepped through every event, the loader scanning every block)
// each run the same F events from the same state, and then the event engine E more; all
// timed in this thread's CPU time. One row per coupling: the engine's events per CPU second
// over the E events and their mean size, both engines' rates over the F events and the
// ratio of those (the speed-up on the same events).
//
//   build/bench_coupling [--blocks N] [--events E] [--full-events F] [--transient T] [R ...]
//                  (defaults: N = 1000, E = 20000, F = 200, T = 20000, R = 1 3 10 30)

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "support/reference_events.hpp"
#include "thread_clock.hpp"

namespace {

struct Row {
  std::string coupling;
  int range;
};

}  // namespace

int main(int argc, char** argv) {
  int n = 1000;
  long long events = 20000, full_events = 200, transient = 20000;
  std::vector<int> ranges;
  for (int i = 1; i < argc; ++i) {
    auto value = [&] { return i + 1 < argc ? std::atoll(argv[++i]) : 0LL; };
    if (std::strcmp(argv[i], "--blocks") == 0)
      n = static_cast<int>(value());
    else if (std::strcmp(argv[i], "--events") == 0)
      events = value();
    else if (std::strcmp(argv[i], "--full-events") == 0)
      full_events = value();
    else if (std::strcmp(argv[i], "--transient") == 0)
      transient = value();
    else
      ranges.push_back(std::atoi(argv[i]));
  }
  if (ranges.empty()) ranges = {1, 3, 10, 30};
  std::vector<Row> rows = {{"nearest", 1}};
  int largest = 1;
  for (int r : ranges) {
    if (r > 1) rows.push_back({"range", r});
    largest = std::max(largest, r);
  }
  rows.push_back({"power", largest});

  std::printf(
      "coupling,range,blocks,events,engine_events_per_cpu_second,mean_blocks_per_event,"
      "same_events,engine_events_per_cpu_second_same,full_chain_events_per_cpu_second_same,"
      "ratio\n");
  try {
    for (const Row& row : rows) {
      bkq::Scene scene;
      scene.set("model.blocks", std::to_string(n));
      scene.set("model.coupling", row.coupling);
      if (row.coupling != "nearest") scene.set("model.range", std::to_string(row.range));
      scene.validate();
      const bkq::ModelParams p = bkq::model_from_scene(scene);
      const bkq::ChainForces forces(p);
      const double dt = scene.real("integrator.dt");
      auto stepper = bkq::make_stepper(scene.choice("integrator.scheme"), n);
      bkq::check_time_step(*stepper, p, dt);
      bkq::EventEngine engine(forces, *stepper, dt, bkq::initial_state(forces, 7, 0.01, true));
      for (long long i = 0; i < transient; ++i) engine.next_event();
      const bkq::ChainState start = engine.state();

      // The same F events both ways (the engine gives the whole chain's events bit for bit
      // with the lone-slip replay off, on here as in a run: the same events to rounding).
      double t0 = bkq::bench::thread_seconds();
      for (long long i = 0; i < full_events; ++i) engine.next_event();
      const double engine_same =
          static_cast<double>(full_events) / (bkq::bench::thread_seconds() - t0);
      auto full_stepper = bkq::make_stepper(scene.choice("integrator.scheme"), n);
      bkq::ReferenceEventEngine full(forces, *full_stepper, dt, start);
      double full_blocks = 0;
      t0 = bkq::bench::thread_seconds();
      for (long long i = 0; i < full_events; ++i) full_blocks += full.next_event().blocks;
      const double full_rate =
          static_cast<double>(full_events) / (bkq::bench::thread_seconds() - t0);
      // Then E more events: the engine's steady rate.
      double blocks = 0;
      t0 = bkq::bench::thread_seconds();
      for (long long i = 0; i < events; ++i) blocks += engine.next_event().blocks;
      const double engine_rate = static_cast<double>(events) / (bkq::bench::thread_seconds() - t0);
      std::printf("%s,%d,%d,%lld,%.6g,%.4g,%lld,%.6g,%.6g,%.4g\n", row.coupling.c_str(), row.range,
                  n, events, engine_rate, blocks / static_cast<double>(events), full_events,
                  engine_same, full_rate, engine_same / full_rate);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_coupling: %s\n", e.what());
    return 2;
  }
  return 0;
}
