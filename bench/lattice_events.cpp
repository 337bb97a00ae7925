// Events per second on the BK lattice (model.rows > 1, Carlson 1991): the event engine, which
// steps only the sliding sites and their stencil partners and loads from a force tree, beside
// the straightforward engine (tests/support/reference_events.hpp: every site stepped through every
// event, every site scanned to load), on the carlson-langer scene (l = l_y = 10, alpha = 2.5,
// sigma = 0.01, clst91, rk4 at dt = 0.01) on L x L sites, free edges.
//
// For each size the event engine is run past its transient (T events per site) from the seeded
// state; from the state S it reached, R rounds, each running the same F events from S with the
// event engine (the lone-slip replay on, as in a run), the event engine with the replay off
// (EventEngine::lone_slip_path, every step integrated) and the straightforward engine, one after
// the other, each timed in this thread's CPU time. The event engines' F events take
// milliseconds, so each repeats them from S until it has run for 0.2 s. One row per round and
// engine: events per CPU second, the ratio to the straightforward engine in the same round,
// blocks advanced per event (sites stepped, summed over the steps), sliding block-steps per
// event (equal for all three: the same events), the shares of events started and finished
// (lone slips) from the replay, and the number of events whose trigger or size differ from
// the straightforward engine's (0: the same events). A last row per size: the event engine
// alone over S more events from S (round "steady"), the rate a long run sees. After each
// round a comment line on stderr gives the event engine's CPU nanoseconds per sliding
// site-step (replay on and off) beside the chain's (the same scene on a chain of L x L
// blocks, its events timed the same way from the state after its transient).
//
//   build/lattice_events [--events F] [--rounds R] [--transient T] [--steady S] [L ...]
//                        (defaults: F = 200, R = 3, T = 10, S = 100000, L = 64 256)

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

// What one engine did over the F events of a round.
struct Pass {
  double seconds = 0;  // CPU time per pass over the F events
  double block_steps = 0, sliding_block_steps = 0, replayed = 0, finished = 0;
  std::vector<bkq::EventRecord> events;
};

// The F events from `start` by the event engine, repeated until it has run for min_seconds.
Pass event_engine_pass(const bkq::ChainForces& forces, const std::string& scheme, double dt,
                       const bkq::EngineSnapshot& start, long long f, bool replay,
                       double min_seconds) {
  Pass out;
  double total = 0;
  int passes = 0;
  while (total < min_seconds || passes == 0) {
    auto stepper = bkq::make_stepper(scheme, forces.n());
    bkq::EventEngine engine(forces, *stepper, dt, start);
    engine.lone_slip_path = replay;
    const bkq::EngineCounters c0 = engine.counters();
    const bool record = passes == 0;
    const double t0 = bkq::bench::thread_seconds();
    for (long long i = 0; i < f; ++i) {
      const bkq::EventRecord e = engine.next_event();
      if (record) out.events.push_back(e);
    }
    total += bkq::bench::thread_seconds() - t0;
    if (record) {
      const bkq::EngineCounters& c = engine.counters();
      out.block_steps = static_cast<double>(c.block_steps - c0.block_steps);
      out.sliding_block_steps = static_cast<double>(c.sliding_block_steps - c0.sliding_block_steps);
      out.replayed = static_cast<double>(engine.lone_slip_starts().replayed);
      out.finished = static_cast<double>(engine.lone_slip_starts().finished);
    }
    ++passes;
  }
  out.seconds = total / passes;
  return out;
}

Pass reference_pass(const bkq::ChainForces& forces, const std::string& scheme, double dt,
                    const bkq::ChainState& start, long long f) {
  Pass out;
  auto stepper = bkq::make_stepper(scheme, forces.n());
  bkq::ReferenceEventEngine engine(forces, *stepper, dt, start);
  const double t0 = bkq::bench::thread_seconds();
  for (long long i = 0; i < f; ++i) out.events.push_back(engine.next_event());
  out.seconds = bkq::bench::thread_seconds() - t0;
  out.block_steps = static_cast<double>(engine.block_steps);
  out.sliding_block_steps = static_cast<double>(engine.sliding_block_steps);
  return out;
}

