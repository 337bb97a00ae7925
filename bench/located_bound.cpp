// A lower bound on the cost of located transitions, measured against a scene's own point.
//
// A located run at step dt takes at least the steps of a step-mode run at the same dt (the
// same scheme, the same events), and each cut (a transition located inside a step) takes at
// least one scheme step more over the blocks of the step's ranges (the whole-range cut,
// integrate/located.hpp): the step to the instant and the rest of the step, where step mode
// takes one. So, whatever the bracketing, the polish and the fast paths cost,
//   located(dt) >= step(dt) + sum over cuts of (one bare scheme step over the blocks cut),
// the bare step timed on its own for each event-size class's mean cut. Three engines run on the
// scene, alternating within each round: the scene's own point (its scheme and dt, transitions at
// the step), SCHEME at DT at the step, and SCHEME at DT located. Each is timed twice per round: a
// whole pass (the µs per event of the totals, thread CPU time) and a pass timed event by event
// (wall clock less its own reading's cost: the split by event size, and the cuts and their blocks
// per class).
//   build/located_bound [EVENTS=50000] [ROUNDS=2] [DT=0.04] [SCHEME=rk4] [SCENE]
// SCENE: an INI file (keys of continuous runs are dropped; the run is event by event), or the
// built-in carlson-langer scene. Prints the ratios to the scene's own point per round, and the
// split by event size of the last round. Without a moving pad it also prints the bound that
// cuts of the sliding stretch alone would have (stretch_blocks of tests/support/located_cuts.hpp:
// a stuck block decouples its two sides for the step), which would need more than this
// stepper does.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "integrate/located.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"
#include "support/located_cuts.hpp"
#include "thread_clock.hpp"

namespace {

using namespace bkq;

// Event-size classes: blocks in [kEdges[c], kEdges[c + 1]).
constexpr std::array<int, 6> kEdges = {1, 2, 4, 10, 30, 1 << 30};
constexpr int kClasses = static_cast<int>(kEdges.size()) - 1;

int size_class(int blocks) {
  int c = 0;
  while (c + 1 < kClasses && blocks >= kEdges[c + 1]) ++c;
  return c;
}

struct ClassTally {
  double events = 0, seconds = 0, block_steps = 0, cuts = 0, cut_blocks = 0, stretch_blocks = 0;
};

struct Config {
  std::string label;
  std::unique_ptr<Stepper> stepper;
  std::unique_ptr<EventEngine> engine;
  double us_per_event = 0;
  std::array<ClassTally, kClasses> split{};
};

// The whole pass: µs per event over `events` events.
double timed_pass(EventEngine& engine, long events) {
  const double t0 = bkq::bench::thread_seconds();
  for (long i = 0; i < events; ++i) engine.next_event();
  return 1e6 * (bkq::bench::thread_seconds() - t0) / static_cast<double>(events);
}

// Wall seconds from the steady clock (read in user space: the thread CPU clock costs a
// system call, too much beside a sub-microsecond event).
double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// What one reading of the clock pair costs, taken off every event's time below.
double clock_overhead() {
  constexpr int kReads = 100000;
  double sink = 0;
  const double t0 = wall_seconds();
  for (int i = 0; i < kReads; ++i) sink += wall_seconds();
  const double each = (wall_seconds() - t0) / kReads;
  return sink > 0 ? each : 0.0;
}

// The pass timed event by event (wall clock, less its own cost), split by event size.
void split_pass(Config& c, long events, double overhead) {
  auto* located = dynamic_cast<LocatedTransitions*>(c.stepper.get());
  LocatedCutCounts counts;
  if (located) located->watch_cuts(&counts);
  c.split = {};
  for (long i = 0; i < events; ++i) {
    const auto block_steps0 = c.engine->counters().block_steps;
    const auto cuts0 = counts.cuts;
    const auto cut_blocks0 = counts.cut_blocks;
    const auto stretch_blocks0 = counts.stretch_blocks;
    const double t0 = wall_seconds();
    const EventRecord e = c.engine->next_event();
    const double seconds = std::max(0.0, wall_seconds() - t0 - overhead);
    ClassTally& t = c.split[size_class(e.blocks)];
    t.events += 1;
    t.seconds += seconds;
    t.block_steps += static_cast<double>(c.engine->counters().block_steps - block_steps0);
    if (located) {
      t.cuts += static_cast<double>(counts.cuts - cuts0);
      t.cut_blocks += static_cast<double>(counts.cut_blocks - cut_blocks0);
      t.stretch_blocks += static_cast<double>(counts.stretch_blocks - stretch_blocks0);
    }
  }
  if (located) located->watch_cuts(nullptr);
}

// µs per bare step of `stepper` over `blocks` sliding blocks of the engine's chain (a range
// from the middle, every block in it sliding; the pad moves with them where it moves),
// timed over a batch of steps from a state put back every 32 steps.
double step_us(Stepper& stepper, const ChainForces& forces, const EventEngine& engine, double dt,
               int blocks) {
  const int n = forces.n();
  ChainState start = engine.state();
  const Range range{std::max(0, (n - blocks) / 2), std::max(0, (n - blocks) / 2) + blocks};
  for (int j = range.lo; j < range.hi; ++j) {
    start.mobile[j] = 1.0;
    start.dir[j] = 1.0;
    start.wd[j] = 0.01;
  }
  const Substrate frozen = Substrate::frozen(start.s);
  ChainState st = start;
  constexpr int kBatch = 32;
  long steps = 0;
  const double t0 = bkq::bench::thread_seconds();
  double elapsed = 0;
  while (elapsed < 0.02) {
    st = start;
    for (int i = 0; i < kBatch; ++i) stepper.step(forces, frozen, st, dt, Ranges(&range, 1));
    steps += kBatch;
    elapsed = bkq::bench::thread_seconds() - t0;
  }
  // The copies of the state, once per batch, are taken out with a batch of copies alone.
  const double c0 = bkq::bench::thread_seconds();
  for (long i = 0; i < steps / kBatch; ++i) {
    st = start;
    asm volatile("" : : "r"(st.w.data()) : "memory");
  }
  const double copies = bkq::bench::thread_seconds() - c0;
  return 1e6 * std::max(0.0, elapsed - copies) / static_cast<double>(steps);
}

}  // namespace

