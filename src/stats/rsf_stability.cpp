// Rate-and-state linear stability; the derivation is in rsf_stability.hpp.
#include "stats/rsf_stability.hpp"

#include <gsl/gsl_poly.h>

#include <algorithm>
#include <cmath>
#include <numbers>

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
  std::sort(roots.begin(), roots.end(), [](auto x, auto y) {
    return x.real() != y.real() ? x.real() > y.real() : x.imag() > y.imag();
  });
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

}  // namespace bkq
