// The locked phase's root search (rsf::first_root) against a bisection in long double over a
// wide sweep of its arguments, and the loader's one-pass clocks (rsf::next_clock) against the
// separate calls it stands for (model/rsf_nucleation.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "model/rsf_nucleation.hpp"

namespace bkq {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The first t > 0 where f0 + alpha t + beta ln(1 + t/theta0) reaches 0 (f0 < 0, alpha > 0), by
// bisection in long double: from right of f's minimum (beta < 0), bracketed by doubling.
long double bisected_root(long double f0, long double alpha, long double beta, long double theta0) {
  const auto f = [&](long double t) { return f0 + alpha * t + beta * std::log1p(t / theta0); };
  long double lo = beta < 0 ? std::max(0.0L, -beta / alpha - theta0) : 0.0L;
  long double hi = lo + std::max(theta0, 1 / alpha);
  while (f(hi) <= 0) {
    lo = hi;
    hi *= 2;
  }
  for (int i = 0; i < 200; ++i) {
    const long double mid = 0.5L * (lo + hi);
    if (mid == lo || mid == hi) break;
    (f(mid) > 0 ? hi : lo) = mid;
  }
  return 0.5L * (lo + hi);
}

// Counts of the regimes a sweep went through.
struct Sweep {
  int cases = 0, at_1e12 = 0, far_right = 0, long_heal = 0, linear = 0, logarithmic = 0;

  // first_root against the bisection, to 1e-12 relative or, where f's rounding in doubles (a
  // few ulps of its terms, over its slope at the root) allows less, to that.
  void check(double f0, double alpha, double beta, double theta0) {
    const double t = rsf::first_root(f0, alpha, beta, theta0);
    const long double ref = bisected_root(f0, alpha, beta, theta0);
    const long double log_term = std::fabs(beta) * std::log1p(ref / theta0);
    const long double slope = alpha + beta / (theta0 + ref);
    const long double floor = 8 * std::numeric_limits<double>::epsilon() *
                              (std::fabs(f0) + alpha * ref + log_term) / slope;
    EXPECT_LE(std::fabs(t - ref), std::max(1e-12L * ref, floor))
        << "f0 " << f0 << " alpha " << alpha << " beta " << beta << " theta0 " << theta0 << ": "
        << t << " against " << static_cast<double>(ref);
    ++cases;
    if (floor <= 1e-12L * ref) ++at_1e12;
    if (beta < 0 && -beta / alpha > 1e3 * theta0) ++far_right;  // the minimum far right
    if (ref > 1e3 * theta0) ++long_heal;
    if (alpha * ref > 1e3 * log_term) ++linear;
    if (log_term > 1e3 * alpha * ref) ++logarithmic;
  }

  // Each regime is there, and most of the sweep is held to 1e-12.
  void expect_all_regimes() const {
    EXPECT_GT(far_right, cases / 20);
    EXPECT_GT(long_heal, cases / 20);
    EXPECT_GT(linear, cases / 20);
    EXPECT_GT(logarithmic, cases / 20);
    EXPECT_GT(at_1e12, 0.9 * cases);
  }
};

TEST(RsfRoots, FirstRootAgreesWithBisectionOverAWideSweep) {
  // f0 from next to the root to far from it, alpha from tiny to large, beta of both signs from
  // near 0 to large (beta < 0 with |beta|/alpha >> theta0: the minimum far right), theta0 from
  // 1 us to 3 years: t >> theta0 and << theta0, the log term dominating or negligible.
  const double f0s[] = {-1e-12, -1e-6, -1e-2, -1, -10, -50, -700};
  const double alphas[] = {1e-12, 1e-6, 1e-3, 0.04, 1, 1e3};
  const double betas[] = {-1e3, -10, -2.5, -1.5, -1e-6, -1e-12, 1e-12, 1e-6, 0.6, 10, 1e3};
  const double theta0s[] = {1e-6, 1e-2, 1, 10, 1e4, 1e8};
  Sweep grid;
  for (const double f0 : f0s)
    for (const double alpha : alphas)
      for (const double beta : betas)
        for (const double theta0 : theta0s) grid.check(f0, alpha, beta, theta0);
  grid.expect_all_regimes();
  // And between the grid's points: each argument log-uniform over the same ranges.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0, 1);
  const auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::log(lo) + u(rng) * (std::log(hi) - std::log(lo)));
  };
  Sweep random;
  for (int i = 0; i < 20000; ++i) {
    const double beta = (u(rng) < 0.5 ? -1 : 1) * log_uniform(1e-12, 1e3);
    random.check(-log_uniform(1e-12, 700), log_uniform(1e-12, 1e3), beta, log_uniform(1e-6, 1e8));
  }
  random.expect_all_regimes();
}

TEST(RsfRoots, FirstRootLimits) {
  EXPECT_EQ(rsf::first_root(0, 0.04, -1.5, 10), 0);
  EXPECT_EQ(rsf::first_root(1, 0.04, 0.6, 10), 0);
  EXPECT_DOUBLE_EQ(rsf::first_root(-3, 0.04, 0, 10), 75);  // linear: -f0/alpha
  // No loading: the log term alone, theta0 (e^{-f0/beta} - 1), or never.
  EXPECT_DOUBLE_EQ(rsf::first_root(-3, 0, 0.6, 10), 10 * std::expm1(5.0));
  EXPECT_TRUE(std::isinf(rsf::first_root(-3, 0, -1.5, 10)));
  // Next to the root: t of order -f0/f'(0).
  const double t = rsf::first_root(-1e-15, 0.04, 0.6, 10);
  EXPECT_NEAR(t / (1e-15 / (0.04 + 0.06)), 1, 1e-9);
}

