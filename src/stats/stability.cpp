// Linear stability of steady sliding; see stability.hpp.
#include "stats/stability.hpp"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_poly.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "model/coupling.hpp"

namespace bkq {

namespace {

using cplx = std::complex<double>;
constexpr double kPi = std::numbers::pi;

bool coupled(const ModelParams& p) {
  return p.has_neighbours() && p.kind != ModelKind::OneDof;
}

// The roots of m l^2 + c l + k = 0 with Im >= 0 (one for a complex pair, two real ones).
void quadratic_roots(double m, double c, double k, std::vector<cplx>& out) {
  const double disc = c * c - 4.0 * m * k;
  if (disc < 0) {
    out.emplace_back(-c / (2.0 * m), std::sqrt(-disc) / (2.0 * m));
    return;
  }
  // Stable form: q = -(c + sgn(c) sqrt(disc))/2, roots q/m and k/q.
  const double q = -0.5 * (c + std::copysign(std::sqrt(disc), c));
  out.emplace_back(q / m, 0.0);
  out.emplace_back(q != 0 ? k / q : 0.0, 0.0);
}

// Share of the kinetic energy carried by the pad in a shape (blocks first, pad last).
double pad_share(const ModelParams& p, const ModeShape& s) {
  double blocks = 0;
  for (int j = 0; j < p.n; ++j) blocks += std::norm(s[j]);
  const double pad = p.m_x * std::norm(s[p.n]);
  const double total = pad + p.m_u * blocks;
  return total > 0 ? pad / total : 0.0;
}

// Scales the shape so that its largest component is 1; among components of (nearly) equal
// size the first, so that symmetric shapes from different solvers agree in sign.
void normalise(ModeShape& s) {
  double big = 0;
  for (const auto& z : s) big = std::max(big, std::abs(z));
  if (big == 0) return;
  std::size_t i = 0;
  while (std::abs(s[i]) < (1 - 1e-9) * big) ++i;
  const cplx f = 1.0 / s[i];
  for (auto& z : s) z *= f;
}

// The bkp uniform mode (every block at a) coupled to the pad x: the rows of
// lambda^2 M + lambda C + K for (a, x), the block row summed over the N blocks.
struct PadPair {
  double m11, m22, c11, c12, c22, k11, k12, k22;
};
PadPair pad_pair(const ModelParams& p, double slope) {
  const double n = p.n, a = p.rayleigh_alpha, b = p.rayleigh_beta;
  PadPair r{};
  r.m11 = n * p.m_u;
  r.m22 = p.m_x;
  r.k11 = n * p.k_p;
  r.k12 = -n * p.k_p;
  r.k22 = n * p.k_p + p.k_p0;
  r.c11 = n * p.m_u * slope + n * p.c_u + a * r.m11 + b * r.k11;
  r.c12 = b * r.k12;
  r.c22 = p.c_p + a * r.m22 + b * r.k22;
  return r;
}

// Null vector (a, x) of the pair's 2x2 matrix at lambda.
ModeShape pad_pair_vector(const PadPair& r, cplx l) {
  const cplx A = (r.m11 * l + r.c11) * l + r.k11;
  const cplx B = r.c12 * l + r.k12;
  const cplx D = (r.m22 * l + r.c22) * l + r.k22;
  // Rows A a + B x = 0 and B a + D x = 0: take the better-conditioned one.
  if (std::abs(A) + std::abs(B) >= std::abs(B) + std::abs(D)) return {-B, A};
  return {D, -B};
}

}  // namespace

const char* to_string(ModeFamily f) {
  switch (f) {
    case ModeFamily::Chain:
      return "chain";
    case ModeFamily::Pad:
      return "pad";
    case ModeFamily::OneDof:
      return "1dof";
  }
  return "?";
}

double Eigenmode::frequency() const {
  return lambda.imag() / (2.0 * kPi);
}

double laplacian_eigenvalue(const ModelParams& p, int q) {
  if (!coupled(p)) return 0.0;
  if (p.long_range()) {
    // A ring's stiffness is circulant for any stencil: the Fourier modes stay its modes, each
    // spring k_r adding k_r 4 sin^2(pi q r / N). (A free chain's cut springs break this; the
    // callers refuse the reduction there.)
    double mu = 0;
    for (const CouplingSpring& c : coupling_stencil(p)) {
      const double x = std::sin(kPi * q * c.offset / p.n);
      mu += c.k / p.k_c * 4.0 * x * x;
    }
    return mu;
  }
  const double s =
      p.boundary == Boundary::Periodic ? std::sin(kPi * q / p.n) : std::sin(kPi * q / (2.0 * p.n));
  return 4.0 * s * s;
}

double chain_shape(const ModelParams& p, int q, int j) {
  if (p.boundary == Boundary::Periodic && coupled(p)) {
    const double arg = 2.0 * kPi * q * j / p.n;
    return 2 * q <= p.n ? std::cos(arg) : std::sin(arg);
  }
  return std::cos(kPi * q * (j + 0.5) / p.n);
}

double damper_eigenvalue(const ModelParams& p, int q) {
  if (!p.viscous() || p.kind == ModelKind::OneDof) return 0.0;
  const CouplingStencil dampers = damper_stencil(p);
  if (dampers.size() == 1) {
    const double s = p.boundary == Boundary::Periodic ? std::sin(kPi * q / p.n)
                                                      : std::sin(kPi * q / (2.0 * p.n));
    return p.viscosity * 4.0 * s * s;
  }
  double mu = 0;
  for (const CouplingSpring& c : dampers) {
    const double x = std::sin(kPi * q * c.offset / p.n);
    mu += c.k * 4.0 * x * x;
  }
  return mu;
}

double chain_mode_damping(const ModelParams& p, int q) {
  const double k = p.k_p + p.k_c * laplacian_eigenvalue(p, q);
  const double d = p.c_u / p.m_u + p.rayleigh_alpha + p.rayleigh_beta * k / p.m_u;
  return p.viscous() ? d + damper_eigenvalue(p, q) / p.m_u : d;
}

std::vector<Eigenmode> modal_eigenmodes(const ModelParams& p, double slope) {
  std::vector<Eigenmode> out;
  std::vector<cplx> roots;
  const ModeFamily block_family =
      p.kind == ModelKind::OneDof ? ModeFamily::OneDof : ModeFamily::Chain;
  const int first = p.pad_moves() ? 1 : 0;
  out.reserve(p.n + 2);
  for (int q = first; q < p.n; ++q) {
    const double k = p.k_p + p.k_c * laplacian_eigenvalue(p, q);
    roots.clear();
    quadratic_roots(p.m_u, p.m_u * (slope + chain_mode_damping(p, q)), k, roots);
    for (cplx l : roots) out.push_back({block_family, q, l});
  }
  if (p.pad_moves()) {
    // det [[A, B], [B, D]] = A D - B^2, a quartic in lambda (coefficients ascending).
    const PadPair r = pad_pair(p, slope);
    const double c[5] = {
        r.k11 * r.k22 - r.k12 * r.k12,
        r.c11 * r.k22 + r.k11 * r.c22 - 2.0 * r.c12 * r.k12,
        r.m11 * r.k22 + r.c11 * r.c22 + r.k11 * r.m22 - r.c12 * r.c12,
        r.m11 * r.c22 + r.c11 * r.m22,
        r.m11 * r.m22,
    };
    double z[8];
    gsl_poly_complex_workspace* w = gsl_poly_complex_workspace_alloc(5);
    gsl_poly_complex_solve(c, 5, w, z);
    gsl_poly_complex_workspace_free(w);
    for (int i = 0; i < 4; ++i) {
      cplx l(z[2 * i], z[2 * i + 1]);
      if (std::abs(l.imag()) <= 1e-13 * std::abs(l)) l.imag(0.0);
      if (l.imag() < 0) continue;
      Eigenmode m{ModeFamily::Chain, 0, l};
      const ModeShape pair = pad_pair_vector(r, l);
      ModeShape s(p.n + 1, pair[0]);
      s[p.n] = pair[1];
      if (pad_share(p, s) > 0.5) m.family = ModeFamily::Pad;
      out.push_back(m);
    }
  }
  return out;
}

ModeShape modal_shape(const ModelParams& p, double slope, const Eigenmode& m) {
  const int dofs = p.n + (p.pad_moves() ? 1 : 0);
  ModeShape s(dofs, 0.0);
  if (p.pad_moves() && m.index == 0) {
    const ModeShape pair = pad_pair_vector(pad_pair(p, slope), m.lambda);
    for (int j = 0; j < p.n; ++j) s[j] = pair[0];
    s[p.n] = pair[1];
  } else {
    for (int j = 0; j < p.n; ++j) s[j] = chain_shape(p, m.index, j);
  }
  normalise(s);
  return s;
}

std::vector<Eigenmode> dense_eigenmodes(const ModelParams& p, double slope,
                                        std::vector<ModeShape>* shapes) {
  const int n = p.n;
  const bool pad = p.pad_moves();
  const int d = n + (pad ? 1 : 0);
  // K and C of the linearisation; M is diagonal.
  std::vector<double> K(d * d, 0.0), C(d * d, 0.0), M(d, p.m_u);
  auto at = [d](std::vector<double>& a, int i, int j) -> double& { return a[i * d + j]; };
  const double kc = coupled(p) ? p.k_c : 0.0;
  const CouplingStencil stencil = coupling_stencil(p);
  const CouplingStencil dampers =
      p.kind == ModelKind::OneDof ? CouplingStencil{} : damper_stencil(p);
  const bool ring = p.boundary == Boundary::Periodic && n > 2;
  for (int j = 0; j < n; ++j) {
    at(K, j, j) += p.k_p;
    if (pad) {
      at(K, j, n) -= p.k_p;
      at(K, n, j) -= p.k_p;
      at(K, n, n) += p.k_p;
    }
    auto spring = [&](int a, int b, double k) {
      at(K, a, a) += k;
      at(K, b, b) += k;
      at(K, a, b) -= k;
      at(K, b, a) -= k;
    };
    // The coupling's stencil (model/coupling.hpp): each spring once, to the block `offset`
    // to the right (wrapped on a ring).
    if (kc != 0)
      for (const CouplingSpring& c : stencil) {
        const int partner = j + c.offset;
        if (partner < n)
          spring(j, partner, c.k);
        else if (ring)
          spring(j, partner - n, c.k);
      }
    at(C, j, j) += p.m_u * slope + p.c_u;
    // The dashpots (model.viscosity) on the same stencil, into C.
    for (const CouplingSpring& c : dampers) {
      const int partner = j + c.offset < n ? j + c.offset : (ring ? j + c.offset - n : -1);
      if (partner < 0) continue;
      at(C, j, j) += c.k;
      at(C, partner, partner) += c.k;
      at(C, j, partner) -= c.k;
      at(C, partner, j) -= c.k;
    }
  }
  if (pad) {
    M[n] = p.m_x;
    at(K, n, n) += p.k_p0;
    at(C, n, n) += p.c_p;
  }
  for (int i = 0; i < d; ++i) {
    at(C, i, i) += p.rayleigh_alpha * M[i];
    for (int j = 0; j < d; ++j) at(C, i, j) += p.rayleigh_beta * at(K, i, j);
  }
  // State (u, u'): A = [[0, I], [-M^-1 K, -M^-1 C]].
  gsl_matrix* A = gsl_matrix_calloc(2 * d, 2 * d);
  for (int i = 0; i < d; ++i) {
    gsl_matrix_set(A, i, d + i, 1.0);
    for (int j = 0; j < d; ++j) {
      gsl_matrix_set(A, d + i, j, -at(K, i, j) / M[i]);
      gsl_matrix_set(A, d + i, d + j, -at(C, i, j) / M[i]);
    }
  }
  gsl_vector_complex* eval = gsl_vector_complex_alloc(2 * d);
  gsl_matrix_complex* evec = gsl_matrix_complex_alloc(2 * d, 2 * d);
  gsl_eigen_nonsymmv_workspace* w = gsl_eigen_nonsymmv_alloc(2 * d);
  gsl_eigen_nonsymmv_params(1, w);  // balance: k_c and k_p may differ by orders
  gsl_eigen_nonsymmv(A, eval, evec, w);
  gsl_eigen_nonsymmv_free(w);

  std::vector<double> basis(p.kind == ModelKind::OneDof ? 0 : n * n), basis_norm(n, 0.0);
  if (p.kind != ModelKind::OneDof)
    for (int q = 0; q < n; ++q)
      for (int j = 0; j < n; ++j) {
        basis[q * n + j] = chain_shape(p, q, j);
        basis_norm[q] += basis[q * n + j] * basis[q * n + j];
      }
  std::vector<Eigenmode> out;
  if (shapes) shapes->clear();
  for (int i = 0; i < 2 * d; ++i) {
    const gsl_complex z = gsl_vector_complex_get(eval, i);
    cplx l(GSL_REAL(z), GSL_IMAG(z));
    if (std::abs(l.imag()) <= 1e-13 * std::abs(l)) l.imag(0.0);
    if (l.imag() < 0) continue;
    ModeShape s(d);
    for (int j = 0; j < d; ++j) {
      const gsl_complex e = gsl_matrix_complex_get(evec, j, i);
      s[j] = cplx(GSL_REAL(e), GSL_IMAG(e));
    }
    Eigenmode m{p.kind == ModelKind::OneDof ? ModeFamily::OneDof : ModeFamily::Chain, 0, l};
    if (p.kind != ModelKind::OneDof) {
      // The chain mode the blocks project onto most.
      double best = -1;
      for (int q = 0; q < n; ++q) {
        cplx c = 0;
        for (int j = 0; j < n; ++j) c += basis[q * n + j] * s[j];
        const double weight = std::norm(c) / basis_norm[q];
        if (weight > best) {
          best = weight;
          m.index = q;
        }
      }
      if (pad && pad_share(p, s) > 0.5) {
        m.family = ModeFamily::Pad;
        m.index = 0;
      }
    }
    normalise(s);
    out.push_back(m);
    if (shapes) shapes->push_back(std::move(s));
  }
  gsl_matrix_free(A);
  gsl_vector_complex_free(eval);
  gsl_matrix_complex_free(evec);
  return out;
}

double largest_growth(const std::vector<Eigenmode>& modes, ModeFamily family) {
  double g = -std::numeric_limits<double>::infinity();
  for (const Eigenmode& m : modes)
    if (m.family == family) g = std::max(g, m.growth());
  return g;
}

GrowthFit fit_growth(const std::vector<double>& t, const std::vector<double>& y) {
  GrowthFit f;
  const std::size_t n = std::min(t.size(), y.size());
  double first = 0, last = 0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if ((y[i - 1] < 0) != (y[i] < 0)) {
      const double tc = t[i - 1] + (t[i] - t[i - 1]) * y[i - 1] / (y[i - 1] - y[i]);
      if (f.crossings++ == 0) first = tc;
      last = tc;
    }
    if (i + 1 < n && std::abs(y[i]) >= std::abs(y[i - 1]) && std::abs(y[i]) > std::abs(y[i + 1]) &&
        (y[i - 1] < 0) == (y[i] < 0) && (y[i + 1] < 0) == (y[i] < 0)) {
      // Parabola through the three samples (equally spaced in t).
      const double a = y[i - 1], b = y[i], c = y[i + 1];
      const double denom = a - 2 * b + c;
      const double off = denom != 0 ? 0.5 * (a - c) / denom : 0.0;
      const double peak = b - 0.25 * (a - c) * off;
      const double tp = t[i] + off * (t[i + 1] - t[i]);
      const double ly = std::log(std::abs(peak));
      sx += tp;
      sy += ly;
      sxx += tp * tp;
      sxy += tp * ly;
      ++f.extrema;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  f.frequency = f.crossings >= 2 ? (f.crossings - 1) / (2.0 * (last - first)) : nan;
  const double m = f.extrema;
  f.growth = f.extrema >= 2 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : nan;
  return f;
}

}  // namespace bkq
