// Steady sliding; see equilibrium.hpp.
#include "model/equilibrium.hpp"

#include <cmath>

namespace bkq {

KineticBranch kinetic_branch(const ModelParams& p, double v, NoEquilibrium* why) {
  auto fail = [&](NoEquilibrium w) {
    if (why) *why = w;
    return KineticBranch{};
  };
  if (!(v > 0)) return fail(NoEquilibrium::NotSliding);
  // All laws of friction.hpp are k0 / (1 + v/s) on y > 0: phi' = -k0/(s (1 + v/s)^2).
  double k0 = 0, scale = HUGE_VAL;
  if (p.law == law_id<law::None>) return KineticBranch{};
  if (p.law == law_id<law::Cl89>) {
    k0 = p.F0;
    scale = p.v_c;
  } else if (p.law == law_id<law::Thesis> || p.law == law_id<law::Clst91>) {
    k0 = p.F0 * (1.0 - p.sigma);
    scale = (1.0 - p.sigma) * p.v_c;
  } else {
    return fail(NoEquilibrium::NoKinetic);
  }
  if (!std::isfinite(scale)) return KineticBranch{k0, 0.0};
  const double d = 1.0 + v / scale;
  return KineticBranch{k0 / d, -k0 / (scale * d * d)};
}

namespace {

// Solves the symmetric tridiagonal T y = r with diagonal d, off-diagonal -k (Thomas).
void thomas(const std::vector<double>& d, double k, std::vector<double>& y,
            std::vector<double>& work) {
  const int n = static_cast<int>(d.size());
  work.resize(n);
  double denom = d[0];
  y[0] /= denom;
  for (int j = 1; j < n; ++j) {
    work[j] = -k / denom;  // c'_{j-1}
    denom = d[j] + k * work[j];
    y[j] = (y[j] + k * y[j - 1]) / denom;
  }
  for (int j = n - 2; j >= 0; --j) y[j] -= work[j + 1] * y[j + 1];
}

// Solves (k_p I + k_c L) y = r in place, L the chain's graph Laplacian (free or ring).
void solve_chain(const ModelParams& p, std::vector<double>& y) {
  const int n = p.n;
  const double kc = p.has_neighbours() ? p.k_c : 0.0;
  std::vector<double> d(n), work;
  const bool ring = p.boundary == Boundary::Periodic && n > 2 && kc != 0;
  for (int j = 0; j < n; ++j) {
    int deg = 2;
    if (!ring && p.boundary != Boundary::Periodic) deg = (j > 0) + (j < n - 1);
    d[j] = p.k_p + kc * (n > 1 ? deg : 0);
  }
  if (!ring) {
    thomas(d, kc, y, work);
    return;
  }
  // Ring: T = T0 + a b^T, a = (g, 0, ..., 0, -k_c), b = (1, 0, ..., 0, -k_c/g), which puts
  // -k_c in both corners (Sherman–Morrison; g = -d_0 keeps T0 diagonally dominant).
  const double g = -d[0];
  std::vector<double> d0 = d;
  d0[0] -= g;
  d0[n - 1] -= kc * kc / g;
  std::vector<double> z(n, 0.0);
  z[0] = g;
  z[n - 1] = -kc;
  thomas(d0, kc, y, work);
  thomas(d0, kc, z, work);
  const double wy = y[0] - kc / g * y[n - 1];
  const double wz = z[0] - kc / g * z[n - 1];
  const double f = wy / (1.0 + wz);
  for (int j = 0; j < n; ++j) y[j] -= f * z[j];
}

}  // namespace

bool solve_static(const ModelParams& p, const std::vector<double>& f, std::vector<double>& u,
                  double& x) {
  // T = k_p I + k_c L is symmetric with T 1 = k_p 1 (both boundaries), so the uniform part
  // of the load is solved exactly and kept out of the tridiagonal solve, whose condition
  // number (about 4 k_c / k_p, 4e8 for thesis scalings at N = 10^5) would spoil it:
  // u = x 1 - mean(f)/k_p 1 + T^-1 (mean(f) 1 - f), the last term summing to zero. The
  // pad row k_p sum_j (u_j - x) = k_p0 x then gives x = -N mean(f)/k_p0.
  const int n = p.n;
  double mean = 0;
  for (double fj : f) mean += fj;
  mean /= n;
  u.assign(n, 0.0);
  for (int j = 0; j < n; ++j) u[j] = mean - f[j];
  solve_chain(p, u);
  x = 0;
  if (p.pad_moves()) {
    if (!(p.k_p0 > 0)) return mean == 0;
    x = -n * mean / p.k_p0;
  }
  for (int j = 0; j < n; ++j) u[j] += x - mean / p.k_p;
  return true;
}

SlidingEquilibrium sliding_equilibrium(const ModelParams& p, double v) {
  SlidingEquilibrium e;
  e.v = v;
  e.friction = kinetic_branch(p, v, &e.why);
  if (!e.exists()) return e;
  const std::vector<double> f(p.n, p.m_u * e.friction.phi);
  if (!solve_static(p, f, e.u, e.x)) {
    // Without a caliper spring the pad balances only a chain without net friction.
    if (e.friction.phi != 0) {
      e.why = NoEquilibrium::NoPadSpring;
      e.u.clear();
    } else {
      e.u.assign(p.n, 0.0);
      e.x = 0;
    }
  }
  return e;
}

}  // namespace bkq