// The QDYN block (a = 0.01, b = 0.025) or its barrier (a and b swapped) on chain-events.ini's
// springs.
rsf::Slider slider(bool weakening) {
  rsf::Slider s;
  s.a = weakening ? 0.01 : 0.025;
  s.b_rsf = weakening ? 0.025 : 0.01;
  s.dc = 1e-5;
  s.sigma = 5e6;
  s.stressing_rate = 2e3;
  s.k_eff = 6e9;
  return s;
}

TEST(RsfRoots, NextClockEqualsTheSeparateCalls) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const double ln_omega_in = std::log(0.1);
  int omega_first = 0, speed_first = 0, slip_first = 0, checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const bool weakening = i % 2 == 0;
    const rsf::Slider s = slider(weakening);
    // Locked far from nucleation to sliding well above steady state, slow to fast.
    const double ln_omega = std::log(1e-6) + u(rng) * std::log(1e8);
    const double ln_v = std::log(1e-10) + u(rng) * std::log(1e6);
    rsf::SliderState x{ln_v, ln_omega + std::log(s.dc) - ln_v};
    if (!weakening && u(rng) < 0.3) x.ln_theta = std::log(s.dc) - x.ln_v;  // steady state
    const double ln_v_target = std::log(3e-6) + (u(rng) < 0.2 ? -5 : 0);
    const double draw = u(rng);
    const double amount = draw < 0.1 ? kInf : draw < 0.15 ? -1e-7 : 1e-8 + 1e-6 * u(rng);
    const double ln_target = u(rng) < 0.7 ? ln_omega_in : 0.0;
    const rsf::NextClock got = rsf::next_clock(s, x, ln_v_target, amount, ln_target);
    // The loader's calls before the one pass.
    double to_speed, to_slip = kInf;
    if (std::isinf(amount)) {
      to_speed = rsf::time_to_speed(s, x, ln_v_target);
    } else {
      const rsf::Clocks c = rsf::clocks(s, x, ln_v_target, amount);
      to_speed = c.to_speed;
      to_slip = c.to_slip;
    }
    double to_omega = kInf;
    if (ln_target < 0 && rsf::locked(s, x)) to_omega = rsf::time_to_omega(s, x, ln_target);
    const double t_vh = std::min(to_speed, to_omega);
    EXPECT_EQ(got.time, std::min(t_vh, to_slip)) << i;
    EXPECT_EQ(got.slip, to_slip < t_vh) << i;
    ++checked;
    if (to_slip < t_vh)
      ++slip_first;
    else if (to_omega < to_speed)
      ++omega_first;
    else
      ++speed_first;
  }
  // Each clock comes first somewhere in the sample.
  EXPECT_GT(omega_first, 1000);
  EXPECT_GT(speed_first, 1000);
  EXPECT_GT(slip_first, 1000);
  EXPECT_EQ(checked, 20000);
}

TEST(RsfRoots, EvolveAndSlipSplitAtTheTimeToNucleation) {
  // evolve and slip tell a locked block's nucleation from the locked form's ln Omega; the
  // state and slip just before and after the time to nucleation (Omega = 1, time_to_omega at
  // ln 1) are those of the split there, continuous across it.
  for (const bool weakening : {true, false}) {
    const rsf::Slider s = slider(weakening);
    for (const double omega0 : {1e-6, 1e-3, 0.5}) {
      const rsf::SliderState x{std::log(omega0 * s.dc / 30), std::log(30.0)};
      const double t_nuc = rsf::time_to_omega(s, x, 0.0);
      ASSERT_GT(t_nuc, 0);
      const rsf::SliderState at = rsf::evolve(s, x, t_nuc);
      EXPECT_NEAR(rsf::ln_omega(s, at), 0, 1e-12);
      for (const double f : {1 - 1e-9, 1 + 1e-9}) {
        const rsf::SliderState y = rsf::evolve(s, x, f * t_nuc);
        EXPECT_NEAR(y.ln_v, at.ln_v, 1e-6);
        EXPECT_NEAR(y.ln_theta, at.ln_theta, 1e-6);
        if (weakening) {
          EXPECT_EQ(rsf::locked(s, y), f < 1);
        }
      }
      EXPECT_EQ(rsf::slip(s, x, (1 - 1e-9) * t_nuc), 0);
      // On past nucleation, short of the instability.
      const double late = t_nuc + std::min(t_nuc, 0.5 * rsf::time_to_speed(s, at, std::log(1e-3)));
      const double split = rsf::slip(s, at, late - t_nuc);
      EXPECT_GT(split, 0);
      EXPECT_NEAR(rsf::slip(s, x, late) / split, 1, 1e-9);
      const rsf::SliderState y = rsf::evolve(s, x, late), z = rsf::evolve(s, at, late - t_nuc);
      EXPECT_NEAR(y.ln_v, z.ln_v, 1e-9);
      EXPECT_NEAR(y.ln_theta, z.ln_theta, 1e-9);
    }
  }
}

}  // namespace
}  // namespace bkq
