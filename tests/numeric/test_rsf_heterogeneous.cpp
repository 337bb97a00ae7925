// Per-block rate-and-state laws (stats/rsf_stability.hpp's dense linearisation): for one law it
// has the modal analysis' roots on chains and lattices, quasi-dynamic and inertial; a chain
// with one velocity-weakening asperity among velocity-strengthening blocks is unstable on weak
// springs and stable on stiff ones, and a run from a small perturbation grows or decays at its
// leading eigenvalue.
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

}  // namespace
}  // namespace bkq
