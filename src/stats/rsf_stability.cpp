// Rate-and-state linear stability; the derivation is in rsf_stability.hpp.
#include "stats/rsf_stability.hpp"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace bkq {

namespace {

struct Slopes {
  double omega, c, B;
};

Slopes slopes(const RsfModel& m) {
  const rsf::Law& law = m.law.at(0);
  const double dc = law.params().dc;
  const double ln_v = std::log(m.v_pl);
  const rsf::FrictionValue fr = law.friction(m.form, ln_v, law.steady_ln_theta(m.v_pl));
  return {m.v_pl / dc, m.eta + m.sigma * fr.f_lnv / m.v_pl, m.sigma * fr.f_lntheta / dc};
}

double mass_of(const RsfModel& m) {
  return m.dynamics == RsfDynamics::Inertial ? m.mass : 0.0;
}

bool by_growth(std::complex<double> x, std::complex<double> y) {
  return x.real() != y.real() ? x.real() > y.real() : x.imag() > y.imag();
}

}  // namespace

std::vector<std::complex<double>> rsf_eigenvalues(const RsfModel& m, double k) {
  const Slopes s = slopes(m);
  const double mass = mass_of(m);
  std::vector<std::complex<double>> roots;
  if (mass == 0) {
    // c s^2 + (k + c omega - B) s + k omega = 0.
    const double p = (k + s.c * s.omega - s.B) / s.c, q = k * s.omega / s.c;
    const std::complex<double> d = std::sqrt(std::complex<double>(p * p / 4 - q));
    roots = {-p / 2 + d, -p / 2 - d};
  } else {
    const double coef[4] = {k * s.omega, k + s.c * s.omega - s.B, mass * s.omega + s.c, mass};
    double z[6];
    gsl_poly_complex_workspace* w = gsl_poly_complex_workspace_alloc(4);
    gsl_poly_complex_solve(coef, 4, w, z);
    gsl_poly_complex_workspace_free(w);
    for (int i = 0; i < 3; ++i) roots.emplace_back(z[2 * i], z[2 * i + 1]);
  }
  std::sort(roots.begin(), roots.end(), by_growth);
  return roots;
}

double rsf_critical_stiffness(const RsfModel& m) {
  const Slopes s = slopes(m);
  return (s.B - s.c * s.omega) * (1 + mass_of(m) * s.omega / s.c);
}

double rsf_critical_frequency(const RsfModel& m) {
  const Slopes s = slopes(m);
  const double k = rsf_critical_stiffness(m);
  if (!(k > 0)) return std::nan("");
  return std::sqrt(k * s.omega / (mass_of(m) * s.omega + s.c)) / (2 * std::numbers::pi);
}

double rsf_chain_laplacian(int n, bool periodic, int q) {
  const double x = std::sin(std::numbers::pi * q / (periodic ? n : 2.0 * n));
  return 4 * x * x;
}

double rsf_mode_stiffness(const RsfModel& m, int qx, int qy) {
  const double pi = std::numbers::pi;
  const double tx = (m.periodic ? 2 : 1) * pi * qx / m.nx();
  const double ty = (m.periodic_y ? 2 : 1) * pi * qy / m.rows;
  double k = 0;
  for (const LatticeSpring& s : m.stencil()) {
    // A spring along an axis of one site adds nothing.
    if ((s.dx != 0 && m.nx() == 1) || (s.dy != 0 && m.rows == 1)) continue;
    k += 2 * s.k * (1 - std::cos(s.dx * tx + s.dy * ty));
  }
  return k;
}

bool rsf_homogeneous(const RsfModel& m) {
  const rsf::Params& p0 = m.law.at(0).params();
  return std::all_of(m.law.begin(), m.law.end(), [&](const rsf::Law& law) {
    const rsf::Params& p = law.params();
    return p.a == p0.a && p.b_rsf == p0.b_rsf && p.dc == p0.dc && p.mu0 == p0.mu0 && p.v0 == p0.v0;
  });
}

std::vector<double> rsf_linearisation(const RsfModel& m) {
  const int n = m.n();
  const double mass = mass_of(m), v = m.v_pl;
  const int d = (mass == 0 ? 2 : 3) * n;
  const RsfNeighbours nb = rsf_neighbours(m);
  std::vector<double> A(static_cast<std::size_t>(d) * d, 0.0);
  const auto add = [&](int i, int j, double x) { A[static_cast<std::size_t>(i) * d + j] += x; };
  // Rows x_j (0..N-1), phi_j (N..2N-1) and, with inertia, xi_j (2N..3N-1); see the header.
  for (int j = 0; j < n; ++j) {
    const rsf::Law& law = m.law[j];
    const double omega = v / law.params().dc;
    const rsf::FrictionValue fr = law.friction(m.form, std::log(v), law.steady_ln_theta(v));
    const double S = m.sigma * fr.f_lnv + m.eta * v, T = m.sigma * fr.f_lntheta;
    const int x = j, phi = n + j, xi = 2 * n + j;
    add(phi, x, -omega);
    add(phi, phi, -omega);
    if (mass == 0) {
      // (K x)_j = k x_j + sum_i k_ji (x_j - x_i).
      add(x, x, (-v * m.k + T * omega) / S);
      add(x, phi, T * omega / S);
      for (int e = nb.start[j]; e < nb.start[j + 1]; ++e) {
        add(x, x, -v * nb.k[e] / S);
        add(x, nb.index[e], v * nb.k[e] / S);
      }
    } else {
      add(xi, x, 1);
      add(x, x, -S / (mass * v));
      add(x, phi, -T / (mass * v));
      add(x, xi, -m.k / mass);
      for (int e = nb.start[j]; e < nb.start[j + 1]; ++e) {
        add(x, xi, -nb.k[e] / mass);
        add(x, 2 * n + nb.index[e], nb.k[e] / mass);
      }
    }
  }
  return A;
}

std::vector<std::complex<double>> rsf_dense_eigenvalues(const RsfModel& m) {
  std::vector<double> a = rsf_linearisation(m);
  const int d = static_cast<int>(std::lround(std::sqrt(static_cast<double>(a.size()))));
  gsl_matrix_view view = gsl_matrix_view_array(a.data(), d, d);
  gsl_matrix* A = &view.matrix;
  gsl_vector_complex* eval = gsl_vector_complex_alloc(d);
  gsl_eigen_nonsymm_workspace* w = gsl_eigen_nonsymm_alloc(d);
  gsl_eigen_nonsymm_params(0, 1, w);  // balance: the rows' scales differ by orders
  gsl_error_handler_t* old = gsl_set_error_handler_off();  // a failure is thrown below
  const int status = gsl_eigen_nonsymm(A, eval, w);
  gsl_set_error_handler(old);
  gsl_eigen_nonsymm_free(w);
  std::vector<std::complex<double>> out;
  out.reserve(d);
  for (int i = 0; i < d; ++i) {
    const gsl_complex z = gsl_vector_complex_get(eval, i);
    out.emplace_back(GSL_REAL(z), GSL_IMAG(z));
  }
  gsl_vector_complex_free(eval);
  if (status != 0) throw Error("stability: the eigenvalue solver did not converge");
  std::sort(out.begin(), out.end(), by_growth);
  return out;
}

}  // namespace bkq
