// The relaxation kernels of the event engine, per sliding block-step, for a cluster of k
// contiguous sliding blocks between two stuck ones (issue 20, goal 2: <= 5 ns per sliding
// block-step). Carlson-langer scene (l = 10, alpha = 2.5, sigma = 0.01, clst91), RK4 at
// dt = 0.01, through the stepper's public entry points:
//   BM_Cluster         SchemeTraits::cluster_kernel, the register cluster (k <= kMaxCluster = 8
//                      only): the step, the dissipated power and the stick rule;
//   BM_Held            Stepper::step_held, the fused held-range step alone;
//   BM_HeldContacts    the same plus what the engine does after it on that path: the copy
//                      of the velocities, dissipated_power and settle_contacts;
//   BM_General         Stepper::step, the general step alone;
//   BM_GeneralContacts the same plus the copy, dissipated_power and settle_contacts;
//   BM_Minimal         a stand-alone loop of the same arithmetic (RK4's four stages, the
//                      interior spring force, the law's division; no stick flags, no
//                      dispatch, no scratch): the bound the kernels are held against;
//   BM_Restore         the restart every iteration pays, alone (see below).
// Every counter is nanoseconds per sliding block-step; after the runs a table puts the
// kernels side by side with the bound's flops and divisions per block-step.
//
// The scene: N = k + 34 blocks, the range [16, k + 18) covered (k sliding blocks between
// the stuck blocks 16 and k + 17), the substrate and the held pad at 0. The sliding
// blocks start at rest in the cluster's lowest mode, w_i = -D sin(pi i/(k+1)), D chosen
// so that even the blocks next to the ends are pulled 20 times the threshold forward;
// every other block is stuck, the blocks beyond the ends far behind so that the ends'
// spring forces stay below the threshold. Every block then slides forward for half a
// period of the lowest mode, pi/omega (22 steps at k = 1, 314 at k = 1000). Each
// iteration restores the range's state from a saved copy (included in the time; its
// cost, BM_Restore, is printed so it can be subtracted) and runs M steps, 0.6 of that
// half period; the set-up checks that every block slides through all M steps.
//   build/cluster_kernel [--benchmark_filter=...] [--benchmark_repetitions=R ...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "carlson_langer_events.hpp"
#include "engine/contacts.hpp"
#include "integrate/cluster.hpp"
#include "model/laws/clst91.hpp"
#include "model/substrate.hpp"

