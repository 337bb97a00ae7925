// Event-driven against continuous rate-and-state on the same chain (engine/rsf_loader.hpp vs
// engine/rsf_cycle.hpp): QDYN's stick-slip block on each of N blocks (or, with --asperities,
// the pattern of rsf.pattern = asperities: blocks with j mod 10 < 5 keep a = 0.01, b = 0.025,
// the others have a and b swapped), springs k_c = k, free ends, quasi-dynamic, V_th = 1e-3 m/s,
// tolerance 1e-8, from the rate-and-state bench's rough start (V_j = V_pl (1 + 0.5 sin(1.3 j)),
// theta = 10 s), over T seconds of simulated time.
//
// Prints each engine's events, CPU seconds and events per CPU second side by side and their
// ratio (the event-driven engine once per creep quantum given, and with none: "off"; each
// event integrated on the whole grid, on its active blocks only, engine/rsf_active.hpp, with
// the mean number of blocks that integration carries per step, what bounds its ratio, and on
// its active blocks with blocks away from their closed forms integrated alone below V_a,
// engine/rsf_alone.hpp, with the steps of those single-block integrations, and the same with
// the active blocks in groups that share no spring, each at its own step size), then the
// magnitude distributions' Kolmogorov-Smirnov distance between each event-driven run and the
// continuous one, beside the distance between two continuous runs from different rough starts
// (phase 1.3 j and 0.7 j); events before T/5 are left out. Then what bounds the speed-up: the
// continuous integrator's steps and CPU split into those taken while the fastest block is below
// V_h (what the event-driven engine replaces by closed forms) and at or above it (what it
// integrates too; of those, the steps taken while the fastest block is seismic, at or above
// V_th); total CPU / the CPU above V_h is the ceiling on the speed-up at equal events.
// Each row also gives the blocks integrated per event: block steps (a step of the whole grid
// counts N, of the active blocks their number, a step of a block alone one) over events. Both
// engines take about as many steps per event (the event's), so the continuous run's block steps
// per event over an event-driven run's bound its speed-up where a block step costs the same.
// The blocks alone are integrated at the scene's auto rsf.alone_tolerance (1e-6; --alone-tol
// sets it), and once more in groups at the integrator's 1e-8: what that accuracy costs.
// --fast runs only the first continuous start and the fastest event-driven engines (active
// blocks with blocks alone, in one integration and in groups): the ratio without the
// seed-to-seed yardstick, for long chains.
//
//   build/rsf_event [--chain N] [--duration T] [--speed V_pl] [--handover V_h]
//                   [--quantum q[,q2,...]] [--asperities] [--rough r] [--alone V_a]
//                   [--alone-tol tol] [--fast]
//     defaults: N = 100, T = 2000 s, V_pl = 1e-6 m/s, q = 1e-6 m (the scene's auto, D_c/10);
//     the handover speed is the scene's auto, min(V_th/10, 0.01 a sigma/eta); --rough r spreads
//     each block's D_c by a factor in [1 - r, 1 + r] (default 0); V_a defaults to the scene's
//     auto, min(100 V_pl, V_th/10, 0.01 a sigma/eta)

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
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
  long long events = 0, steps = 0, syncs = 0;
  double cpu = 0;
  double mean_active = NAN;   // active-block engine: blocks integrated per step
  long long alone_steps = 0;  // the single-block integrations' steps
  long long block_steps = 0;  // blocks integrated, summed over steps (alone steps included)
  // Continuous only: steps and CPU while the fastest block is below V_h, and at or above it.
  long long steps_below = 0, steps_above = 0;
  long long steps_seismic = 0;  // of those above: the fastest block at or above V_th
  double cpu_below = 0, cpu_above = 0;
};

std::vector<double> rough(int n, double v_pl, double phase) {
  std::vector<double> v(n);
  for (int j = 0; j < n; ++j) v[j] = v_pl * (1 + 0.5 * std::sin(phase * j));
  return v;
}

