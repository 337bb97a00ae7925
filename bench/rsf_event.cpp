// Event-driven against continuous rate-and-state on the same chain (engine/rsf_loader.hpp vs
// engine/rsf_cycle.hpp): QDYN's stick-slip block on each of N blocks, springs k_c = k, free
// ends, quasi-dynamic, V_th = 1e-3 m/s, tolerance 1e-8, from the rate-and-state bench's rough
// start (V_j = V_pl (1 + 0.5 sin(1.3 j)), theta = 10 s), over T seconds of simulated time.
// Prints each engine's events, CPU seconds and events per CPU second side by side and their
// ratio, then the magnitude distributions' Kolmogorov-Smirnov distance between the
// event-driven run and the continuous one, beside the distance between two continuous runs
// from different rough starts (phase 1.3 j and 0.7 j); events before T/5 are left out.
//
//   build/rsf_event [--chain N] [--duration T] [--speed V_pl] [--handover V_h]
//     defaults: N = 100, T = 2000 s, V_pl = 1e-6 m/s (the handover speed is the scene's auto:
//     min(V_th/10, 0.01 a sigma/eta))

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "engine/rsf_cycle.hpp"
#include "engine/rsf_events.hpp"
#include "engine/rsf_loader.hpp"
#include "support/qdyn_stickslip.hpp"
#include "thread_clock.hpp"

namespace {

using namespace bkq;

struct Result {
  std::vector<double> magnitudes;  // after the transient
  long long events = 0;
  double cpu = 0;
};

std::vector<double> rough(int n, double v_pl, double phase) {
  std::vector<double> v(n);
  for (int j = 0; j < n; ++j) v[j] = v_pl * (1 + 0.5 * std::sin(phase * j));
  return v;
}

Result continuous(const RsfModel& m, double duration, double phase) {
  Result r;
  RsfCycle c(m, 1e-8, rough(m.n(), m.v_pl, phase), {10});
  RsfEventDetector events(1e-3);
  const double t0 = bench::thread_seconds();
  while (c.t() < duration) {
    c.step(duration);
    if (auto e = events.observe(c))
      if (e->hypocentre_time > duration / 5) r.magnitudes.push_back(e->magnitude);
  }
  r.cpu = bench::thread_seconds() - t0;
  r.events = events.events();
  return r;
}

Result event_driven(const RsfModel& m, double duration, double phase, double v_h) {
  Result r;
  RsfEventEngine engine(m, 1e-8, 1e-3, v_h, rough(m.n(), m.v_pl, phase), {10});
  const double t0 = bench::thread_seconds();
  while (auto e = engine.next(duration))
    if (e->hypocentre_time > duration / 5) r.magnitudes.push_back(e->magnitude);
  r.cpu = bench::thread_seconds() - t0;
  r.events = engine.events();
  return r;
}

// sup |F1 - F2| of the two samples' empirical distributions.
double ks(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return NAN;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::size_t i = 0, j = 0;
  double d = 0;
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
    d = std::max(d,
                 std::fabs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
  }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  int n = 100;
  double duration = 2000, v_pl = 1e-6, v_h = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--chain") == 0 && i + 1 < argc)
      n = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--duration") == 0 && i + 1 < argc)
      duration = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--speed") == 0 && i + 1 < argc)
      v_pl = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--handover") == 0 && i + 1 < argc)
      v_h = std::atof(argv[++i]);
  }
  RsfModel m = test::qdyn_stickslip(n);
  m.springs = {{1, 0, 2e9}};
  m.v_pl = v_pl;
  if (v_h == 0) v_h = std::min(1e-4, 0.01 * 0.01 * m.sigma / m.eta);
  std::printf("chain %d, V_pl = %g m/s, %g s simulated, V_h = %g m/s\n", n, v_pl, duration, v_h);
  const Result c1 = continuous(m, duration, 1.3);
  const Result e1 = event_driven(m, duration, 1.3, v_h);
  std::printf("%14s %10s %10s %14s\n", "engine", "events", "CPU [s]", "events/CPU s");
  std::printf("%14s %10lld %10.3f %14.2f\n", "continuous", c1.events, c1.cpu, c1.events / c1.cpu);
  std::printf("%14s %10lld %10.3f %14.2f\n", "event-driven", e1.events, e1.cpu, e1.events / e1.cpu);
  std::printf("ratio of events per CPU second (event-driven / continuous): %.1fx\n",
              (e1.events / e1.cpu) / (c1.events / c1.cpu));
  const Result c2 = continuous(m, duration, 0.7);
  std::printf(
      "magnitudes after T/5: KS(event-driven, continuous) = %.3f (%zu, %zu events); "
      "KS(continuous, continuous from another start) = %.3f (%zu events)\n",
      ks(e1.magnitudes, c1.magnitudes), e1.magnitudes.size(), c1.magnitudes.size(),
      ks(c1.magnitudes, c2.magnitudes), c2.magnitudes.size());
  return 0;
}
