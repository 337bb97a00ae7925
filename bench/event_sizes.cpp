// Where the event engine's time goes, by event size: the carlson-langer scene (RK4,
// dt = 0.01), past a transient of 20 events per block, each event timed on its own and
// filed by the number of blocks that slipped. Prints, per size class, the share of the
// events, the steps per event, the share of the time and the time per event. The clock
// is read twice per event (some tens of nanoseconds, which the one-block row feels).
//   build/event_sizes [N=100] [EVENTS=400000]
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "carlson_langer_events.hpp"

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 100;
  const std::int64_t events = argc > 2 ? std::atoll(argv[2]) : 400000;
  if (n < 1 || events < 1) {
    std::fprintf(stderr, "usage: event_sizes [BLOCKS >= 1] [EVENTS >= 1]\n");
    return 2;
  }
  bkq::bench::CarlsonLangerEvents setup(n);
  bkq::EventEngine& engine = setup.engine;

  constexpr int kClasses = 5;
  const int lowest[kClasses + 1] = {1,  2,      4, 10,
                                    30, 1 << 30};  // class k: lowest[k] <= blocks < lowest[k + 1]
  double seconds[kClasses] = {};
  std::int64_t count[kClasses] = {}, steps[kClasses] = {};
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  for (std::int64_t i = 0; i < events; ++i) {
    const std::int64_t steps_before = engine.counters().steps;
    const Clock::time_point t0 = Clock::now();
    const bkq::EventRecord e = engine.next_event();
    const Clock::time_point t1 = Clock::now();
    int k = 0;
    while (e.blocks >= lowest[k + 1]) ++k;
    seconds[k] += std::chrono::duration<double>(t1 - t0).count();
    ++count[k];
    steps[k] += engine.counters().steps - steps_before;
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  double timed = 0;
  for (double s : seconds) timed += s;
  std::printf("N = %d, %lld events: %.3g events/s\n", n, static_cast<long long>(events),
              events / wall);
  std::printf(
      "| event size (blocks) | share of events | steps per event | share of the time | time per "
      "event |\n");
  std::printf("|---|---|---|---|---|\n");
  for (int k = 0; k < kClasses; ++k) {
    if (count[k] == 0) continue;
    const std::string size =
        lowest[k + 1] - lowest[k] == 1 ? std::to_string(lowest[k])
        : k + 1 == kClasses            ? ">= " + std::to_string(lowest[k])
                            : std::to_string(lowest[k]) + "-" + std::to_string(lowest[k + 1] - 1);
    std::printf("| %s | %.1f %% | %.0f | %.1f %% | %.3g us |\n", size.c_str(),
                100.0 * count[k] / events, static_cast<double>(steps[k]) / count[k],
                100.0 * seconds[k] / timed, 1e6 * seconds[k] / count[k]);
  }
  return 0;
}