// The clock is read only where the fastest block crosses V_h, so the split costs nothing per
// step; a step counts on the side its start lies on.
Result continuous(const RsfModel& m, double duration, double phase, double v_h) {
  Result r;
  RsfCycle c(m, 1e-8, rough(m.n(), m.v_pl, phase), {10});
  RsfEventDetector events(1e-3);
  const double ln_vh = std::log(v_h), ln_vth = std::log(1e-3);
  const auto fastest = [&] {
    double ln_v = -HUGE_VAL;
    for (int j = 0; j < c.n(); ++j) ln_v = std::max(ln_v, c.ln_v(j));
    return ln_v;
  };
  const double t0 = bench::thread_seconds();
  double t_mark = t0;
  bool was_above = fastest() >= ln_vh;
  while (c.t() < duration) {
    c.step(duration);
    (was_above ? r.steps_above : r.steps_below) += 1;
    const double top = fastest();  // one scan a step, for both splits
    if (was_above && top >= ln_vth) ++r.steps_seismic;
    if (auto e = events.observe(c))
      if (e->hypocentre_time > duration / 5) r.magnitudes.push_back(e->magnitude);
    const bool now_above = top >= ln_vh;
    if (now_above != was_above) {
      const double t = bench::thread_seconds();
      (was_above ? r.cpu_above : r.cpu_below) += t - t_mark;
      t_mark = t;
      was_above = now_above;
    }
  }
  const double t1 = bench::thread_seconds();
  (was_above ? r.cpu_above : r.cpu_below) += t1 - t_mark;
  r.cpu = t1 - t0;
  r.events = events.events();
  r.steps = c.accepted();
  r.block_steps = r.steps * c.n();
  return r;
}

// active: each event on its active blocks (groups: in groups that share no spring, each at
// its own step size); v_alone > 0: blocks alone below it.
Result event_driven(const RsfModel& m, double duration, double phase, double v_h, double q,
                    bool active, double v_alone = 0, bool groups = false, double alone_tol = 0) {
  Result r;
  RsfEventEngine engine(m, 1e-8, 1e-3, v_h, q, rough(m.n(), m.v_pl, phase), {10});
  engine.set_active_blocks(active);
  engine.set_groups(groups);
  if (v_alone > 0) engine.set_alone_speed(v_alone, alone_tol);
  const double t0 = bench::thread_seconds();
  while (auto e = engine.next(duration))
    if (e->hypocentre_time > duration / 5) r.magnitudes.push_back(e->magnitude);
  r.cpu = bench::thread_seconds() - t0;
  r.events = engine.events();
  r.steps = engine.steps();
  r.syncs = engine.syncs();
  if (active) r.mean_active = static_cast<double>(engine.active_block_steps()) / r.steps;
  r.alone_steps = engine.loader().alone_steps();
  r.block_steps = (active ? engine.active_block_steps() : r.steps * m.n()) + r.alone_steps;
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

double mean(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v;
  return x.empty() ? NAN : s / static_cast<double>(x.size());
}

}  // namespace