int main(int argc, char** argv) {
  const long events = argc > 1 ? std::atol(argv[1]) : 50000;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 2;
  const double dt = argc > 3 ? std::atof(argv[3]) : 0.04;
  const std::string scheme = argc > 4 ? argv[4] : "rk4";
  if (events < 1 || rounds < 1 || !(dt > 0)) {
    std::fprintf(stderr,
                 "usage: located_bound [EVENTS=50000] [ROUNDS=2] [DT=0.04] [SCHEME=rk4] [SCENE]\n");
    return 2;
  }
  try {
    Scene scene = argc > 5 ? Scene::from_file(argv[5]) : Scene();
    scene.set("drive.mode", "events", "located_bound");
    scene.drop_inapplicable();
    scene.validate();
    const Settings settings = settings_from_scene(scene);
    const ModelParams p = model_from_scene(scene);
    const ChainForces forces(p);
    const ChainState start =
        initial_state(forces, settings.run.seed, settings.run.initial_disorder, true);

    char dt_text[32];
    std::snprintf(dt_text, sizeof dt_text, "%g", dt);
    std::array<Config, 3> configs;
    configs[0].label = settings.integrator.scheme + " step, dt " + scene.text("integrator.dt");
    configs[0].stepper = make_stepper(settings.integrator.scheme, p.n);
    configs[1].label = scheme + " step, dt " + dt_text;
    configs[1].stepper = make_stepper(scheme, p.n);
    configs[2].label = scheme + " located, dt " + dt_text;
    configs[2].stepper = with_located_transitions(make_stepper(scheme, p.n), p.n);
    const double dts[3] = {settings.integrator.dt, dt, dt};
    for (int i = 0; i < 3; ++i) {
      check_time_step(*configs[i].stepper, p, dts[i]);
      configs[i].engine = std::make_unique<EventEngine>(forces, *configs[i].stepper, dts[i], start);
      for (int k = 0; k < 2000; ++k) configs[i].engine->next_event();  // the transient
    }
    std::printf("scene: %s; %ld events per pass, thread CPU time\n", scene.origin.c_str(), events);
    std::printf("%5s %14s %14s %16s %14s %14s %14s %18s\n", "round", "own us/event",
                "step us/event", "located us/event", "cut us/event", "bound/own", "located/own",
                "stretch bound/own");
    // A pass of each, not counted: the first timed round ran slow without it.
    for (Config& c : configs) timed_pass(*c.engine, events);
    const double overhead = clock_overhead();
    for (int round = 1; round <= rounds; ++round) {
      for (Config& c : configs) c.us_per_event = timed_pass(*c.engine, events);
      for (Config& c : configs) split_pass(c, events, overhead);
      // Each class's cuts priced at what one bare scheme step of its mean cut costs per block
      // (the step alone: no engine bookkeeping, no location), and the same for the stretch.
      double cut_us = 0, stretch_us = 0;
      for (int k = 0; k < kClasses; ++k) {
        const ClassTally& loc = configs[2].split[k];
        if (loc.cuts == 0) continue;
        const auto blocks = [&](double sum) {
          return std::clamp(static_cast<int>(std::lround(sum / loc.cuts)), 1, p.n);
        };
        const int b_cut = blocks(loc.cut_blocks), b_stretch = blocks(loc.stretch_blocks);
        cut_us += loc.cut_blocks *
                  step_us(*configs[1].stepper, forces, *configs[2].engine, dt, b_cut) / b_cut;
        stretch_us += loc.stretch_blocks *
                      step_us(*configs[1].stepper, forces, *configs[2].engine, dt, b_stretch) /
                      b_stretch;
      }
      cut_us /= static_cast<double>(events);
      stretch_us /= static_cast<double>(events);
      const double own = configs[0].us_per_event;
      std::printf("%5d %14.3f %14.3f %16.3f %14.3f %14.3f %14.3f", round, own,
                  configs[1].us_per_event, configs[2].us_per_event, cut_us,
                  (configs[1].us_per_event + cut_us) / own, configs[2].us_per_event / own);
      // A moving pad couples every block: there the stretch alone could not be cut.
      if (p.pad_moves())
        std::printf(" %18s\n", "n/a (pad)");
      else
        std::printf(" %18.3f\n", (configs[1].us_per_event + stretch_us) / own);
    }
    std::printf(
        "\nsplit by event size (last round's timed pass; us per event of the class, its\n"
        "share of the run's time; located: cuts per event, blocks per cut):\n");
    std::printf("%-12s", "blocks");
    for (const Config& c : configs) std::printf(" | %-30s", c.label.c_str());
    std::printf(" | %-16s\n", "cuts, blocks/cut");
    for (int k = 0; k < kClasses; ++k) {
      char range[32];
      if (k + 1 < kClasses)
        std::snprintf(range, sizeof range, "%d-%d", kEdges[k], kEdges[k + 1] - 1);
      else
        std::snprintf(range, sizeof range, ">= %d", kEdges[k]);
      std::printf("%-12s", range);
      for (const Config& c : configs) {
        double total = 0;
        for (const ClassTally& t : c.split) total += t.seconds;
        const ClassTally& t = c.split[k];
        std::printf(" | share %5.3f %8.2f us %5.1f%%", t.events / static_cast<double>(events),
                    t.events > 0 ? 1e6 * t.seconds / t.events : 0.0,
                    total > 0 ? 100 * t.seconds / total : 0.0);
      }
      const ClassTally& loc = configs[2].split[k];
      std::printf(" | %6.1f %8.1f\n", loc.events > 0 ? loc.cuts / loc.events : 0.0,
                  loc.cuts > 0 ? loc.cut_blocks / loc.cuts : 0.0);
    }
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "located_bound: %s\n", e.what());
    return 2;
  }
}
