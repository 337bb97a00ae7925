// Steady sliding and its linear stability: the equilibrium against its closed
// form, the eigenvalues against the closed forms of thesis eqs. 2.15-2.17 (1DOF) and of the
// chain modes with and without Rayleigh damping, and the exact modal reduction against the
// dense state matrix (eigenvalues one by one, and the bkp pad-mode speed threshold).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <vector>

#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/equilibrium.hpp"
#include "stats/stability.hpp"

namespace bkq {
namespace {

// Thesis Table 3.1 with the thesis law, `kind`, `n` blocks and the given boundary.
ModelParams thesis_model(const char* kind, int n, const char* boundary = "free") {
  Scene s;
  s.set("model.parameterisation", "thesis");
  s.set("friction.law", "thesis");
  s.set("model.kind", kind);
  if (std::string(kind) != "1dof") s.set("model.blocks", std::to_string(n));
  s.set("model.boundary", boundary);
  s.validate();
  return model_from_scene(s);
}

double slope_at(const ModelParams& p, double v) {
  return kinetic_branch(p, v).slope;
}

// The v in [lo, hi] where f changes sign (f(lo) and f(hi) of opposite signs), by bisection.
double root(const std::function<double(double)>& f, double lo, double hi) {
  const bool lo_sign = f(lo) > 0;
  EXPECT_NE(lo_sign, f(hi) > 0) << "no sign change in [" << lo << ", " << hi << "]";
  for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) > 0) == lo_sign ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(SlidingEquilibrium, EqualsItsClosedForm) {
  for (const char* kind : {"bk", "bkp"})
    for (const char* boundary : {"free", "periodic"})
      for (int n : {10, 1000, 100000}) {
        const ModelParams p = thesis_model(kind, n, boundary);
        const double v = 0.1;
        const SlidingEquilibrium e = sliding_equilibrium(p, v);
        ASSERT_TRUE(e.exists());
        const double phi = p.F0 * (1 - p.sigma) / (1 + v / ((1 - p.sigma) * p.v_c));
        EXPECT_DOUBLE_EQ(e.friction.phi, phi);
        const double x = p.pad_moves() ? -n * p.m_u * phi / p.k_p0 : 0.0;
        const double u = x - p.m_u * phi / p.k_p;
        EXPECT_NEAR(e.x, x, 1e-11 * std::abs(x) + 1e-15) << kind << " " << boundary << " " << n;
        double worst = 0;
        for (double uj : e.u) worst = std::max(worst, std::abs(uj - u));
        EXPECT_LT(worst, 1e-10 * std::abs(u)) << kind << " " << boundary << " " << n;
      }
}

TEST(SlidingEquilibrium, SolvesNonUniformLoads) {
  // The O(N) structure against the residual of the static equations themselves.
  for (const char* boundary : {"free", "periodic"}) {
    const ModelParams p = thesis_model("bkp", 37, boundary);
    std::vector<double> f(p.n), u;
    for (int j = 0; j < p.n; ++j) f[j] = std::sin(0.7 * j) + 0.3;
    double x = 0;
    ASSERT_TRUE(solve_static(p, f, u, x));
    double pad = -p.k_p0 * x;
    for (int j = 0; j < p.n; ++j) {
      const bool ring = std::string(boundary) == "periodic";
      const int l = j > 0 ? j - 1 : (ring ? p.n - 1 : -1);
      const int r = j + 1 < p.n ? j + 1 : (ring ? 0 : -1);
      double force = -p.k_p * (u[j] - x);
      if (l >= 0) force += p.k_c * (u[l] - u[j]);
      if (r >= 0) force += p.k_c * (u[r] - u[j]);
      EXPECT_NEAR(force, f[j], 1e-9) << boundary << " block " << j;
      pad += p.k_p * (u[j] - x);
    }
    EXPECT_NEAR(pad, 0.0, 1e-9) << boundary;
  }
}

TEST(SlidingEquilibrium, SaysWhenThereIsNone) {
  const ModelParams p = thesis_model("bkp", 10);
  EXPECT_EQ(sliding_equilibrium(p, 0.0).why, NoEquilibrium::NotSliding);
  ModelParams loose = p;
  loose.k_p0 = 0;
  EXPECT_EQ(sliding_equilibrium(loose, 0.1).why, NoEquilibrium::NoPadSpring);
  ModelParams frictionless = loose;
  frictionless.law = law_id<law::None>;
  EXPECT_TRUE(sliding_equilibrium(frictionless, 0.1).exists());
}

TEST(LinearStability, OneDofIsItsCharacteristicPolynomial) {
  // Thesis eqs. 2.15-2.17 with eta = -m phi'(v): lambda = (eta - c)/2m +- i sqrt(4mk -
  // (eta - c)^2)/2m, from the modal solver and the dense one.
  const ModelParams p = thesis_model("1dof", 1);
  for (double v : {0.05, 0.5, 1.0, 3.0}) {
    const double eta = -p.m_u * slope_at(p, v);
    const std::complex<double> expect(
        (eta - p.c_u) / (2 * p.m_u),
        std::sqrt(4 * p.m_u * p.k_p - (eta - p.c_u) * (eta - p.c_u)) / (2 * p.m_u));
    for (const auto& modes :
         {modal_eigenmodes(p, slope_at(p, v)), dense_eigenmodes(p, slope_at(p, v))}) {
      ASSERT_EQ(modes.size(), 1u);
      EXPECT_EQ(modes[0].family, ModeFamily::OneDof);
      EXPECT_NEAR(modes[0].lambda.real(), expect.real(), 1e-12);
      EXPECT_NEAR(modes[0].lambda.imag(), expect.imag(), 1e-12);
    }
  }
}

TEST(LinearStability, OneDofThresholdSpeedIsItsClosedForm) {
  // Unstable iff c < eta = m F0 / (v_c (1 + v/((1-s) v_c))^2): below
  // v* = (1 - s) v_c (sqrt(m F0/(c v_c)) - 1).
  const ModelParams p = thesis_model("1dof", 1);
  const double closed = (1 - p.sigma) * p.v_c * (std::sqrt(p.m_u * p.F0 / (p.c_u * p.v_c)) - 1);
  const double found =
      root([&](double v) { return modal_eigenmodes(p, slope_at(p, v))[0].growth(); }, 1e-3, 10);
  EXPECT_NEAR(found, closed, 1e-10 * closed);
  EXPECT_NEAR(closed, 1.434995, 1e-6);  // thesis Table 3.1 with zeta = 1/12
  EXPECT_GT(dense_eigenmodes(p, slope_at(p, 0.99 * closed))[0].growth(), 0);
  EXPECT_LT(dense_eigenmodes(p, slope_at(p, 1.01 * closed))[0].growth(), 0);
}

TEST(LinearStability, UndampedChainModesGrowAtMinusHalfTheSlope) {
  for (const char* kind : {"bk", "bkp"})
    for (const char* boundary : {"free", "periodic"}) {
      const ModelParams p = thesis_model(kind, 40, boundary);
      for (double v : {0.01, 0.2, 2.0}) {
        const double slope = slope_at(p, v);
        int chain = 0;
        for (const Eigenmode& m : modal_eigenmodes(p, slope)) {
          if (m.family != ModeFamily::Chain || (p.pad_moves() && m.index == 0)) continue;
          ++chain;
          EXPECT_NEAR(m.growth(), -slope / 2, 1e-12) << kind << " q " << m.index;
          EXPECT_TRUE(m.unstable());
        }
        EXPECT_EQ(chain, p.pad_moves() ? 39 : 40);
      }
    }
}

TEST(LinearStability, RayleighChainThresholdsAreTheirClosedForms) {
  // Chain mode q is stable iff alpha_M + beta_K k_q/m_u > -phi'(v): at fixed v, with
  // beta_K given, alpha*_q = -phi'(v) - beta_K k_q/m_u; with alpha_M given, the speed
  // threshold v*_q = (1 - s) v_c (sqrt(F0/(v_c d_q)) - 1), d_q = alpha + beta k_q/m_u.
  ModelParams p = thesis_model("bkp", 30);
  p.rayleigh_beta = 1e-4;
  const double v = 0.3, slope = slope_at(p, v);
  for (int q : {1, 7, 29}) {
    const double kq = p.k_p + p.k_c * laplacian_eigenvalue(p, q);
    const double closed = -slope - p.rayleigh_beta * kq / p.m_u;
    auto growth_q = [&](double alpha) {
      ModelParams r = p;
      r.rayleigh_alpha = alpha;
      for (const Eigenmode& m : modal_eigenmodes(r, slope))
        if (m.family == ModeFamily::Chain && m.index == q) return m.growth();
      return std::nan("");
    };
    EXPECT_NEAR(root(growth_q, 0.0, 2.0), closed, 1e-10) << "q " << q;
  }
  ModelParams r = p;
  r.rayleigh_alpha = 0.2;
  for (int q : {1, 5}) {
    const double dq =
        r.rayleigh_alpha + r.rayleigh_beta * (r.k_p + r.k_c * laplacian_eigenvalue(r, q)) / r.m_u;
    EXPECT_NEAR(chain_mode_damping(r, q), dq, 1e-15);
    const double closed = (1 - r.sigma) * r.v_c * (std::sqrt(r.F0 / (r.v_c * dq)) - 1);
    auto growth_v = [&](double speed) {
      for (const Eigenmode& m : modal_eigenmodes(r, slope_at(r, speed)))
        if (m.family == ModeFamily::Chain && m.index == q) return m.growth();
      return std::nan("");
    };
    EXPECT_NEAR(root(growth_v, 1e-3, 10.0), closed, 1e-9 * closed) << "q " << q;
  }
}

// Sorted by (Re, Im) for a one-to-one comparison.
std::vector<std::complex<double>> sorted(const std::vector<Eigenmode>& modes) {
  std::vector<std::complex<double>> l;
  for (const auto& m : modes) l.push_back(m.lambda);
  std::sort(l.begin(), l.end(), [](auto a, auto b) {
    return a.imag() != b.imag() ? a.imag() < b.imag() : a.real() < b.real();
  });
  return l;
}

TEST(LinearStability, ModalReductionEqualsDenseStateMatrix) {
  for (const char* kind : {"bk", "bkp"})
    for (const char* boundary : {"free", "periodic"})
      for (double beta : {0.0, 2e-3}) {
        ModelParams p = thesis_model(kind, 24, boundary);
        p.rayleigh_alpha = beta > 0 ? 0.05 : 0.0;
        p.rayleigh_beta = beta;
        const double slope = slope_at(p, 0.15);
        const auto modal = modal_eigenmodes(p, slope);
        const auto dense = dense_eigenmodes(p, slope);
        ASSERT_EQ(modal.size(), dense.size()) << kind << " " << boundary << " beta " << beta;
        const auto a = sorted(modal), b = sorted(dense);
        for (std::size_t i = 0; i < a.size(); ++i)
          EXPECT_LT(std::abs(a[i] - b[i]), 1e-9 * std::max(1.0, std::abs(a[i])))
              << kind << " " << boundary << " beta " << beta << " " << a[i] << " vs " << b[i];
        // Free ends: no degenerate modes, so the families and indices agree too.
        if (std::string(boundary) == "free")
          for (const Eigenmode& m : modal) {
            const auto match = std::find_if(dense.begin(), dense.end(), [&](const Eigenmode& d) {
              return std::abs(d.lambda - m.lambda) < 1e-9 * std::max(1.0, std::abs(m.lambda));
            });
            ASSERT_NE(match, dense.end());
            EXPECT_EQ(match->family, m.family) << m.lambda;
            EXPECT_EQ(match->index, m.index) << m.lambda;
          }
      }
}

TEST(LinearStability, PadModeThresholdFromQuarticEqualsDenseSolve) {
  ModelParams p = thesis_model("bkp", 16);
  auto pad_growth = [&](bool dense) {
    return [&p, dense](double v) {
      const double slope = kinetic_branch(p, v).slope;
      return largest_growth(dense ? dense_eigenmodes(p, slope) : modal_eigenmodes(p, slope),
                            ModeFamily::Pad);
    };
  };
  const double modal = root(pad_growth(false), 1e-3, 5.0);
  const double dense = root(pad_growth(true), 1e-3, 5.0);
  EXPECT_NEAR(modal, dense, 1e-8 * modal);
  EXPECT_GT(modal, 1e-3);
}

TEST(LinearStability, ModalShapesAreEigenvectors) {
  // Residual of (lambda^2 M + lambda C + K) s for a few modes of each family.
  ModelParams p = thesis_model("bkp", 9);
  const double slope = slope_at(p, 0.1);
  std::vector<ModeShape> shapes;
  const auto dense = dense_eigenmodes(p, slope, &shapes);
  for (const Eigenmode& m : modal_eigenmodes(p, slope)) {
    const ModeShape s = modal_shape(p, slope, m);
    // The dense eigenvector of the same eigenvalue spans the same line.
    for (std::size_t i = 0; i < dense.size(); ++i)
      if (std::abs(dense[i].lambda - m.lambda) < 1e-9) {
        for (std::size_t k = 0; k < s.size(); ++k)
          EXPECT_NEAR(std::abs(s[k] - shapes[i][k]), 0.0, 1e-8)
              << to_string(m.family) << m.index << " dof " << k;
      }
  }
}

}  // namespace
}  // namespace bkq
