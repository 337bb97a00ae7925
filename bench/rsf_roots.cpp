// The event-driven rate-and-state engine's closed forms call by call (model/rsf_nucleation.hpp):
// CPU nanoseconds per rsf::clocks, rsf::time_to_omega, rsf::evolve and rsf::slip, and per what
// RsfLoader::schedule asks of a block (clocks to V_h and to half a creep quantum, and for a
// locked velocity-weakening block the time to V theta/D_c = 1/10), over sets of slider states
// the engine meets. The sliders are chain-events.ini's and the 16 x 8 lattice's (QDYN's block:
// a = 0.01, b = 0.025, D_c = 10 um, sigma = 5 MPa, k = 2e9 Pa/m, k_eff = 6e9 Pa/m, V_pl = 1 um/s,
// V_h = 3 V_pl, q = D_c/10) and its barrier (a and b swapped), and the same at V_pl = 1 nm/s
// (chain100-asperities.ini's plate rate). The states, log-uniform in each set:
//   VW locked, far      Omega = V theta/D_c in [1e-6, 1e-2], theta in [1, 1e3] s (times the
//                       plate's slowness 1 um/s / V_pl): just after an event;
//   VW locked, near     Omega in [1e-2, 0.99]: healing towards nucleation;
//   VW nucleating       Omega in [1, 100], V in [0.1, 100] V_pl;
//   VS locked           the barrier, Omega in [1e-4, 0.9];
//   VS steady state     the barrier, theta = D_c/V, V in [0.01, 10] V_pl.
// evolve and slip are asked for dt log-uniform in [1e-2, 1e3] s (times the slowness).
// "schedule" is the loader's three calls (clocks, time_to_omega), "one pass" rsf::next_clock,
// which it calls now; "root" is the time to nucleation of the set's locked states alone, by
// rsf::first_root and by the search it replaced (kept here: bracketed by doubling, then Newton
// to a bracket of 1e-15), with the largest relative difference between the two. Each figure is
// the smallest of five timings of `--repeat` passes over `--states` states.
//
//   build/rsf_roots [--states N] [--repeat R]
//     defaults: N = 4096, R = 50

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "model/rsf_nucleation.hpp"
#include "thread_clock.hpp"

namespace {

using namespace bkq;

struct Case {
  rsf::SliderState x;
  double dt = 0;
};

struct Set {
  std::string name;
  rsf::Slider s;
  bool weakening = true;
  std::vector<Case> cases;
};

rsf::Slider slider(bool weakening, double v_pl) {
  rsf::Slider s;
  s.a = weakening ? 0.01 : 0.025;
  s.b_rsf = weakening ? 0.025 : 0.01;
  s.dc = 1e-5;
  s.sigma = 5e6;
  s.stressing_rate = 2e9 * v_pl;
  s.k_eff = 6e9;
  return s;
}

enum class Kind { kFar, kNear, kNucleating, kVsLocked, kVsSteady };

Set make_set(Kind kind, double v_pl, int n, std::mt19937_64& rng) {
  const bool vw = kind == Kind::kFar || kind == Kind::kNear || kind == Kind::kNucleating;
  static const char* names[] = {"VW locked, far", "VW locked, near", "VW nucleating", "VS locked",
                                "VS steady state"};
  Set set{names[static_cast<int>(kind)], slider(vw, v_pl), vw, {}};
  const double slow = 1e-6 / v_pl, dc = set.s.dc;
  std::uniform_real_distribution<double> u(0, 1);
  const auto log_uniform = [&](double lo, double hi) {
    return std::log(lo) + u(rng) * (std::log(hi) - std::log(lo));
  };
  for (int i = 0; i < n; ++i) {
    Case c;
    c.dt = std::exp(log_uniform(1e-2 * slow, 1e3 * slow));
    double ln_omega = 0;
    switch (kind) {
      case Kind::kFar:
        ln_omega = log_uniform(1e-6, 1e-2);
        break;
      case Kind::kNear:
        ln_omega = log_uniform(1e-2, 0.99);
        break;
      case Kind::kNucleating:
        ln_omega = log_uniform(1, 100);
        break;
      case Kind::kVsLocked:
        ln_omega = log_uniform(1e-4, 0.9);
        break;
      case Kind::kVsSteady:
        ln_omega = 0;
        break;
    }
    if (kind == Kind::kNucleating || kind == Kind::kVsSteady) {
      c.x.ln_v = log_uniform(kind == Kind::kVsSteady ? 0.01 * v_pl : 0.1 * v_pl,
                             kind == Kind::kVsSteady ? 10 * v_pl : 100 * v_pl);
      c.x.ln_theta = ln_omega + std::log(dc) - c.x.ln_v;
    } else {
      c.x.ln_theta = log_uniform(1 * slow, 1e3 * slow);
      c.x.ln_v = ln_omega + std::log(dc) - c.x.ln_theta;
    }
    set.cases.push_back(c);
  }
  return set;
}

// The search rsf::first_root replaced: the first t > 0 where f0 + alpha t + beta ln(1 +
// t/theta0) reaches 0, bracketed by doubling, then Newton kept inside the bracket.
double old_first_root(double f0, double alpha, double beta, double theta0) {
  const double never = std::numeric_limits<double>::infinity();
  if (f0 >= 0) return 0;
  const auto f = [&](double t) { return f0 + alpha * t + beta * std::log1p(t / theta0); };
  if (alpha <= 0) return beta > 0 ? theta0 * std::expm1(-f0 / beta) : never;
  double lo = beta < 0 ? std::max(0.0, -beta / alpha - theta0) : 0.0;
  double hi = lo + std::max(theta0, 1 / alpha);
  for (int i = 0; f(hi) <= 0; ++i) {
    if (i > 2000 || !std::isfinite(hi)) return never;
    lo = hi;
    hi *= 2;
  }
  double t = hi;
  for (int i = 0; i < 200; ++i) {
    const double ft = f(t);
    (ft > 0 ? hi : lo) = t;
    double next = t - ft / (alpha + beta / (theta0 + t));
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == t || hi - lo <= 1e-15 * hi) return next;
    t = next;
  }
  return t;
}

