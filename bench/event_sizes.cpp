// Where the event engine's time goes, by event size: the carlson-langer scene (RK4,
// dt = 0.01), past a transient of 20 events per block, each event timed on its own and
// filed by the number of blocks that slipped. Prints, per size class, the share of the
// events, the steps per event, the share of the time and the time per event. The clock
// is read twice per event (some tens of nanoseconds, which the one-block row feels).
// With --csv FILE it also writes, for every event size that occurred, the number of
// events, their mean time (microseconds), mean steps and mean sliding block-steps
// (analysis/plot_event_sizes.py draws it).
//   build/event_sizes [N=100] [EVENTS=400000] [--csv FILE]
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "carlson_langer_events.hpp"

int main(int argc, char** argv) {
  std::vector<const char*> positional;
  const char* csv_path = nullptr;
  bool usage_error = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--csv") == 0) {
      if (i + 1 < argc)
        csv_path = argv[++i];
      else
        usage_error = true;
    } else {
      positional.push_back(argv[i]);
    }
  }
  const int n = positional.size() > 0 ? std::atoi(positional[0]) : 100;
  const std::int64_t events = positional.size() > 1 ? std::atoll(positional[1]) : 400000;
  if (usage_error || positional.size() > 2 || n < 1 || events < 1) {
    std::fprintf(stderr, "usage: event_sizes [BLOCKS >= 1] [EVENTS >= 1] [--csv FILE]\n");
    return 2;
  }
  bkq::bench::CarlsonLangerEvents setup(n);
  bkq::EventEngine& engine = setup.engine;

  constexpr int kClasses = 5;
  const int lowest[kClasses + 1] = {1,  2,      4, 10,
                                    30, 1 << 30};  // class k: lowest[k] <= blocks < lowest[k + 1]
  double seconds[kClasses] = {};
  std::int64_t count[kClasses] = {}, steps[kClasses] = {};
  // The same per event size (index: blocks), for the CSV.
  std::vector<double> size_seconds(n + 1, 0.0);
  std::vector<std::int64_t> size_count(n + 1, 0), size_steps(n + 1, 0), size_sliding(n + 1, 0);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  for (std::int64_t i = 0; i < events; ++i) {
    const std::int64_t steps_before = engine.counters().steps;
    const std::int64_t sliding_before = engine.counters().sliding_block_steps;
    const Clock::time_point t0 = Clock::now();
    const bkq::EventRecord e = engine.next_event();
    const Clock::time_point t1 = Clock::now();
    int k = 0;
    while (e.blocks >= lowest[k + 1]) ++k;
    const double dt = std::chrono::duration<double>(t1 - t0).count();
    const std::int64_t event_steps = engine.counters().steps - steps_before;
    seconds[k] += dt;
    ++count[k];
    steps[k] += event_steps;
    size_seconds[e.blocks] += dt;
    ++size_count[e.blocks];
    size_steps[e.blocks] += event_steps;
    size_sliding[e.blocks] += engine.counters().sliding_block_steps - sliding_before;
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
  if (csv_path != nullptr) {
    std::FILE* f = std::fopen(csv_path, "w");
    if (f == nullptr) {
      std::fprintf(stderr, "event_sizes: cannot write %s\n", csv_path);
      return 1;
    }
    std::fprintf(f, "# N = %d, %lld events, carlson-langer scene, rk4 dt = 0.01\n", n,
                 static_cast<long long>(events));
    std::fprintf(f, "blocks,count,mean_time_us,mean_steps,mean_sliding_block_steps\n");
    for (int b = 1; b <= n; ++b) {
      if (size_count[b] == 0) continue;
      const double c = static_cast<double>(size_count[b]);
      std::fprintf(f, "%d,%lld,%.6g,%.6g,%.6g\n", b, static_cast<long long>(size_count[b]),
                   1e6 * size_seconds[b] / c, static_cast<double>(size_steps[b]) / c,
                   static_cast<double>(size_sliding[b]) / c);
    }
    if (std::fclose(f) != 0) {
      std::fprintf(stderr, "event_sizes: cannot write %s\n", csv_path);
      return 1;
    }
  }
  return 0;
}
