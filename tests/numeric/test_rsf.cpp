// Rate-and-state friction: the law (model/laws/rsf.hpp), the cycle integrator
// (engine/rsf_cycle.hpp) and the linear stability (stats/rsf_stability.hpp) against QDYN's
// stick-slip case, the velocity step's closed forms, the steady-state fixed point, the
// linearisation's eigenvalues, the single block in an uncoupled chain, and the two forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "engine/rsf_cycle.hpp"
#include "model/laws/rsf.hpp"
#include "stats/rsf_stability.hpp"
#include "stats/stability.hpp"
#include "support/qdyn_stickslip.hpp"

namespace bkq {
namespace {

// QDYN's test "stickslip" (frozen reference 5ba3c6b008): support/qdyn_stickslip.hpp.
RsfModel qdyn_model(int n = 1) {
  return test::qdyn_stickslip(n);
}

// The limit cycle of one block: slip-rate peaks (times) and the extremes of tau/sigma, both
// located inside the steps on the Hermite cubic of the step's ends (values and derivatives).
struct Cycles {
  std::vector<double> peaks;
  double f_min = 1e300, f_max = -1e300;
  double period() const {
    std::vector<double> d;
    for (std::size_t i = 1; i < peaks.size(); ++i) d.push_back(peaks[i] - peaks[i - 1]);
    std::sort(d.begin(), d.end());
    return d.size() % 2 ? d[d.size() / 2] : 0.5 * (d[d.size() / 2 - 1] + d[d.size() / 2]);
  }
};

// f and df/dt of block j from a state and its derivative.
std::pair<double, double> f_and_rate(const RsfModel& m, const std::vector<double>& y,
                                     const std::vector<double>& dy, int j) {
  const int n = m.n();
  const rsf::FrictionValue fr = m.law[j].friction(m.form, y[n + j], y[2 * n + j]);
  return {fr.f, fr.f_lnv * dy[n + j] + fr.f_lntheta * dy[2 * n + j]};
}

// Integrates to t_end, recording block j's cycles after `skip` peaks (the transient).
Cycles run_cycles(RsfCycle& c, double t_end, int j = 0, int skip = 2) {
  Cycles out;
  const RsfModel& m = c.model();
  const int n = c.n();
  int seen = 0;
  while (c.t() < t_end) {
    c.step(t_end);
    const auto& y0 = c.y_prev();
    const auto& d0 = c.dy_prev();
    const auto& y1 = c.y();
    const auto& d1 = c.dy();
    if (d0[n + j] > 0 && d1[n + j] <= 0) {
      const Extremum e =
          hermite_extremum(c.t_prev(), y0[n + j], d0[n + j], c.t(), y1[n + j], d1[n + j]);
      if (++seen > skip) out.peaks.push_back(e.t);
    }
    if (seen < skip) continue;
    const auto [fa, ra] = f_and_rate(m, y0, d0, j);
    const auto [fb, rb] = f_and_rate(m, y1, d1, j);
    out.f_min = std::min({out.f_min, fa, fb});
    out.f_max = std::max({out.f_max, fa, fb});
    if ((ra > 0) != (rb > 0)) {
      const double x = hermite_extremum(c.t_prev(), fa, ra, c.t(), fb, rb).x;
      out.f_min = std::min(out.f_min, x);
      out.f_max = std::max(out.f_max, x);
    }
  }
  return out;
}

TEST(RsfCycle, QdynStickSlipPeriodAndStressExtremes) {
  // QDYN's frozen run starts at V = 2e-5 m/s, theta = D_c/V_pl; 1e4 s is 17 cycles.
  RsfCycle c(qdyn_model(), 1e-9, {2e-5}, {1e-5 / 1e-6});
  const Cycles cy = run_cycles(c, 1e4);
  ASSERT_GE(cy.peaks.size(), 10u);
  const double period = cy.period();
  std::printf(
      "QDYN stickslip: period %.6f s (QDYN 585.48), tau/sigma %.7f .. %.7f (QDYN 0.41166 "
      ".. 0.67887), %lld steps (%lld rejected) in 1e4 s\n",
      period, cy.f_min, cy.f_max, static_cast<long long>(c.accepted()),
      static_cast<long long>(c.rejected()));
  EXPECT_NEAR(period / 585.48, 1, 1e-4);
  EXPECT_NEAR(cy.f_min / 0.41166, 1, 1e-4);
  EXPECT_NEAR(cy.f_max / 0.67887, 1, 1e-4);
}

// The velocity step V1 -> V2 imposed (lab convention): the direct effect a ln(V2/V1), then
// the state's evolution over D_c against the closed forms. Returns the largest error of mu.
double velocity_step_error(rsf::StateLaw law, double tol, double* jump = nullptr) {
  RsfModel m = qdyn_model();
  m.dynamics = RsfDynamics::ImposedRate;
  m.state_law = law;
  const rsf::Params& p = m.law[0].params();
  const double v1 = 1e-6, v2 = 1e-5, theta0 = p.dc / v1;
  RsfCycle c(m, tol, {v2}, {theta0});
  const auto mu = [&](double theta) {
    return p.mu0 + p.a * std::log(v2 / p.v0) + p.b_rsf * std::log(p.v0 * theta / p.dc);
  };
  if (jump) *jump = c.friction_stress(0) / m.sigma - m.law[0].steady_friction(m.form, v1);
  double worst = 0;
  const double t_d = p.dc / v2;
  // At the integrator's own steps (sampling on a fixed grid would cap the step size).
  while (c.t() < 10 * t_d) {
    c.step(10 * t_d);
    const double t = c.t();
    double theta;
    if (law == rsf::StateLaw::Aging) {
      theta = p.dc / v2 + (theta0 - p.dc / v2) * std::exp(-v2 * t / p.dc);
    } else {
      theta = p.dc / v2 * std::exp(std::log(theta0 * v2 / p.dc) * std::exp(-v2 * t / p.dc));
    }
    worst = std::max(worst, std::fabs(c.friction_stress(0) / m.sigma - mu(theta)));
  }
  return worst;
}

TEST(RsfCycle, VelocityStepMatchesClosedFormForBothStateLaws) {
  for (rsf::StateLaw law : {rsf::StateLaw::Aging, rsf::StateLaw::Slip}) {
    double jump = 0;
    const double loose = velocity_step_error(law, 1e-5, &jump);
    const double tight = velocity_step_error(law, 1e-9);
    std::printf("velocity step (%s law): max |mu - closed form| %.3e at tol 1e-5, %.3e at 1e-9\n",
                law == rsf::StateLaw::Aging ? "aging" : "slip", loose, tight);
    EXPECT_NEAR(jump, 0.01 * std::log(10.0), 1e-14);  // a ln(V2/V1)
    EXPECT_LT(loose, 1e-6);
    EXPECT_LT(tight, 1e-10);
    EXPECT_LT(tight, loose / 10);  // the error falls with the tolerance
  }
}

TEST(RsfCycle, SteadySlidingAtPlateRateIsAFixedPoint) {
  // Both sides of k_crit: QDYN's unstable k and a stable 2 k_crit; the derivative vanishes, so
  // only rounding can move the state, and the unstable case amplifies it by e^{0.055 t}.
  for (double k : {2e9, 1.5e10}) {
    RsfModel m = qdyn_model();
    m.k = k;
    RsfCycle c(m, 1e-8, {m.v_pl}, {m.law[0].params().dc / m.v_pl});
    c.advance_to(100);
    EXPECT_NEAR(c.ln_v(0), std::log(m.v_pl), 1e-10) << "k = " << k;
    EXPECT_NEAR(c.ln_theta(0), std::log(10.0), 1e-10) << "k = " << k;
    EXPECT_NEAR(c.slip(0), 100 * m.v_pl, 1e-15) << "k = " << k;
  }
}

TEST(RsfStability, CriticalStiffnessClosedForms) {
  RsfModel m = qdyn_model();
  const double ruina = 5e6 * (0.025 - 0.01) / 1e-5;  // sigma (b - a)/D_c = 7.5e9 Pa/m
  EXPECT_DOUBLE_EQ(rsf::critical_stiffness(m.law[0].params(), m.sigma), ruina);
  // Radiation damping lowers it by eta V_pl/D_c.
  EXPECT_NEAR(rsf_critical_stiffness(m), ruina - m.eta * m.v_pl / 1e-5, 1e-6 * ruina);
  m.eta = 0;
  EXPECT_NEAR(rsf_critical_stiffness(m), ruina, 1e-9 * ruina);
  // Rice & Ruina 1983: inertia raises it by the factor 1 + m V^2/(sigma a D_c).
  m.dynamics = RsfDynamics::Inertial;
  m.mass = 1e9;
  const double factor = 1 + m.mass * 1e-12 / (5e6 * 0.01 * 1e-5);
  EXPECT_NEAR(rsf_critical_stiffness(m), ruina * factor, 1e-9 * ruina * factor);
  // At k_crit the cubic's leading pair sits on the imaginary axis at the stated frequency.
  const auto roots = rsf_eigenvalues(m, rsf_critical_stiffness(m));
  EXPECT_NEAR(roots[0].real(), 0, 1e-9 * std::abs(roots[0]));
  EXPECT_NEAR(std::abs(roots[0].imag()) / (2 * std::numbers::pi), rsf_critical_frequency(m),
              1e-9 * rsf_critical_frequency(m));
}

// Around steady sliding at 0.9 and 1.1 k_crit a small perturbation grows or decays at the
// linearisation's rate and oscillates at its frequency.
TEST(RsfStability, PerturbationGrowsBelowAndDecaysAboveCriticalStiffness) {
  for (double ratio : {0.9, 1.1}) {
    RsfModel m = qdyn_model();
    m.k = ratio * rsf_critical_stiffness(m);
    const std::complex<double> lambda = rsf_eigenvalues(m, m.k)[0];
    ASSERT_GT(std::fabs(lambda.imag()), 0);
    const double period = 2 * std::numbers::pi / std::fabs(lambda.imag());
    RsfCycle c(m, 1e-10, {m.v_pl * (1 + 1e-5)}, {m.law[0].params().dc / m.v_pl});
    std::vector<double> t, x;
    for (int i = 1; i <= 4000; ++i) {
      c.advance_to(i * period / 400);
      t.push_back(c.t());
      x.push_back(c.ln_v(0) - std::log(m.v_pl));
    }
    const GrowthFit fit = fit_growth(t, x);
    const double f_lin = std::fabs(lambda.imag()) / (2 * std::numbers::pi);
    std::printf("k = %.1f k_crit: growth %.6e (linear %.6e), frequency %.6e (linear %.6e)\n", ratio,
                fit.growth, lambda.real(), fit.frequency, f_lin);
    EXPECT_EQ(fit.growth > 0, ratio < 1);
    EXPECT_EQ(lambda.real() > 0, ratio < 1);
    EXPECT_NEAR(fit.frequency / f_lin, 1, 0.01);
    EXPECT_NEAR(fit.growth / lambda.real(), 1, 0.05);
  }
}

// The inertial block (Rice & Ruina 1983): a mass large enough to raise k_crit by half, so that
// 0.9 and 1.1 of the corrected k_crit both lie above the quasi-static sigma (b - a)/D_c. The
// quasi-static analysis would call both stable; the first grows, at the cubic's root.
TEST(RsfStability, InertiaRaisesTheCriticalStiffnessAsPredicted) {
  for (double ratio : {0.9, 1.1}) {
    RsfModel m = qdyn_model();
    m.eta = 0;
    m.dynamics = RsfDynamics::Inertial;
    m.mass = 2.5e11;  // m V_pl^2/(sigma a D_c) = 0.5
    const double k_static = rsf::critical_stiffness(m.law[0].params(), m.sigma);
    ASSERT_NEAR(rsf_critical_stiffness(m) / k_static, 1.5, 1e-12);
    m.k = ratio * rsf_critical_stiffness(m);
    ASSERT_GT(m.k, k_static);
    const std::complex<double> lambda = rsf_eigenvalues(m, m.k)[0];
    const double period = 2 * std::numbers::pi / std::fabs(lambda.imag());
    RsfCycle c(m, 1e-10, {m.v_pl * (1 + 1e-5)}, {m.law[0].params().dc / m.v_pl});
    std::vector<double> t, x;
    for (int i = 1; i <= 4000; ++i) {
      c.advance_to(i * period / 400);
      t.push_back(c.t());
      x.push_back(c.ln_v(0) - std::log(m.v_pl));
    }
    const GrowthFit fit = fit_growth(t, x);
    const double f_lin = std::fabs(lambda.imag()) / (2 * std::numbers::pi);
    std::printf(
        "inertial, k = %.1f k_crit: growth %.6e (linear %.6e), frequency %.6e (linear "
        "%.6e)\n",
        ratio, fit.growth, lambda.real(), fit.frequency, f_lin);
    EXPECT_EQ(fit.growth > 0, ratio < 1);
    EXPECT_NEAR(fit.frequency / f_lin, 1, 0.01);
    EXPECT_NEAR(fit.growth / lambda.real(), 1, 0.05);
  }
}

TEST(RsfCycle, UncoupledChainReproducesTheSingleBlock) {
  // Same start on every block: every block takes the single block's steps, bit for bit.
  RsfCycle one(qdyn_model(1), 1e-8, {2e-5}, {10});
  RsfCycle three(qdyn_model(3), 1e-8, {2e-5}, {10});
  one.advance_to(2000);
  three.advance_to(2000);
  for (int j = 0; j < 3; ++j) {
    EXPECT_EQ(three.ln_v(j), one.ln_v(0));
    EXPECT_EQ(three.ln_theta(j), one.ln_theta(0));
    EXPECT_EQ(three.slip(j), one.slip(0));
  }
  // Different starts: each block keeps its own cycle, which is the single block's limit cycle.
  const std::vector<double> starts = {2e-5, 1e-7, 3e-6};
  RsfCycle single(qdyn_model(1), 1e-9, {2e-5}, {10});
  const Cycles ref = run_cycles(single, 6000);
  for (int j = 0; j < 3; ++j) {
    RsfCycle c(qdyn_model(3), 1e-9, starts, {10});
    const Cycles cy = run_cycles(c, 6000, j);
    EXPECT_NEAR(cy.period() / ref.period(), 1, 1e-6) << "block " << j;
    EXPECT_NEAR(cy.f_min / ref.f_min, 1, 1e-6) << "block " << j;
    EXPECT_NEAR(cy.f_max / ref.f_max, 1, 1e-6) << "block " << j;
  }
}

TEST(RsfLaw, RegularisedAndLogFormsAgreeWhereFrictionFarExceedsA) {
  const rsf::Law law(rsf::Params{});
  const double ln_theta = std::log(10.0);
  for (double v : {1e-9, 1e-6, 1e-3, 1.0}) {
    const auto lg = law.friction(rsf::Form::Log, std::log(v), ln_theta);
    const auto rg = law.friction(rsf::Form::Regularised, std::log(v), ln_theta);
    EXPECT_NEAR(rg.f, lg.f, 1e-12) << v;
    EXPECT_NEAR(rg.f_lnv, lg.f_lnv, 1e-12) << v;
    EXPECT_NEAR(rg.f_lntheta, lg.f_lntheta, 1e-12) << v;
  }
  // Where the log form reaches 0 (V far below V*), the regularised one is a asinh(1/2) > 0.
  const rsf::Params p;
  const double v_zero = p.v0 * std::exp(-(p.mu0 + p.b_rsf * std::log(p.v0 * 10 / p.dc)) / p.a);
  EXPECT_NEAR(law.friction(rsf::Form::Log, std::log(v_zero), ln_theta).f, 0, 1e-12);
  EXPECT_NEAR(law.friction(rsf::Form::Regularised, std::log(v_zero), ln_theta).f,
              p.a * std::asinh(0.5), 1e-12);
  // And the QDYN cycle comes out the same with either form.
  RsfModel m = qdyn_model();
  m.form = rsf::Form::Regularised;
  RsfCycle reg(m, 1e-9, {2e-5}, {10});
  RsfCycle lg(qdyn_model(), 1e-9, {2e-5}, {10});
  const Cycles a = run_cycles(reg, 4000), b = run_cycles(lg, 4000);
  EXPECT_NEAR(a.period() / b.period(), 1, 1e-7);
  EXPECT_NEAR(a.f_min / b.f_min, 1, 1e-7);
}

}  // namespace
}  // namespace bkq
