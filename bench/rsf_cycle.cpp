// CPU seconds and steps per seismic cycle of the rate-and-state spring-slider on QDYN's
// stick-slip case (tests/numeric/test_rsf.cpp; data/scenes/rsf/qdyn-stickslip.ini), beside
// QDYN's own figure (about 0.25 s of CPU for 1e4 s of simulated time, 17 cycles and about
// 44 000 adaptive steps with output off: about 15 ms per cycle), at several tolerances, with
// the period and tau/sigma extremes each reaches (QDYN: 585.48 s, 0.41166 .. 0.67887; the
// extremes here are read at step ends, the test locates them inside the steps). Then chains
// of N coupled blocks (k_c = k) and square lattices (k_c = k/2 along and across, periodic along
// strike, free across) from a rough start: events per CPU second, the steps, and the springs per
// block, which bound the coupling sums (one term per spring: 2 for a nearest-neighbour chain, 4
// on a lattice, 2R for a chain of range R; the rest of a step is O(N)).
//
//   build/rsf_cycle [--repeat R] [--chain N ...] [--lattice L ...] [--range R] [--duration T]
//     defaults: R = 5, chains of 100 and 1000, a 64 x 64 lattice, nearest neighbours, T = 2000 s
//     of simulated time for the chains and lattices

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "engine/rsf_cycle.hpp"
#include "engine/rsf_events.hpp"
#include "support/qdyn_stickslip.hpp"
#include "thread_clock.hpp"

namespace {

using namespace bkq;

// The chain (rows = 1) or lattice, and its springs: nearest neighbours, or a range-R chain.
RsfModel grid(int nx, int rows, int range) {
  RsfModel m = test::qdyn_stickslip(nx * rows);
  m.rows = rows;
  if (rows > 1) {
    m.periodic = true;
    m.springs = {{1, 0, 1e9}, {0, 1, 1e9}};
  } else {
    for (int r = 1; r <= range; ++r) m.springs.push_back({r, 0, 2e9 / range});
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5, range = 1;
  double duration = 2000;
  std::vector<int> chains, lattices;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc)
      repeat = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--chain") == 0 && i + 1 < argc)
      chains.push_back(std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--lattice") == 0 && i + 1 < argc)
      lattices.push_back(std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--range") == 0 && i + 1 < argc)
      range = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--duration") == 0 && i + 1 < argc)
      duration = std::atof(argv[++i]);
  }
  if (chains.empty() && lattices.empty()) chains = {100, 1000}, lattices = {64};
  std::printf("QDYN stick-slip, 1e4 s (17 cycles); QDYN: ~15 ms CPU and ~2600 steps per cycle\n");
  std::printf("%10s %12s %12s %14s %12s %12s %10s\n", "tolerance", "ms/cycle", "steps/cycle",
              "period [s]", "tau/s min", "tau/s max", "vs QDYN");
  for (double tol : {1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
    double best = 1e300;
    std::vector<double> peaks;
    double f_min = 1e300, f_max = -1e300;
    std::int64_t steps = 0;
    for (int r = 0; r < repeat; ++r) {
      peaks.clear();
      RsfCycle c(test::qdyn_stickslip(1), tol, {2e-5}, {10});
      const double t0 = bench::thread_seconds();
      while (c.t() < 1e4) {
        c.step(1e4);
        // Peaks on the step ends' Hermite cubic (as the test locates them); cheap beside a step.
        if (c.dy_prev()[1] > 0 && c.dy()[1] <= 0)
          peaks.push_back(hermite_extremum(c.t_prev(), c.y_prev()[1], c.dy_prev()[1], c.t(),
                                           c.y()[1], c.dy()[1])
                              .t);
        if (peaks.size() >= 2) {
          const double f = c.friction_stress(0) / 5e6;
          f_min = std::min(f_min, f);
          f_max = std::max(f_max, f);
        }
      }
      best = std::min(best, bench::thread_seconds() - t0);
      steps = c.accepted();
    }
    const double cycles = static_cast<double>(peaks.size());
    std::vector<double> d;
    for (std::size_t i = 3; i < peaks.size(); ++i) d.push_back(peaks[i] - peaks[i - 1]);
    std::sort(d.begin(), d.end());
    const double period = d.empty() ? NAN : d[d.size() / 2];
    const double ms = 1e3 * best / cycles;
    std::printf("%10.0e %12.4f %12.0f %14.6f %12.6f %12.6f %9.1fx\n", tol, ms, steps / cycles,
                period, f_min, f_max, 15.0 / ms);
  }
  std::printf(
      "\nchains (k_c = k, free ends) and lattices (k_c = k/2 each way, periodic x, free y):\n"
      "quasi-dynamic, V_th = 1e-3 m/s, tol 1e-8, %g s from a rough start\n",
      duration);
  std::printf("%12s %8s %10s %12s %14s %12s %14s\n", "system", "springs", "events", "CPU [s]",
              "events/CPU s", "steps", "us/step/block");
  const auto run = [&](const char* what, int nx, int rows) {
    const RsfModel m = grid(nx, rows, rows > 1 ? 1 : range);
    const int n = m.n();
    std::vector<double> v(n);
    for (int j = 0; j < n; ++j) v[j] = 1e-6 * (1 + 0.5 * std::sin(1.3 * j));  // a rough start
    RsfCycle c(m, 1e-8, v, {10});
    RsfEventDetector events(1e-3);
    const double t0 = bench::thread_seconds();
    while (c.t() < duration) {
      c.step(duration);
      events.observe(c);
    }
    const double cpu = bench::thread_seconds() - t0;
    char name[32];
    if (rows > 1)
      std::snprintf(name, sizeof name, "%s %dx%d", what, nx, rows);
    else
      std::snprintf(name, sizeof name, "%s %d", what, nx);
    std::printf("%12s %8zu %10lld %12.3f %14.2f %12lld %14.3f\n", name, 2 * m.stencil().size(),
                static_cast<long long>(events.events()), cpu, events.events() / cpu,
                static_cast<long long>(c.accepted()),
                1e6 * cpu / static_cast<double>(c.accepted() + c.rejected()) / n);
  };
  for (int n : chains) run("chain", n, 1);
  for (int l : lattices) run("lattice", l, l);
  return 0;
}