namespace {

constexpr double kDt = 0.01;
constexpr int kMargin = 16;  // blocks before the range (and after it)

// Flops and divisions of one RK4 block-step with the clst91 law, counted from the code
// (a fused multiply-add counts 2). Per stage, the acceleration: interior_force 7
// (anchor - w, k_p *, 2 w, -, +, k_c *, +), the law's magnitude fma 2 and its division,
// f/m - phi 2, times the stick flag 1: 12 and one division. The updates
// (integrate/rk4.hpp): first 4, middle 8 twice, last 6: 26. In all 4 * 12 + 26 (the
// minimal loops below leave out the stick flag's product: 70). The register cluster
// takes the first stage's |phi| from the end of the step before, where the power needs
// it, so it too divides four times; the engine's other paths add dissipated_power's two
// magnitudes (two more divisions) and its 10 flops, and the stick rule.
constexpr int kFlopsPerBlockStep = 74;
constexpr int kDivisionsPerBlockStep = 4;

struct ClusterScene {
  explicit ClusterScene(int k)
      : k(k),
        n(k + 2 + 2 * kMargin),
        p(bkq::model_from_scene(bkq::bench::carlson_langer_scene(n, "bk"))),
        forces(p),
        stepper(bkq::make_stepper("rk4", n)),
        range{kMargin, kMargin + k + 2} {
    // The lowest mode of k blocks between fixed ends: K u = lambda u.
    const double half = std::numbers::pi / (2.0 * (k + 1));
    const double lambda = p.k_p + 4.0 * p.k_c * std::sin(half) * std::sin(half);
    const double omega = std::sqrt(lambda / p.m_u);
    const double depth = 20.0 * forces.friction().threshold / (lambda * std::sin(2.0 * half));
    steps = std::max(4, static_cast<int>(0.6 * std::numbers::pi / (omega * kDt)));
    saved.resize(n);
    saved.s = saved.x = saved.xd = saved.t = 0;
    for (int j = 0; j < n; ++j) {
      saved.w[j] = j < range.lo || j >= range.hi ? -(10.0 * depth + 10.0) : 0.0;
      saved.wd[j] = 0;
      saved.mobile[j] = 0;
      saved.dir[j] = 1;
    }
    for (int i = 1; i <= k; ++i) {
      saved.w[range.lo + i] = -depth * std::sin(2.0 * half * i);
      saved.mobile[range.lo + i] = 1;
    }
    saved.recompute_sum_w();
    st = saved;
    old.assign(n, 0.0);
  }
  // The range's state as saved, and the time.
  void restore() {
    const int lo = range.lo, hi = range.hi;
    std::copy(saved.w.begin() + lo, saved.w.begin() + hi, st.w.begin() + lo);
    std::copy(saved.wd.begin() + lo, saved.wd.begin() + hi, st.wd.begin() + lo);
    std::copy(saved.mobile.begin() + lo, saved.mobile.begin() + hi, st.mobile.begin() + lo);
    std::copy(saved.dir.begin() + lo, saved.dir.begin() + hi, st.dir.begin() + lo);
    st.t = 0;
  }
  bkq::Ranges ranges() const { return bkq::Ranges(&range, 1); }
  // One step of the engine's held or general path (engine/event_engine.cpp): the
  // stepper, then the power and the stick rule over the range. Returns the blocks
  // sliding after it.
  int engine_step(bool held) {
    std::copy(st.wd.begin() + range.lo, st.wd.begin() + range.hi, old.begin() + range.lo);
    if (held)
      stepper->step_held(forces, frozen, st, kDt, ranges());
    else
      stepper->step(forces, frozen, st, kDt, ranges());
    dissipated += 0.5 * kDt * p.m_u * bkq::dissipated_power(forces, st, old.data(), ranges());
    const bkq::ContactScan scan =
        bkq::settle_contacts(forces, st, old.data(), 0.0, ranges(), true, [&](int) { ++releases; });
    return scan.sliding;
  }
  // The register cluster for `steps` steps; returns its sliding block-steps.
  std::int64_t cluster_run() {
    bkq::ClusterRelaxation r;
    r.lo = range.lo;
    r.k = k;
    r.anchor = 0.0;
    r.sub = bkq::SubstrateState{0.0, 0.0, 0.0};
    r.dt = kDt;
    r.half_dt_m = 0.5 * kDt * p.m_u;
    r.max_steps = steps;
    r.state = &st;
    r.dissipated = &dissipated;
    if (!stepper->traits().cluster_kernel(forces, r) || r.steps != steps) return -1;
    return r.sliding_block_steps;
  }
  // Does every block slide through the M steps, on the general path?
  bool slides_throughout() {
    restore();
    bool ok = true;
    for (int s = 0; s < steps; ++s) ok = ok && engine_step(false) == k && releases == 0;
    restore();
    return ok;
  }

