// BKP against BK events per second, side by side in one process (issue 20, goal 3: BKP
// >= 0.7x BK at N = 100 and 1000). The carlson-langer scene (bench/carlson_langer_events.hpp)
// with model.kind = bk and bkp, each engine past its transient, and a third engine, bkp
// with the cluster and held-range paths off (every step on the general path, as before
// the pad had fast paths; the same events bit for bit); then ROUNDS rounds in which each
// engine runs for about SLICE seconds of this thread's CPU time, in turn, so that the
// machine's load falls on all alike. Prints, per N, the rates (events per CPU-second over
// all rounds), the medians of the per-round ratios BKP/BK with their ranges, and the
// sliding block-steps per event of each model (how much work an event of each is). Each
// N is measured with the transitions at the step and located inside it
// (integrator.transitions = step, located; rk4 at dt = 0.01 both), a row per mode.
//   build/bkp_ratio [ROUNDS=7] [SLICE=0.3] [N...=100 1000]

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "carlson_langer_events.hpp"
#include "thread_clock.hpp"

namespace {

struct Tally {
  std::int64_t events = 0, sliding_block_steps = 0;
  double seconds = 0;
};

// Runs events in batches until `slice` CPU seconds have passed; returns events per second.
double run_slice(bkq::EventEngine& engine, double slice, Tally& tally) {
  const std::int64_t sliding0 = engine.counters().sliding_block_steps;
  const double t0 = bkq::bench::thread_seconds();
  std::int64_t events = 0;
  double t = t0;
  while (t - t0 < slice) {
    for (int i = 0; i < 256; ++i) engine.next_event();
    events += 256;
    t = bkq::bench::thread_seconds();
  }
  tally.events += events;
  tally.seconds += t - t0;
  tally.sliding_block_steps += engine.counters().sliding_block_steps - sliding0;
  return static_cast<double>(events) / (t - t0);
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 7;
  const double slice = argc > 2 ? std::atof(argv[2]) : 0.3;
  std::vector<int> sizes;
  for (int i = 3; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {100, 1000};
  if (rounds < 1 || !(slice > 0) ||
      std::any_of(sizes.begin(), sizes.end(), [](int n) { return n < 2; })) {
    std::fprintf(stderr, "usage: bkp_ratio [ROUNDS >= 1] [SLICE > 0 seconds] [N >= 2 ...]\n");
    return 2;
  }
  std::printf(
      "| N | transitions | BK events/s | BKP events/s | BKP/BK (median of %d, min-max) | BKP "
      "general path only / BK | sliding block-steps per event BK, BKP |\n"
      "|---|---|---|---|---|---|---|\n",
      rounds);
  for (int n : sizes) {
    for (const bool located : {false, true}) {
      bkq::bench::CarlsonLangerEvents bk(n, "bk", true, located), bkp(n, "bkp", true, located),
          general(n, "bkp", true, located);
      general.engine.cluster_path = false;
      general.engine.held_ranges_path = false;
      std::vector<double> ratios, before;
      Tally tb, tp, tg;
      for (int r = 0; r < rounds; ++r) {
        const double a = run_slice(bk.engine, slice, tb);
        const double b = run_slice(bkp.engine, slice, tp);
        const double g = run_slice(general.engine, slice, tg);
        ratios.push_back(b / a);
        before.push_back(g / a);
      }
      std::sort(ratios.begin(), ratios.end());
      std::sort(before.begin(), before.end());
      std::printf("| %d | %s | %.3g | %.3g | %.3f (%.3f-%.3f) | %.3f (%.3f-%.3f) | %.0f, %.0f |\n",
                  n, located ? "located" : "step", static_cast<double>(tb.events) / tb.seconds,
                  static_cast<double>(tp.events) / tp.seconds, ratios[ratios.size() / 2],
                  ratios.front(), ratios.back(), before[before.size() / 2], before.front(),
                  before.back(),
                  static_cast<double>(tb.sliding_block_steps) / static_cast<double>(tb.events),
                  static_cast<double>(tp.sliding_block_steps) / static_cast<double>(tp.events));
      std::fflush(stdout);
    }
  }
  return 0;
}