volatile double sink = 0;

// CPU ns per call of f over the set's cases, the smallest of five timings.
double ns_per_call(const Set& set, int repeat, const std::function<double(const Case&)>& f) {
  double best = 1e300;
  for (int trial = 0; trial < 5; ++trial) {
    double acc = 0;
    const double t0 = bench::thread_seconds();
    for (int r = 0; r < repeat; ++r)
      for (const Case& c : set.cases) acc += f(c);
    const double t = bench::thread_seconds() - t0;
    sink = sink + acc;
    best = std::min(best, t);
  }
  return 1e9 * best / (static_cast<double>(repeat) * static_cast<double>(set.cases.size()));
}

}  // namespace

int main(int argc, char** argv) {
  int n = 4096, repeat = 50;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--states") == 0 && i + 1 < argc)
      n = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc)
      repeat = std::atoi(argv[++i]);
  }
  const double ln_omega_in = std::log(0.1);
  std::mt19937_64 rng(20261129);
  std::printf("CPU ns per call, %d states a set, smallest of 5 timings of %d passes\n", n, repeat);
  std::printf("%-10s %-17s %9s %9s %9s %9s %9s %9s %9s %9s %9s\n", "V_pl", "states", "clocks",
              "to_omega", "evolve", "slip", "schedule", "one pass", "root old", "root new",
              "max diff");
  for (const double v_pl : {1e-6, 1e-9}) {
    for (const Kind kind :
         {Kind::kFar, Kind::kNear, Kind::kNucleating, Kind::kVsLocked, Kind::kVsSteady}) {
      const Set set = make_set(kind, v_pl, n, rng);
      const rsf::Slider& s = set.s;
      const double ln_vh = std::log(3 * v_pl), amount = 0.5 * 0.1 * s.dc;
      const double t_clocks = ns_per_call(set, repeat, [&](const Case& c) {
        const rsf::Clocks k = rsf::clocks(s, c.x, ln_vh, amount);
        return k.to_speed + k.to_slip;
      });
      const double t_omega = ns_per_call(
          set, repeat, [&](const Case& c) { return rsf::time_to_omega(s, c.x, ln_omega_in); });
      const double t_evolve = ns_per_call(set, repeat, [&](const Case& c) {
        const rsf::SliderState y = rsf::evolve(s, c.x, c.dt);
        return y.ln_v + y.ln_theta;
      });
      const double t_slip =
          ns_per_call(set, repeat, [&](const Case& c) { return rsf::slip(s, c.x, c.dt); });
      // What RsfLoader::schedule computes for a block that nucleates alone (velocity-weakening)
      // or not (the barrier): the earlier clock and whether it is the quantum's.
      const double t_schedule = ns_per_call(set, repeat, [&](const Case& c) {
        const rsf::Clocks k = rsf::clocks(s, c.x, ln_vh, amount);
        double t_vh = k.to_speed;
        if (set.weakening && rsf::locked(s, c.x))
          t_vh = std::min(t_vh, rsf::time_to_omega(s, c.x, ln_omega_in));
        return std::min(t_vh, k.to_slip) + (k.to_slip < t_vh ? 1 : 0);
      });
      const double t_one_pass = ns_per_call(set, repeat, [&](const Case& c) {
        const rsf::NextClock k =
            rsf::next_clock(s, c.x, ln_vh, amount, set.weakening ? ln_omega_in : 0.0);
        return k.time + (k.slip ? 1 : 0);
      });
      // The time to nucleation's root problem of each state (f0 >= 0, not locked: 0 at once).
      const double alpha = s.stressing_rate / (s.a * s.sigma), beta = 1 - s.b_rsf / s.a;
      const auto f0 = [&](const Case& c) { return rsf::ln_omega(s, c.x); };
      const double t_old = ns_per_call(set, repeat, [&](const Case& c) {
        return old_first_root(f0(c), alpha, beta, std::exp(c.x.ln_theta));
      });
      const double t_new = ns_per_call(set, repeat, [&](const Case& c) {
        return rsf::first_root(f0(c), alpha, beta, std::exp(c.x.ln_theta));
      });
      double diff = 0;
      for (const Case& c : set.cases) {
        const double theta0 = std::exp(c.x.ln_theta);
        const double t1 = old_first_root(f0(c), alpha, beta, theta0);
        const double t2 = rsf::first_root(f0(c), alpha, beta, theta0);
        if (t1 != t2) diff = std::max(diff, std::fabs(t2 - t1) / std::fabs(t1));
      }
      std::printf("%-10g %-17s %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1e\n", v_pl,
                  set.name.c_str(), t_clocks, t_omega, t_evolve, t_slip, t_schedule, t_one_pass,
                  t_old, t_new, diff);
    }
  }
  return 0;
}