int main(int argc, char** argv) {
  int n = 100;
  double duration = 2000, v_pl = 1e-6, v_h = 0, v_alone = 0, alone_tol = 1e-6;
  std::vector<double> quanta;
  bool asperities = false, fast = false;
  double rough_dc = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--chain") == 0 && i + 1 < argc)
      n = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--duration") == 0 && i + 1 < argc)
      duration = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--speed") == 0 && i + 1 < argc)
      v_pl = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--handover") == 0 && i + 1 < argc)
      v_h = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--alone") == 0 && i + 1 < argc)
      v_alone = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--alone-tol") == 0 && i + 1 < argc)
      alone_tol = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--quantum") == 0 && i + 1 < argc) {
      const std::string list = argv[++i];
      for (std::size_t p = 0; p < list.size();) {
        const std::size_t comma = std::min(list.find(',', p), list.size());
        const std::string item = list.substr(p, comma - p);
        quanta.push_back(item == "off" ? std::numeric_limits<double>::infinity()
                                       : std::atof(item.c_str()));
        p = comma + 1;
      }
    } else if (std::strcmp(argv[i], "--asperities") == 0) {
      asperities = true;
    } else if (std::strcmp(argv[i], "--rough") == 0 && i + 1 < argc) {
      rough_dc = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--fast") == 0) {
      fast = true;
    }
  }
  if (quanta.empty()) quanta = {1e-6};
  RsfModel m = test::qdyn_stickslip(n);
  m.springs = {{1, 0, 2e9}};
  m.v_pl = v_pl;
  if (asperities) {
    rsf::Params barrier = m.law[0].params();
    std::swap(barrier.a, barrier.b_rsf);
    for (int j = 0; j < n; ++j)
      if (j % 10 >= 5) m.law[j] = rsf::Law(barrier);
  }
  // Identical blocks keep equivalent ones in step in the continuous integration; a rough D_c
  // (each block's times U[1 - r, 1 + r], a fixed seed) breaks that symmetry.
  if (rough_dc > 0) {
    std::mt19937_64 draw(1);
    for (int j = 0; j < n; ++j) {
      rsf::Params p = m.law[j].params();
      const double u = static_cast<double>(draw() >> 11) * 0x1p-53;  // [0, 1), portable
      p.dc *= 1 + rough_dc * (2 * u - 1);
      m.law[j] = rsf::Law(p);
    }
  }
  if (v_h == 0) v_h = std::min(1e-4, 0.01 * 0.01 * m.sigma / m.eta);
  if (v_alone == 0) v_alone = std::min({100 * v_pl, 1e-4, 0.01 * 0.01 * m.sigma / m.eta});
  std::printf(
      "chain %d%s, D_c spread %g, V_pl = %g m/s, %g s simulated, V_h = %g m/s, V_a = %g m/s, "
      "blocks alone at tolerance %g\n",
      n, asperities ? " (asperities)" : "", rough_dc, v_pl, duration, v_h, v_alone, alone_tol);
  const Result c1 = continuous(m, duration, 1.3, v_h);
  const Result c2 = fast ? Result{} : continuous(m, duration, 0.7, v_h);
  std::printf(
      "continuous steps with the fastest block below V_h: %lld (%.3f CPU s), at or above: %lld "
      "(%.3f CPU s; %lld of them, %.0f %%, ending with a block at or above V_th); ceiling on the "
      "speed-up at equal events: total/above = %.1fx\n",
      c1.steps_below, c1.cpu_below, c1.steps_above, c1.cpu_above, c1.steps_seismic,
      100.0 * static_cast<double>(c1.steps_seismic) / static_cast<double>(c1.steps),
      c1.cpu / c1.cpu_above);
  std::printf("%-42s %9s %9s %10s %13s %7s %10s %10s %9s %8s %11s %12s %13s\n", "engine", "events",
              "CPU [s]", "events/CPU s", "ratio", "KS", "mean M", "steps", "syncs", "active",
              "alone steps", "steps/event", "blocks/event");
  const auto per_event = [](const Result& r) {
    return static_cast<double>(r.block_steps) / static_cast<double>(r.events);
  };
  const auto row = [&](const char* name, const Result& r, double ks_value) {
    std::printf(
        "%-42s %9lld %9.3f %10.2f %12.1fx %7.3f %10.3f %10lld %9lld %8.2f %11lld %12.1f %13.0f\n",
        name, r.events, r.cpu, r.events / r.cpu, (r.events / r.cpu) / (c1.events / c1.cpu),
        ks_value, mean(r.magnitudes), r.steps, r.syncs, r.mean_active, r.alone_steps,
        static_cast<double>(r.steps) / static_cast<double>(r.events), per_event(r));
  };
  row("continuous", c1, 0.0);
  if (!fast) row("continuous, other start", c2, ks(c2.magnitudes, c1.magnitudes));
  double ceiling = NAN, ceiling_groups = NAN;
  for (const double q : quanta)
    for (const int how_ : {0, 1, 2, 4, 3}) {
      if (fast && how_ < 2) continue;
      const bool active = how_ > 0;
      // 4: groups, their blocks alone at the integrator's tolerance (0: the engine's, 1e-8).
      const Result e = event_driven(m, duration, 1.3, v_h, q, active, how_ >= 2 ? v_alone : 0,
                                    how_ >= 3, how_ == 4 ? 0 : alone_tol);
      char name[64];
      const char* how = how_ == 4   ? "groups, alone at 1e-8"
                        : how_ == 3 ? "groups, alone"
                        : how_ == 2 ? "active blocks, alone"
                        : active    ? "active blocks"
                                    : "whole grid";
      if (std::isinf(q))
        std::snprintf(name, sizeof name, "events, %s, q off", how);
      else
        std::snprintf(name, sizeof name, "events, %s, q = %g", how, q);
      row(name, e, ks(e.magnitudes, c1.magnitudes));
      if (how_ >= 2) (how_ == 2 ? ceiling : ceiling_groups) = per_event(c1) / per_event(e);
    }
  std::printf(
      "magnitudes counted after T/5 (%zu and %zu continuous events); KS to the first "
      "continuous run\n",
      c1.magnitudes.size(), c2.magnitudes.size());
  std::printf(
      "blocks integrated per event, continuous over active blocks with blocks alone (last "
      "quantum): %.1fx, in groups %.1fx; the ratio if a block step cost the same in both\n",
      ceiling, ceiling_groups);
  return 0;
}