int differing(const std::vector<bkq::EventRecord>& a, const std::vector<bkq::EventRecord>& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    n += a[i].trigger != b[i].trigger || a[i].blocks != b[i].blocks;
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  long long f = 200, transient_per_site = 10, steady = 100000;
  int rounds = 3;
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) {
    auto value = [&] { return i + 1 < argc ? std::atoll(argv[++i]) : 0LL; };
    if (std::strcmp(argv[i], "--events") == 0)
      f = value();
    else if (std::strcmp(argv[i], "--rounds") == 0)
      rounds = static_cast<int>(value());
    else if (std::strcmp(argv[i], "--transient") == 0)
      transient_per_site = value();
    else if (std::strcmp(argv[i], "--steady") == 0)
      steady = value();
    else
      sizes.push_back(std::atoi(argv[i]));
  }
  if (sizes.empty()) sizes = {64, 256};
  for (int l : sizes)
    if (l < 2 || f < 1 || rounds < 1 || transient_per_site < 0 || steady < 0) {
      std::fprintf(stderr,
                   "usage: lattice_events [--events F >= 1] [--rounds R >= 1] [--transient T >= "
                   "0] [--steady S >= 0] [L >= 2 ...]\n");
      return 2;
    }

  std::printf(
      "lattice,round,engine,events,events_per_cpu_second,ratio,blocks_per_event,"
      "sliding_block_steps_per_event,mean_event_blocks,replayed_share,finished_share,"
      "differing_events\n");
  try {
    for (int l : sizes) {
      bkq::Scene scene;
      scene.set("model.blocks", std::to_string(l));
      scene.set("model.rows", std::to_string(l));
      scene.validate();
      const bkq::ModelParams p = bkq::model_from_scene(scene);
      const bkq::ChainForces forces(p);
      const double dt = scene.real("integrator.dt");
      const std::string scheme = scene.choice("integrator.scheme");
      auto stepper = bkq::make_stepper(scheme, p.n);
      bkq::check_time_step(*stepper, p, dt);
      bkq::EventEngine warm(forces, *stepper, dt, bkq::initial_state(forces, 7, 0.01, true));
      for (long long i = 0; i < transient_per_site * p.n; ++i) warm.next_event();
      const bkq::EngineSnapshot start = warm.snapshot();
      // The same scene on a chain of as many blocks, for its cost per sliding block-step.
      bkq::Scene chain_scene;
      chain_scene.set("model.blocks", std::to_string(p.n));
      chain_scene.validate();
      const bkq::ChainForces chain_forces(bkq::model_from_scene(chain_scene));
      bkq::EventEngine chain_warm(chain_forces, *stepper, dt,
                                  bkq::initial_state(chain_forces, 7, 0.01, true));
      for (long long i = 0; i < transient_per_site * p.n; ++i) chain_warm.next_event();
      const bkq::EngineSnapshot chain_start = chain_warm.snapshot();

      for (int round = 1; round <= rounds; ++round) {
        const Pass fast = event_engine_pass(forces, scheme, dt, start, f, true, 0.2);
        const Pass direct = event_engine_pass(forces, scheme, dt, start, f, false, 0.2);
        const Pass full = reference_pass(forces, scheme, dt, start.state, f);
        double blocks = 0;
        for (const bkq::EventRecord& e : full.events) blocks += e.blocks;
        const double ff = static_cast<double>(f);
        auto row = [&](const char* name, const Pass& pass) {
          std::printf("%dx%d,%d,%s,%lld,%.6g,%.4g,%.6g,%.6g,%.4g,%.4g,%.4g,%d\n", l, l, round, name,
                      f, ff / pass.seconds, full.seconds / pass.seconds, pass.block_steps / ff,
                      pass.sliding_block_steps / ff, blocks / ff, pass.replayed / ff,
                      pass.finished / ff, differing(pass.events, full.events));
        };
        row("event", fast);
        row("event_replay_off", direct);
        row("straightforward", full);
        std::fflush(stdout);
        const Pass chain = event_engine_pass(chain_forces, scheme, dt, chain_start, f, true, 0.2);
        const Pass chain_direct =
            event_engine_pass(chain_forces, scheme, dt, chain_start, f, false, 0.2);
        auto ns = [](const Pass& pass) { return 1e9 * pass.seconds / pass.sliding_block_steps; };
        std::fprintf(stderr,
                     "# %dx%d round %d: ns per sliding site-step: lattice %.3g (replay off %.3g), "
                     "chain of %d blocks %.3g (replay off %.3g)\n",
                     l, l, round, ns(fast), ns(direct), p.n, ns(chain), ns(chain_direct));
      }
      if (steady > 0) {
        bkq::EventEngine engine(forces, *stepper, dt, start);
        const bkq::EngineCounters c0 = engine.counters();
        double blocks = 0;
        const double t0 = bkq::bench::thread_seconds();
        for (long long i = 0; i < steady; ++i) blocks += engine.next_event().blocks;
        const double seconds = bkq::bench::thread_seconds() - t0;
        const bkq::EngineCounters& c = engine.counters();
        const double s = static_cast<double>(steady);
        std::printf("%dx%d,steady,event,%lld,%.6g,,%.6g,%.6g,%.4g,%.4g,%.4g,\n", l, l, steady,
                    s / seconds, static_cast<double>(c.block_steps - c0.block_steps) / s,
                    static_cast<double>(c.sliding_block_steps - c0.sliding_block_steps) / s,
                    blocks / s, static_cast<double>(engine.lone_slip_starts().replayed) / s,
                    static_cast<double>(engine.lone_slip_starts().finished) / s);
        std::fflush(stdout);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lattice_events: %s\n", e.what());
    return 2;
  }
  return 0;
}
