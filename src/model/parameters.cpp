// Derived quantities of the physical parameters (Ferre 2018 eq. 3.1, Table 3.1; Carlson & Langer
// 1989 eq. 2.2).
#include "model/parameters.hpp"

#include <algorithm>
#include <cmath>

namespace bkq {

// Critical damping of a mass m on a spring k is 2 sqrt(k m); zeta scales it (Ferre 2018 §3.1).
double critical_damping(double zeta, double k, double m) {
  return zeta * 2.0 * std::sqrt(k * m);
}

ModelParams line_as_chain(ModelParams p) {
  if (p.rows <= 1 || p.n != p.rows) return p;
  p.rows = 1;
  p.k_c = p.k_c_y;
  p.k_c_y = 0;
  p.boundary = p.boundary_y;
  p.boundary_y = Boundary::Free;
  return p;
}

double ModelParams::max_angular_frequency() const {
  // Thesis eq. 3.2: the fastest chain mode has neighbours in antiphase, sqrt((4 k_c + k_p)/m_u);
  // on a lattice the checkerboard mode, with 4 (k_c + k_c_y).
  const double k_nb = has_neighbours() ? 4.0 * (k_c + (lattice() ? k_c_y : 0.0)) : 0.0;
  double w = std::sqrt((k_nb + k_p) / m_u);
  // A damper is a real eigenvalue of size c/m; explicit steppers must resolve it too.
  w = std::max(w, c_u / m_u);
  // The dashpots' fastest mode (neighbours in antiphase) decays at 4 eta / m_u at most.
  if (viscous()) w = std::max(w, (c_u + 4.0 * viscosity) / m_u);
  if (pad_moves()) {
    const double K = k_p0 + n * k_p;
    w = std::max({w, std::sqrt(K / m_x), c_p / m_x});
  }
  if (rayleigh_alpha != 0 || rayleigh_beta != 0) {
    // Rayleigh damping alpha_M M + beta_K K adds alpha_M + beta_K omega^2 to a mode of
    // angular frequency omega: the fastest block and pad modes' damping rates, as the dampers'.
    const double wb2 = (k_nb + k_p) / m_u;
    const double eta = viscous() ? 4.0 * viscosity / m_u : 0.0;
    w = std::max(w, c_u / m_u + rayleigh_alpha + rayleigh_beta * wb2 + eta);
    if (pad_moves())
      w = std::max(w, c_p / m_x + rayleigh_alpha + rayleigh_beta * (k_p0 + n * k_p) / m_x);
  }
  return w;
}

double ModelParams::loading_rate() const {
  // Quasistatic loading: BK, every stuck block gains k_p per unit substrate displacement; with a
  // quasi-statically relaxing pad the pad follows by N k_p/(k_p0 + N k_p) of the way.
  if (!pad_moves()) return k_p;
  return k_p * k_p0 / (k_p0 + n * k_p);
}

const char* to_string(ModelKind k) {
  switch (k) {
    case ModelKind::BK:
      return "bk";
    case ModelKind::BKP:
      return "bkp";
    case ModelKind::OneDof:
      return "1dof";
  }
  return "?";
}

}  // namespace bkq