  int k, n;
  bkq::ModelParams p;
  bkq::ChainForces forces;
  std::unique_ptr<bkq::Stepper> stepper;
  bkq::Range range;
  bkq::Substrate frozen = bkq::Substrate::frozen(0.0);
  int steps = 0;  // M
  bkq::ChainState saved, st;
  std::vector<double> old;
  double dissipated = 0;
  std::int64_t releases = 0;
};

void report(benchmark::State& state, const ClusterScene& scene, double sliding_block_steps) {
  state.counters["ns_per_block_step"] = benchmark::Counter(
      sliding_block_steps * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["steps_per_restart"] = scene.steps;
}

// Runs `body` (M steps) after a restore each iteration.
template <class Body>
void run_kernel(benchmark::State& state, Body&& body) {
  ClusterScene scene(static_cast<int>(state.range(0)));
  if (!scene.slides_throughout()) {
    state.SkipWithError("the blocks do not all slide through the measured steps");
    return;
  }
  double sliding = 0;
  for (auto _ : state) {
    scene.restore();
    body(scene);
    sliding += static_cast<double>(scene.k) * scene.steps;
  }
  benchmark::DoNotOptimize(scene.st.w.data());
  report(state, scene, sliding);
}

void BM_Cluster(benchmark::State& state) {
  ClusterScene probe(static_cast<int>(state.range(0)));
  if (probe.cluster_run() != static_cast<std::int64_t>(probe.k) * probe.steps) {
    state.SkipWithError("the cluster path did not take all the steps with every block sliding");
    return;
  }
  run_kernel(state, [](ClusterScene& s) { benchmark::DoNotOptimize(s.cluster_run()); });
}

void BM_Held(benchmark::State& state) {
  run_kernel(state, [](ClusterScene& s) {
    for (int i = 0; i < s.steps; ++i)
      s.stepper->step_held(s.forces, s.frozen, s.st, kDt, s.ranges());
  });
}

void BM_HeldContacts(benchmark::State& state) {
  run_kernel(state, [](ClusterScene& s) {
    for (int i = 0; i < s.steps; ++i) benchmark::DoNotOptimize(s.engine_step(true));
  });
}

void BM_General(benchmark::State& state) {
  run_kernel(state, [](ClusterScene& s) {
    for (int i = 0; i < s.steps; ++i) s.stepper->step(s.forces, s.frozen, s.st, kDt, s.ranges());
  });
}

void BM_GeneralContacts(benchmark::State& state) {
  run_kernel(state, [](ClusterScene& s) {
    for (int i = 0; i < s.steps; ++i) benchmark::DoNotOptimize(s.engine_step(false));
  });
}

void BM_Restore(benchmark::State& state) {
  run_kernel(state, [](ClusterScene& s) { benchmark::DoNotOptimize(s.st.w.data()); });
}

// The bound: RK4's stages over k blocks between two fixed ends as plain loops, the
// accelerations as the kernels form them (interior_force, the clst91 magnitude, f/m - phi)
// and rk4.hpp's updates (blocks fused), the stage points double-buffered. Out of line
// with restrict parameters so that each stage vectorises.
struct MinimalConstants {
  double k_p, k_c, inv_m, kinetic0, inv_scale, anchor;
};

[[gnu::noinline]] void minimal_rk4_steps(int k, int steps, double h, const MinimalConstants& c,
                                         double* __restrict w, double* __restrict v,
                                         double* __restrict xa, double* __restrict ya,
                                         double* __restrict xb, double* __restrict yb,
                                         double* __restrict cw, double* __restrict cv) {
  const double k_p = c.k_p, k_c = c.k_c, inv_m = c.inv_m, kinetic0 = c.kinetic0,
               inv_scale = c.inv_scale, anchor = c.anchor;
  const double h2 = 0.5 * h, h6 = h / 6.0;
  auto acc = [&](const double* x, const double* y, int i) {
    const double f = k_p * (anchor - x[i]) + k_c * (x[i - 1] - 2.0 * x[i] + x[i + 1]);
    return f * inv_m - kinetic0 / std::fma(std::max(y[i], 0.0), inv_scale, 1.0);
  };
  // The second and third stages: from the point (xs, ys) to the next at h c.
  auto middle = [&](double c, const double* __restrict xs, const double* __restrict ys,
                    double* __restrict xo, double* __restrict yo) {
    for (int i = 1; i <= k; ++i) {
      const double a = acc(xs, ys, i);
      cw[i] += 2.0 * ys[i];
      cv[i] += 2.0 * a;
      xo[i] = std::fma(c, ys[i], w[i]);
      yo[i] = std::fma(c, a, v[i]);
    }
  };
  for (int s = 0; s < steps; ++s) {
    for (int i = 1; i <= k; ++i) {
      const double a = acc(w, v, i);
      cw[i] = v[i];
      cv[i] = a;
      xa[i] = std::fma(h2, v[i], w[i]);
      ya[i] = std::fma(h2, a, v[i]);
    }
    middle(h2, xa, ya, xb, yb);
    middle(h, xb, yb, xa, ya);
    for (int i = 1; i <= k; ++i) {
      const double a = acc(xa, ya, i);
      w[i] += h6 * (cw[i] + ya[i]);
      v[i] = std::fma(h6, cv[i] + a, v[i]);
    }
  }
}

// The scene's numbers as the minimal loops take them (the anchor at 0).
MinimalConstants minimal_constants(const ClusterScene& scene) {
  const bkq::law::Clst91& law = scene.forces.law<bkq::law::Clst91>();
  return {scene.p.k_p, scene.p.k_c, 1.0 / scene.p.m_u, law.kinetic0, law.inv_scale, 0.0};
}

// The minimal loop from the same start, run on without restarts (it has no stick test:
// the blocks oscillate about the anchor, the same operations whatever the values).
void BM_Minimal(benchmark::State& state) {
  ClusterScene scene(static_cast<int>(state.range(0)));
  const int k = scene.k, lo = scene.range.lo;
  const MinimalConstants c = minimal_constants(scene);
  std::vector<double> w(scene.saved.w.begin() + lo, scene.saved.w.begin() + lo + k + 2),
      v(k + 2, 0.0), xa = w, ya(k + 2, 0.0), xb = w, yb(k + 2, 0.0), cw(k + 2), cv(k + 2);
  double sliding = 0;
  for (auto _ : state) {
    minimal_rk4_steps(k, scene.steps, kDt, c, w.data(), v.data(), xa.data(), ya.data(), xb.data(),
                      yb.data(), cw.data(), cv.data());
    sliding += static_cast<double>(k) * scene.steps;
  }
  benchmark::DoNotOptimize(w.data());
  report(state, scene, sliding);
  state.counters["flops_per_block_step"] = kFlopsPerBlockStep;
  state.counters["divisions_per_block_step"] = kDivisionsPerBlockStep;
}

// The same with the blocks in registers (K a constant, the loops unrolled), as the
// register cluster holds them: at small K the bound is then the latency of the chain each
// stage forms (the stage velocity, the law's fma and division, the acceleration, the
// next stage velocity), not the loops' overheads.
template <int K>
[[gnu::noinline]] void minimal_registers(int steps, double h, const MinimalConstants& c,
                                         double* w_io, double* v_io) {
  const double k_p = c.k_p, k_c = c.k_c, inv_m = c.inv_m, kinetic0 = c.kinetic0,
               inv_scale = c.inv_scale, anchor = c.anchor;
  const double h2 = 0.5 * h, h6 = h / 6.0;
  using Array = std::array<double, K + 2>;
  Array w, v, x, y, cw, cv;
  for (int i = 0; i < K + 2; ++i) w[i] = w_io[i], v[i] = v_io[i];
  x = w;
  y = v;
  auto acc = [&](const Array& p, const Array& q, int i) {
    const double f = k_p * (anchor - p[i]) + k_c * (p[i - 1] - 2.0 * p[i] + p[i + 1]);
    return f * inv_m - kinetic0 / std::fma(std::max(q[i], 0.0), inv_scale, 1.0);
  };
  // The second and third stages: from the point (x, y) to the next at h c.
  auto middle = [&](double c) {
    Array xn = x, yn = y;
    for (int i = 1; i <= K; ++i) {
      const double a = acc(x, y, i);
      cw[i] += 2.0 * y[i];
      cv[i] += 2.0 * a;
      xn[i] = std::fma(c, y[i], w[i]);
      yn[i] = std::fma(c, a, v[i]);
    }
    x = xn;
    y = yn;
  };
  for (int s = 0; s < steps; ++s) {
    Array xn = x, yn = y;
    for (int i = 1; i <= K; ++i) {
      const double a = acc(w, v, i);
      cw[i] = v[i];
      cv[i] = a;
      xn[i] = std::fma(h2, v[i], w[i]);
      yn[i] = std::fma(h2, a, v[i]);
    }
    x = xn;
    y = yn;
    middle(h2);
    middle(h);
    for (int i = 1; i <= K; ++i) {
      const double a = acc(x, y, i);
      w[i] += h6 * (cw[i] + y[i]);
      v[i] = std::fma(h6, cv[i] + a, v[i]);
    }
    x = w;
    y = v;
  }
  for (int i = 0; i < K + 2; ++i) w_io[i] = w[i], v_io[i] = v[i];
}

void BM_MinimalRegisters(benchmark::State& state) {
  ClusterScene scene(static_cast<int>(state.range(0)));
  const int k = scene.k, lo = scene.range.lo;
  const MinimalConstants c = minimal_constants(scene);
  std::vector<double> w(scene.saved.w.begin() + lo, scene.saved.w.begin() + lo + k + 2),
      v(k + 2, 0.0);
  auto run = [&]<int K>() { minimal_registers<K>(scene.steps, kDt, c, w.data(), v.data()); };
  double sliding = 0;
  for (auto _ : state) {
    switch (k) {
      case 1:
        run.template operator()<1>();
        break;
      case 2:
        run.template operator()<2>();
        break;
      case 4:
        run.template operator()<4>();
        break;
      default:
        run.template operator()<8>();
        break;
    }
    sliding += static_cast<double>(k) * scene.steps;
  }
  benchmark::DoNotOptimize(w.data());
  report(state, scene, sliding);
}

// The law's division alone: as a dependent chain (y = kinetic0 / (1 + y s), its fma and
// division one after the other: a lone block's stage waits on it) and over 1024
// independent values (a vector loop, the division units' throughput). Counter: ns per
// division.
void BM_DivisionChain(benchmark::State& state) {
  double y = 0.3;
  const double kinetic0 = 0.99, s = 5.05;
  double divisions = 0;
  for (auto _ : state) {
    for (int i = 0; i < 1000; ++i) y = kinetic0 / std::fma(y, s, 1.0);
    benchmark::DoNotOptimize(y);
    divisions += 1000;
  }
  state.counters["ns_per_division"] = benchmark::Counter(
      divisions * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

[[gnu::noinline]] void divide_all(int n, double* __restrict y, double kinetic0, double s) {
  for (int i = 0; i < n; ++i) y[i] = kinetic0 / std::fma(y[i], s, 1.0);
}

void BM_DivisionThroughput(benchmark::State& state) {
  std::vector<double> y(1024, 0.3);
  double divisions = 0;
  for (auto _ : state) {
    divide_all(1024, y.data(), 0.99, 5.05);
    benchmark::DoNotOptimize(y.data());
    divisions += 1024;
  }
  state.counters["ns_per_division"] = benchmark::Counter(
      divisions * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void all_sizes(benchmark::internal::Benchmark* b) {
  for (int k : {1, 2, 4, 8, 10, 16, 32, 100, 1000}) b->Arg(k);
  b->MinTime(0.2);
}
void cluster_sizes(benchmark::internal::Benchmark* b) {
  for (int k : {1, 2, 4, 8}) b->Arg(k);
  b->MinTime(0.2);
}

BENCHMARK(BM_Cluster)->Apply(cluster_sizes);
BENCHMARK(BM_Held)->Apply(all_sizes);
BENCHMARK(BM_HeldContacts)->Apply(all_sizes);
BENCHMARK(BM_General)->Apply(all_sizes);
BENCHMARK(BM_GeneralContacts)->Apply(all_sizes);
BENCHMARK(BM_Minimal)->Apply(all_sizes);
BENCHMARK(BM_MinimalRegisters)->Apply(cluster_sizes);
BENCHMARK(BM_Restore)->Apply(all_sizes);
BENCHMARK(BM_DivisionChain)->MinTime(0.2);
BENCHMARK(BM_DivisionThroughput)->MinTime(0.2);

// The console output, then the counters side by side: a row per cluster size, a column
// per kernel (the median where there are repetitions), and the division's costs.
class TableReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      const bool aggregate = run.run_type == Run::RT_Aggregate;
      if (aggregate && run.aggregate_name != "median") continue;
      const std::string kernel = run.run_name.function_name.substr(3);  // less "BM_"
      const int k = std::atoi(run.run_name.args.c_str());
      for (const char* counter : {"ns_per_block_step", "ns_per_division"}) {
        const auto it = run.counters.find(counter);
        if (it == run.counters.end()) continue;
        Cell& cell = cells_[kernel][k];
        if (aggregate) cell = Cell{{it->second.value}, true};
        if (!cell.median) cell.values.push_back(it->second.value);
      }
    }
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    const char* order[] = {"Cluster",         "Held",    "HeldContacts",     "General",
                           "GeneralContacts", "Minimal", "MinimalRegisters", "Restore"};
    std::printf(
        "\nns per sliding block-step, RK4 at dt = %g, carlson-langer clst91 (the bound, Minimal: "
        "%d flops and %d divisions per block-step)\n\n| k |",
        kDt, kFlopsPerBlockStep, kDivisionsPerBlockStep);
    for (const char* kernel : order) std::printf(" %s |", kernel);
    std::printf("\n|---|");
    for (std::size_t i = 0; i < std::size(order); ++i) std::printf("---|");
    std::printf("\n");
    for (int k : {1, 2, 4, 8, 10, 16, 32, 100, 1000}) {
      std::printf("| %d |", k);
      for (const char* kernel : order) {
        const double v = value(kernel, k);
        if (v == v)
          std::printf(" %.3g |", v);
        else
          std::printf(" |");
      }
      std::printf("\n");
    }
    std::printf(
        "\nthe law's division (with its fma): %.3g ns in a dependent chain, %.3g ns each "
        "over 1024 independent values\n",
        value("DivisionChain", 0), value("DivisionThroughput", 0));
    std::fflush(stdout);
  }

 private:
  struct Cell {
    std::vector<double> values;
    bool median = false;
  };
  // The median of the runs (NaN if none).
  double value(const std::string& kernel, int k) const {
    const auto column = cells_.find(kernel);
    if (column == cells_.end() || column->second.count(k) == 0) return std::nan("");
    std::vector<double> v = column->second.at(k).values;
    std::sort(v.begin(), v.end());
    return v.empty() ? std::nan("") : v[v.size() / 2];
  }
  std::map<std::string, std::map<int, Cell>> cells_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  TableReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
