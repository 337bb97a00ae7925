// Rayleigh block damping in the simulations: the force kernels apply the
// same damping matrix alpha_M M + beta_K K as the stability analysis (blocks and pad, K with
// k_c, the k_p coupling and the pad row, lab-frame velocities); every scheme's energy
// balance books the damper's work; the explicit schemes' stability limit with damping
// holds on a damped mode of every damping ratio; event runs refuse the damping.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "engine/continuous.hpp"
#include "engine/event_engine.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"

namespace bkq {
namespace {

// A frictionless, otherwise undamped BK-Pad chain (thesis units) with Rayleigh damping.
ModelParams damped_chain(const char* boundary, int n, const char* alpha, const char* beta) {
  Scene s;
  s.set("model.kind", "bkp");
  s.set("model.parameterisation", "thesis");
  s.set("model.boundary", boundary);
  s.set("model.blocks", std::to_string(n));
  s.set("model.damping_ratio", "0");
  s.set("model.rayleigh_alpha", alpha);
  s.set("model.rayleigh_beta", beta);
  s.set("friction.law", "none");
  s.set("drive.mode", "continuous");
  s.validate();
  return settings_from_scene(s).model;
}

// The accelerations equal -M^-1 (K u + C u'), C = alpha_M M + beta_K K, with M, K built here
// as the dense stability analysis builds them (u_j = w_j - s, u'_j = w'_j - v, pad x).
TEST(RayleighDamping, KernelsApplyTheAnalysisDampingMatrix) {
  for (const char* boundary : {"free", "periodic"}) {
    const ModelParams p = damped_chain(boundary, 7, "0.3", "0.02");
    ASSERT_GT(p.k_c, 0.0);
    const ChainForces forces(p);
    ASSERT_TRUE(forces.rayleigh());
    const int n = p.n, d = n + 1;
    std::vector<double> K(d * d, 0.0), M(d, p.m_u);
    auto at = [d](std::vector<double>& a, int i, int j) -> double& { return a[i * d + j]; };
    auto spring = [&](int a, int b, double k) {
      at(K, a, a) += k;
      at(K, b, b) += k;
      at(K, a, b) -= k;
      at(K, b, a) -= k;
    };
    for (int j = 0; j < n; ++j) {
      spring(j, n, p.k_p);
      if (j + 1 < n) spring(j, j + 1, p.k_c);
    }
    if (std::string(boundary) == "periodic") spring(n - 1, 0, p.k_c);
    at(K, n, n) += p.k_p0;
    M[n] = p.m_x;

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<double> w(n), wd(n), mobile(n, 1.0), dir(n, 1.0), a(n);
    const double s = 0.4, v = 0.3, x = 0.2 * U(rng), xd = 0.2 * U(rng);
    double sum_w = 0, sum_wd = 0;
    for (int j = 0; j < n; ++j) {
      w[j] = s + x + U(rng);
      wd[j] = v + U(rng);
      sum_w += w[j];
      sum_wd += wd[j];
    }
    const SubstrateState sub{s, v, 0.0};
    const Range all{0, n};
    forces.block_accelerations(w.data(), wd.data(), mobile.data(), dir.data(), s + x, v + xd, sub,
                               Ranges(&all, 1), a.data());
    const double a_pad = forces.pad_acceleration(x, xd, sum_w, s, sum_wd, v);

    std::vector<double> u(d), ud(d);
    for (int j = 0; j < n; ++j) {
      u[j] = w[j] - s;
      ud[j] = wd[j] - v;
    }
    u[n] = x;
    ud[n] = xd;
    double power = 0;
    for (int i = 0; i < d; ++i) {
      double f = 0, cud = p.rayleigh_alpha * M[i] * ud[i];
      for (int j = 0; j < d; ++j) {
        f += at(K, i, j) * u[j];
        cud += p.rayleigh_beta * at(K, i, j) * ud[j];
      }
      const double expected = -(f + cud) / M[i];
      const double got = i < n ? a[i] : a_pad;
      EXPECT_NEAR(got, expected, 1e-12 * (1 + std::abs(expected))) << boundary << " row " << i;
      power += ud[i] * cud;
    }
    // The power the damping dissipates is u'^T C u'.
    EXPECT_NEAR(forces.rayleigh_power(wd.data(), xd, v), power, 1e-12 * power) << boundary;
  }
}

// Every scheme: a frictionless chain released from a random displacement loses its energy to
// the damping alone, and the run's energy balance (work - dissipated) accounts for it.
TEST(RayleighDamping, EnergyBalanceBooksTheDamperWork) {
  const ModelParams p = damped_chain("free", 20, "0.05", "0.01");
  const ChainForces forces(p);
  for (const char* scheme : {"rk2", "rk4", "verlet", "theta", "adaptive"}) {
    const auto stepper = make_stepper(scheme, p.n, 1e-9);
    const double dt = std::min(0.01, 0.2 * stability_limit(*stepper, p));
    ChainState st;
    st.resize(p.n);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int j = 0; j < p.n; ++j) st.w[j] = 0.05 * U(rng);
    st.x = 0.01;
    ContinuousDriver driver(forces, *stepper, Substrate::constant(0.0), st, dt);
    const double e0 = driver.energy();
    for (int i = 0; i < static_cast<int>(40.0 / dt); ++i) driver.step();
    const EnergyBalance& b = driver.energy_balance();
    // Most of the energy went into the damping, so leaving its work out would show.
    EXPECT_GT(b.dissipated, 0.5 * e0) << scheme;
    EXPECT_LT(std::abs(b.residual(driver.energy())), 2e-3) << scheme;
  }
}

// One step of `scheme` on a single damped block (omega = 1, damping rate c = alpha_M +
// beta_K) as a 2x2 map of (u, u'); its spectral radius.
double amplification(const std::string& scheme, double alpha, double beta, double dt) {
  ModelParams p;
  p.kind = ModelKind::BK;
  p.n = 1;
  p.m_u = 1;
  p.k_p = 1;
  p.law = law_id<law::None>;
  p.rayleigh_alpha = alpha;
  p.rayleigh_beta = beta;
  const ChainForces forces(p);
  const auto stepper = make_stepper(scheme, 1);
  const Range all{0, 1};
  double m[2][2];
  for (int k = 0; k < 2; ++k) {
    ChainState st;
    st.resize(1);
    st.mobile[0] = 1;
    st.w[0] = k == 0 ? 1.0 : 0.0;
    st.wd[0] = k == 1 ? 1.0 : 0.0;
    stepper->step(forces, Substrate::constant(0.0), st, dt, Ranges(&all, 1));
    m[0][k] = st.w[0];
    m[1][k] = st.wd[0];
  }
  const double tr = m[0][0] + m[1][1], det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const std::complex<double> root = std::sqrt(std::complex<double>(tr * tr / 4 - det));
  return std::max(std::abs(tr / 2 + root), std::abs(tr / 2 - root));
}

// The explicit schemes' limit with damping: rate max(omega, c) * dt <= the scheme's damped
// constant keeps every damping ratio stable (rk2: no worse than undamped), and for rk4 the undamped
// constant (2.8) would not (ratio 1/2 is unstable above 2.62).
TEST(RayleighDamping, ExplicitStabilityLimitHoldsAtEveryDampingRatio) {
  for (const std::string scheme : {"rk2", "rk4", "verlet"}) {
    for (double c : {0.02, 0.2, 0.6, 1.0, 1.4, 2.0, 3.0, 10.0, 100.0})
      for (double share : {0.0, 1.0}) {  // c from alpha_M alone or from beta_K alone
        ModelParams p;
        p.kind = ModelKind::BK;
        p.n = 1;
        p.k_p = 1;
        p.rayleigh_alpha = (1 - share) * c;
        p.rayleigh_beta = share * c;
        const auto stepper = make_stepper(scheme, 1);
        const Stepper::TimeStepLimit limit = stepper->time_step_limit(p);
        EXPECT_NEAR(limit.dt * std::max(1.0, c), stepper->damped_stability_constant(), 1e-12);
        EXPECT_NE(limit.why.find("Rayleigh"), std::string::npos) << limit.why;
        // rk2 is not stable on undamped modes at all; its bound accepts the growth
        // sqrt(1 + (omega dt)^4/4) per step at omega dt = 0.5, and damping adds none.
        const double allowed = scheme == "rk2" ? std::sqrt(1 + std::pow(0.5, 4) / 4) : 1.0;
        EXPECT_LE(amplification(scheme, p.rayleigh_alpha, p.rayleigh_beta, limit.dt),
                  allowed + 1e-12)
            << scheme << " c = " << c;
      }
  }
  EXPECT_GT(amplification("rk4", 1.0, 0.0, 2.8), 1.0);
  EXPECT_LE(amplification("rk4", 1.0, 0.0, 2.6), 1.0);
}

TEST(RayleighDamping, EventRunsRefuseIt) {
  ModelParams p = damped_chain("free", 10, "0.1", "0");
  p.law = law_id<law::Thesis>;
  try {
    EventEngine::check_model(p);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("model.rayleigh_alpha = 0.1"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("continuous"), std::string::npos) << e.what();
  }
  p.rayleigh_alpha = 0;
  EXPECT_NO_THROW(EventEngine::check_model(p));
}

}  // namespace
}  // namespace bkq
