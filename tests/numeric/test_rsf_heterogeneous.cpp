// Per-block rate-and-state laws (stats/rsf_stability.hpp's dense linearisation): for one law it
// has the modal analysis' roots on chains and lattices, quasi-dynamic and inertial; a chain
// with one velocity-weakening asperity among velocity-strengthening blocks is unstable on weak
// springs and stable on stiff ones, and a run from a small perturbation grows or decays at its
// leading eigenvalue. And the law's units: scaled scenes run the scaled cycle.
#include <gsl/gsl_eigen.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <vector>

#include "engine/rsf_cycle.hpp"
#include "model/coupling.hpp"
#include "stats/rsf_stability.hpp"
#include "stats/stability.hpp"
#include "support/qdyn_stickslip.hpp"

namespace bkq {
namespace {

// Every modal root (mode by mode, each mode's 2 or 3 roots) next to a dense eigenvalue, and
// as many of them.
void expect_modal_roots_are_dense(const RsfModel& m, const char* what) {
  std::vector<std::complex<double>> modal;
  for (int q = 0; q < m.n(); ++q) {
    const double k = m.k + rsf_mode_stiffness(m, q % m.nx(), q / m.nx());
    for (const auto& s : rsf_eigenvalues(m, k)) modal.push_back(s);
  }
  std::vector<std::complex<double>> dense = rsf_dense_eigenvalues(m);
  ASSERT_EQ(dense.size(), modal.size()) << what;
  double scale = 0;
  for (const auto& s : modal) scale = std::max(scale, std::abs(s));
  // Match greedily: each modal root takes the nearest dense eigenvalue still free.
  std::vector<bool> used(dense.size(), false);
  for (const auto& s : modal) {
    std::size_t best = 0;
    double dist = HUGE_VAL;
    for (std::size_t i = 0; i < dense.size(); ++i)
      if (!used[i] && std::abs(dense[i] - s) < dist) dist = std::abs(dense[i] - s), best = i;
    used[best] = true;
    EXPECT_LT(dist, 1e-9 * scale) << what << ": modal root " << s.real() << " + " << s.imag()
                                  << "i";
  }
  // The leading eigenvalue is the modal analysis' largest growth rate.
  double top = -HUGE_VAL;
  for (const auto& s : modal) top = std::max(top, s.real());
  EXPECT_NEAR(dense[0].real(), top, 1e-9 * scale) << what;
}

TEST(RsfHeterogeneous, OneLawGivesTheModalRoots) {
  RsfModel m = test::qdyn_stickslip(7);
  m.k_c = 3e9;
  expect_modal_roots_are_dense(m, "free chain");
  m.periodic = true;
  expect_modal_roots_are_dense(m, "ring");
  // A lattice with different springs along and across strike.
  RsfModel l = test::qdyn_stickslip(4 * 3);
  l.rows = 3;
  l.springs = {{1, 0, 3e8}, {0, 1, 7e9}};
  expect_modal_roots_are_dense(l, "lattice");
  // Inertia (Rice & Ruina 1983): three roots per mode.
  m.dynamics = RsfDynamics::Inertial;
  m.mass = 1e11;
  expect_modal_roots_are_dense(m, "inertial ring");
  EXPECT_TRUE(rsf_homogeneous(m));
}

// Nine blocks: velocity strengthening (a and b_rsf swapped) but for the middle one, QDYN's
// velocity-weakening block, on coupling springs k_c.
RsfModel asperity_chain(double k_c) {
  RsfModel m = test::qdyn_stickslip(9);
  rsf::Params barrier = m.law[0].params();
  std::swap(barrier.a, barrier.b_rsf);
  for (int j = 0; j < 9; ++j)
    if (j != 4) m.law[j] = rsf::Law(barrier);
  m.k_c = k_c;
  return m;
}

// The linearisation's leading eigenvalue and its eigenvector (GSL's gsl_eigen_nonsymmv).
struct LeadingMode {
  std::complex<double> lambda;
  std::vector<std::complex<double>> z;
};
LeadingMode leading_mode(const RsfModel& m) {
  std::vector<double> a = rsf_linearisation(m);
  const int d = static_cast<int>(std::lround(std::sqrt(static_cast<double>(a.size()))));
  gsl_matrix_view A = gsl_matrix_view_array(a.data(), d, d);
  gsl_vector_complex* eval = gsl_vector_complex_alloc(d);
  gsl_matrix_complex* evec = gsl_matrix_complex_alloc(d, d);
  gsl_eigen_nonsymmv_workspace* w = gsl_eigen_nonsymmv_alloc(d);
  gsl_eigen_nonsymmv(&A.matrix, eval, evec, w);
  gsl_eigen_nonsymmv_free(w);
  int best = 0;
  for (int i = 0; i < d; ++i) {
    const gsl_complex z = gsl_vector_complex_get(eval, i), b = gsl_vector_complex_get(eval, best);
    if (GSL_REAL(z) > GSL_REAL(b) || (GSL_REAL(z) == GSL_REAL(b) && GSL_IMAG(z) > GSL_IMAG(b)))
      best = i;
  }
  LeadingMode mode;
  const gsl_complex l = gsl_vector_complex_get(eval, best);
  mode.lambda = {GSL_REAL(l), GSL_IMAG(l)};
  for (int i = 0; i < d; ++i) {
    const gsl_complex z = gsl_matrix_complex_get(evec, i, best);
    mode.z.emplace_back(GSL_REAL(z), GSL_IMAG(z));
  }
  gsl_matrix_complex_free(evec);
  gsl_vector_complex_free(eval);
  return mode;
}

// Nine blocks on weak springs (k_c = k/20): the asperity slips on its own, steady sliding is
// unstable; on stiff springs (5 k) the barriers hold it, stable. Block 0's law alone (a
// barrier's) would call both stable. Started on the leading eigenvector, a run follows the
// linear mode eps Re(z e^{lambda t}) on every block to 1 % of its envelope while it grows or
// decays by e^{+-12}.
TEST(RsfHeterogeneous, AsperityAmongBarriersGrowsOrDecaysAsTheLinearisationSays) {
  for (const double k_c : {1e8, 1e10}) {
    const RsfModel m = asperity_chain(k_c);
    ASSERT_FALSE(rsf_homogeneous(m));
    const LeadingMode mode = leading_mode(m);
    const std::complex<double> lambda = mode.lambda;
    EXPECT_NEAR(lambda.real(), rsf_dense_eigenvalues(m)[0].real(), 1e-12);
    EXPECT_EQ(lambda.real() > 0, k_c < 1e9) << "k_c = " << k_c;
    EXPECT_LT(rsf_eigenvalues(m, m.k + k_c * rsf_chain_laplacian(9, false, 0))[0].real(), 0);
    const int n = m.n();
    double zmax = 0;
    for (const auto& z : mode.z) zmax = std::max(zmax, std::abs(z));
    // Small enough to stay linear at the end of a growth by e^12.
    const double eps = (lambda.real() > 0 ? 1e-8 : 1e-5) / zmax;
    std::vector<double> v(n), theta(n);
    for (int j = 0; j < n; ++j) {
      v[j] = m.v_pl * std::exp(eps * mode.z[j].real());
      theta[j] = m.law[j].params().dc / m.v_pl * std::exp(eps * mode.z[n + j].real());
    }
    RsfCycle c(m, 1e-11, v, theta);
    const double span = 12 / std::fabs(lambda.real());
    double worst = 0;
    for (int i = 1; i <= 200; ++i) {
      const double t = i * span / 200;
      c.advance_to(t);
      const double envelope = eps * zmax * std::exp(lambda.real() * t);
      for (int j = 0; j < n; ++j) {
        const double linear = eps * (mode.z[j] * std::exp(lambda * t)).real();
        worst = std::max(worst, std::fabs(c.ln_v(j) - std::log(m.v_pl) - linear) / envelope);
      }
    }
    std::printf(
        "k_c = %g: lambda = %.6e %+.6e i, largest deviation from the linear mode %.2e "
        "of its envelope\n",
        k_c, lambda.real(), lambda.imag(), worst);
    EXPECT_LT(worst, 0.01) << "k_c = " << k_c;
  }
}

// The law's units (docs/explanation/rate-and-state.md, "Dimensionless form"): a scene whose
// D_c, sigma or V_pl is scaled, with k, k_c and eta scaled to keep k D_c/sigma, k_c D_c/sigma
// and eta V_pl/sigma, runs the same cycle in time units of D_c/V_pl: slip-rate peaks at the
// scaled times, tau/sigma between the same extremes.
struct Scaled {
  std::vector<double> peaks;  // slip-rate maxima of block 0 [s]
  double f_min = HUGE_VAL, f_max = -HUGE_VAL;
};
Scaled cycle_of(const RsfModel& m, double v_scale, double theta0, double t_end) {
  // The two blocks start apart, so that the coupling springs work.
  RsfCycle c(m, 1e-10, {2e-5 * v_scale, 3e-6 * v_scale}, {theta0});
  Scaled out;
  const int n = m.n();
  while (c.t() < t_end) {
    c.step(t_end);
    const double d0 = c.dy_prev()[n], d1 = c.dy()[n];
    if (d0 > 0 && d1 <= 0)
      out.peaks.push_back(hermite_extremum(c.t_prev(), c.y_prev()[n], d0, c.t(), c.y()[n], d1).t);
    const double f = c.friction_stress(0) / m.sigma;
    out.f_min = std::min(out.f_min, f);
    out.f_max = std::max(out.f_max, f);
  }
  return out;
}

TEST(RsfUnits, ScaledScenesRunTheScaledCycle) {
  RsfModel base = test::qdyn_stickslip(2);
  base.k_c = 1e9;
  const double t_end = 3000;
  const Scaled ref = cycle_of(base, 1, 10, t_end);
  ASSERT_GE(ref.peaks.size(), 4u);
  struct Case {
    const char* what;
    double dc, sigma, v;  // factors on D_c, sigma and V_pl (with V*)
  };
  for (const Case& k :
       {Case{"D_c x 8", 8, 1, 1}, Case{"sigma x 3", 1, 3, 1}, Case{"V_pl x 5", 1, 1, 5}}) {
    RsfModel m = base;
    for (rsf::Law& law : m.law) {
      rsf::Params p = law.params();
      p.dc *= k.dc;
      p.v0 *= k.v;
      law = rsf::Law(p);
    }
    m.sigma *= k.sigma;
    m.v_pl *= k.v;
    const double stiff = k.sigma / k.dc;  // k D_c/sigma kept
    m.k *= stiff;
    m.k_c *= stiff;
    m.eta *= k.sigma / k.v;          // eta V_pl/sigma kept
    const double time = k.dc / k.v;  // D_c/V_pl
    const Scaled s = cycle_of(m, k.v, 10 * time, t_end * time);
    ASSERT_EQ(s.peaks.size(), ref.peaks.size()) << k.what;
    double worst = 0;
    for (std::size_t i = 0; i < ref.peaks.size(); ++i) {
      EXPECT_NEAR(s.peaks[i] / time, ref.peaks[i], 1e-7 * t_end) << k.what << ", peak " << i;
      worst = std::max(worst, std::fabs(s.peaks[i] / time - ref.peaks[i]));
    }
    std::printf(
        "%s: %zu peaks, largest difference of a scaled peak time %.2e s, of tau/sigma "
        "%.2e\n",
        k.what, ref.peaks.size(), worst,
        std::max(std::fabs(s.f_min - ref.f_min), std::fabs(s.f_max - ref.f_max)));
    EXPECT_NEAR(s.f_min, ref.f_min, 1e-9) << k.what;
    EXPECT_NEAR(s.f_max, ref.f_max, 1e-9) << k.what;
  }
}

}  // namespace
}  // namespace bkq
