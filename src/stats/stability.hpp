// Linear stability of steady sliding (Sinou, Chiello & Charroyer 2019 §2.3 and §3.2 applied to
// thesis eq. 3.1). About the sliding equilibrium (model/equilibrium.hpp) a small perturbation obeys
// M u'' + C u' + K u = 0, where friction enters as a damping m_u phi'(v) on every block (negative
// for a velocity-weakening law), C also holds the pad damper c_p, the 1DOF damper c_u and the
// Rayleigh damping alpha_M M + beta_K K (model/parameters.hpp), and M, K are the masses and springs
// of blocks and pad. Eigenvalues lambda of det(lambda^2 M + lambda C + K) = 0 give each mode's
// growth rate Re lambda and frequency Im lambda / 2 pi; steady sliding is unstable when any Re
// lambda > 0.
//
// Two solvers that check each other:
//   modal  the exact reduction of the uniform chain: the chain's graph Laplacian has the
//          cosine modes (free ends) or Fourier modes (ring) with eigenvalues mu_q, and every
//          mode q but the uniform one (q = 0) leaves the pad alone, so it is one quadratic
//          m_u lambda^2 + c_q lambda + k_q = 0, k_q = k_p + k_c mu_q,
//          c_q = m_u phi' + c_u + alpha_M m_u + beta_K k_q + eta_q (the dashpots of
//          model.viscosity). The uniform mode of bkp is
//          coupled to the pad: a quartic. O(N): N = 10^5 takes milliseconds.
//   dense  the first-order state matrix [[0, I], [-M^-1 K, -M^-1 C]] (2N + 2 for bkp, 2N
//          for bk, 2 for 1dof) with GSL's gsl_eigen_nonsymmv; O(N^3), for N up to a few
//          hundred.
// Families: `chain` (index q: the chain's q-th cosine/Fourier mode; for bkp chain 0 is
// the block-dominated root of the quartic), `pad` (bkp: the pad-dominated root of the
// quartic, index 0), `1dof`. A complex pair is listed once, with Im lambda > 0; an
// overdamped mode lists its two real roots.
#pragma once

#include <complex>
#include <vector>

#include "model/parameters.hpp"

namespace bkq {

enum class ModeFamily { Chain, Pad, OneDof };
const char* to_string(ModeFamily f);

struct Eigenmode {
  ModeFamily family = ModeFamily::Chain;
  int index = 0;
  std::complex<double> lambda;
  double growth() const { return lambda.real(); }
  double frequency() const;  // Im lambda / 2 pi
  bool unstable() const { return lambda.real() > 0; }
};

// Displacement amplitudes of a mode: blocks 0..N-1, then the pad (bkp only), normalised
// so that the largest is 1 (real).
using ModeShape = std::vector<std::complex<double>>;

// Eigenvalue mu_q of the chain's graph Laplacian (0 without neighbour springs); with range
// coupling (model/coupling.hpp) that of the stencil's stiffness over k_c, sum_r (k_r/k_c) 4
// sin^2(pi q r/N), exact on a ring only: a free chain with range coupling has no cosine modes
// (its cut springs), and the modal solver must not be used there (dense_eigenmodes is exact).
double laplacian_eigenvalue(const ModelParams& p, int q);
// Block j's amplitude in chain mode q: cos(pi q (j + 1/2)/N) for free ends; for a ring
// cos(2 pi q j/N) for q <= N/2 and sin(2 pi q j/N) above (q and N - q span one pair).
double chain_shape(const ModelParams& p, int q, int j);

// Eigenvalue of chain mode q for the dashpots of model.viscosity (their stencil's
// Laplacian, times eta; 0 without viscosity): eta 4 sin^2(...) for nearest neighbours.
double damper_eigenvalue(const ModelParams& p, int q);
// The modal damping of chain mode q (per unit block mass, the "c_q / m_u" above without
// friction): c_u/m_u + alpha_M + beta_K k_q/m_u + eta_q/m_u (eta_q: damper_eigenvalue). Chain mode
// q (q >= 1 for bkp) is unstable iff -phi'(v) exceeds it.
double chain_mode_damping(const ModelParams& p, int q);

// (a) The exact modal reduction; `slope` is phi'(v) per unit block mass.
std::vector<Eigenmode> modal_eigenmodes(const ModelParams& p, double slope);
// The shape of a mode of modal_eigenmodes.
ModeShape modal_shape(const ModelParams& p, double slope, const Eigenmode& m);

// (b) The dense state matrix's eigenvalues, each classified by its eigenvector (the chain
// mode it projects onto most; pad or chain 0 by the pad's share of the kinetic energy);
// with `shapes` also the displacement eigenvectors, normalised like ModeShape.
std::vector<Eigenmode> dense_eigenmodes(const ModelParams& p, double slope,
                                        std::vector<ModeShape>* shapes = nullptr);

// The largest growth rate of the modes of one family (-inf when it has none).
double largest_growth(const std::vector<Eigenmode>& modes, ModeFamily family);

// Growth rate and frequency of a sampled signal y(t) = A e^{s t} cos(w t + c) (a modal
// coordinate of a simulation): s from a least-squares line through ln |y| at the extrema
// of |y| (parabolic interpolation between samples), w from the mean spacing pi/w of the
// zero crossings (linear interpolation). NaN when the signal has fewer than two of either.
struct GrowthFit {
  double growth = 0;
  double frequency = 0;  // w / 2 pi
  int extrema = 0, crossings = 0;
};
GrowthFit fit_growth(const std::vector<double>& t, const std::vector<double>& y);

}  // namespace bkq
