// Scaling with the chain length (issue 20, goals 7 and 8): for each N, the event engine of
// the carlson-langer benchmark scene (bench/carlson_langer_events.hpp: rk4, dt = 0.01,
// twenty events per block of transient) runs E events, timed in this thread's CPU time (so
// the other processes of a loaded machine do not count). One row per N: events per
// second, ns per block-step and per sliding block-step, the mean work per event, the
// heap the model, stepper and engine hold per block after the transient (malloc's own
// count: what they allocated, whether or not the pages were touched), and the ratio of
// events per second to the first N's.
//
//   build/scaling [--events E] [N ...]        (default: E = 200000, N = 100 1000 10000 100000)
#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "carlson_langer_events.hpp"
#include "thread_clock.hpp"

namespace {

double heap_bytes() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd);
}

}  // namespace

int main(int argc, char** argv) {
  long long events = 200000;
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--events") == 0 && i + 1 < argc)
      events = std::atoll(argv[++i]);
    else
      sizes.push_back(std::atoi(argv[i]));
  }
  if (sizes.empty()) sizes = {100, 1000, 10000, 100000};
  std::printf(
      "blocks,events,events_per_cpu_second,ns_per_block_step,ns_per_sliding_block_step,"
      "block_steps_per_event,sliding_block_steps_per_event,heap_bytes_per_block,"
      "events_per_second_vs_first\n");
  double first = 0;
  for (const int n : sizes) {
    const double heap0 = heap_bytes();
    auto setup = std::make_unique<bkq::bench::CarlsonLangerEvents>(n);
    const double per_block = (heap_bytes() - heap0) / n;
    bkq::EventEngine& engine = setup->engine;
    const bkq::EngineCounters c0 = engine.counters();
    const double t0 = bkq::bench::thread_seconds();
    for (long long e = 0; e < events; ++e) engine.next_event();
    const double cpu = bkq::bench::thread_seconds() - t0;
    const bkq::EngineCounters& c = engine.counters();
    const double bs = static_cast<double>(c.block_steps - c0.block_steps);
    const double sbs = static_cast<double>(c.sliding_block_steps - c0.sliding_block_steps);
    const double e = static_cast<double>(events);
    const double rate = e / cpu;
    if (first == 0) first = rate;
    std::printf("%d,%lld,%.4g,%.4g,%.4g,%.4g,%.4g,%.1f,%.3f\n", n, events, rate, cpu * 1e9 / bs,
                cpu * 1e9 / sbs, bs / e, sbs / e, per_block, rate / first);
    std::fflush(stdout);
  }
  return 0;
}
