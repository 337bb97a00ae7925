// Topplings per second of the OFC automaton (engine/ofc.hpp), printed: the engine alone,
// then whole `bkquake run`s of the same scene with the catalogue off (output.catalog = none),
// with catalog.csv and with catalog.h5, all in this one process, so the ratios compare like with
// like. The lattice starts from a random field and is run past a transient first (the timed events
// are those of the stationary state, not of the start).
//   build/ofc [L=256] [ALPHA=0.2] [EVENTS=2000000] [TRANSIENT=2000000] [WHAT=all|engine]
// WHAT = engine times the engine alone (no runs).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include "app/run.hpp"
#include "engine/ofc.hpp"
#include "io/scene.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CPU seconds of this process (on a shared machine the wall clock also counts others' work).
double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

}  // namespace

int main(int argc, char** argv) {
  const int L = argc > 1 ? std::atoi(argv[1]) : 256;
  const double alpha = argc > 2 ? std::atof(argv[2]) : 0.2;
  const long events = argc > 3 ? std::atol(argv[3]) : 2000000;
  const long transient = argc > 4 ? std::atol(argv[4]) : 2000000;
  const bool runs = !(argc > 5 && std::string(argv[5]) == "engine");
  if (L < 1 || !(alpha > 0 && alpha <= 0.25) || events < 1 || transient < 0) {
    std::fprintf(stderr,
                 "usage: ofc [L >= 1] [0 < ALPHA <= 0.25] [EVENTS >= 1] [TRANSIENT >= 0]\n");
    return 2;
  }
  bkq::OfcParams p;
  p.nx = p.ny = L;
  p.alpha = alpha;

  // The engine alone.
  bkq::OfcEngine engine(p, bkq::ofc_initial_field(p, 1));
  for (long k = 0; k < transient; ++k) engine.next_event();
  const std::int64_t t0 = engine.counters().topplings;
  const auto c0 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  for (long k = 0; k < events; ++k) engine.next_event();
  const double s = seconds_since(c0), cpu = cpu_seconds() - cpu0;
  const double topplings = static_cast<double>(engine.counters().topplings - t0);
  std::printf("ofc %dx%d alpha %g, %ld events after %ld transient (%.3g topplings per event)\n", L,
              L, alpha, events, transient, topplings / static_cast<double>(events));
  std::printf(
      "  engine alone:               %.3e topplings/s wall, %.3e per CPU s; %.3e events/s\n",
      topplings / s, topplings / cpu, static_cast<double>(events) / s);

  // The engine allocates everything when it starts: the peak memory must not grow with the
  // number of events (compare two runs with different EVENTS).
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("  peak resident memory:       %.1f MB\n",
              static_cast<double>(usage.ru_maxrss) / 1024);
  if (!runs) return 0;
  // Whole runs: the transient is run but not timed by the summary; the bench times the run.
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("bkquake-bench-ofc-" + std::to_string(getpid())))
          .string();
  for (const char* catalog : {"none", "csv", "hdf5"}) {
    bkq::RunRequest req;
    req.scene.set("model.kind", "ofc");
    req.scene.set("model.blocks", std::to_string(L));
    req.scene.set("model.rows", std::to_string(L));
    req.scene.set("ofc.alpha", std::to_string(alpha));
    req.scene.set("run.transient_events", std::to_string(transient));
    req.scene.set("run.events", std::to_string(events));
    req.scene.set("run.seed", "1");
    req.scene.set("output.catalog", catalog);
    req.scene.validate();
    req.out_dir = dir;
    req.force = true;
    req.quiet = true;
    const auto r0 = std::chrono::steady_clock::now();
    const double rcpu0 = cpu_seconds();
    bkq::run_scene(req);
    const double whole = seconds_since(r0), whole_cpu = cpu_seconds() - rcpu0;
    // The same events as the engine alone (same seed): the topplings of transient + events.
    const double all = static_cast<double>(engine.counters().topplings);
    std::printf(
        "  run, output.catalog = %-4s %.3e topplings/s wall, %.3e per CPU s (transient "
        "included; %.3g s)\n",
        catalog, all / whole, all / whole_cpu, whole);
  }
  std::filesystem::remove_all(dir);
  return 0;
}
