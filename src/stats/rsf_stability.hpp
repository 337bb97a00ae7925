// Linear stability of rate-and-state steady sliding (model/laws/rsf.hpp, engine/rsf_cycle.hpp)
// at the plate rate V_pl, theta = D_c/V_pl. With x = ln(V/V_pl), phi = ln(theta V_pl/D_c) and
// omega = V_pl/D_c, both state laws linearise to phi' = -omega (x + phi). A block on a spring k
// with inertia m per unit area, radiation damping eta, friction slopes f_lnv = V df/dV and
// f_lntheta = theta df/dtheta at steady state (a and b_rsf for the log form) then has the
// characteristic polynomial (Laplace variable s), with c = eta + sigma f_lnv/V_pl and
// B = sigma f_lntheta/D_c:
//   m s^3 + (m omega + c) s^2 + (k + c omega - B) s + k omega = 0
// (quasi-dynamic: m = 0, a quadratic; the 2x2 Jacobian in (x, phi) is
//   [[(B - k)/c, B/c], [-omega, -omega]], trace (B - k)/c - omega, determinant k omega/c).
// The Hopf point (s = i Omega) gives the critical stiffness and its frequency:
//   k_crit = (B - c omega)(1 + m omega/c)
//          = [sigma (b_rsf - a) - eta V_pl]/D_c [1 + m V_pl^2/(D_c (sigma a + eta V_pl))] (log
//          form),
//   Omega^2 = k_crit omega/(m omega + c);
// eta = m = 0 is Ruina's quasi-static sigma (b_rsf - a)/D_c, eta = 0 Rice & Ruina's (1983)
// inertial correction. Steady sliding is unstable for k < k_crit. A chain's mode q has the
// stiffness k + k_c mu_q, mu_q the graph Laplacian's eigenvalue (4 sin^2(pi q/(2N)) free,
// 4 sin^2(pi q/N) ring), so mode q is unstable iff k + k_c mu_q < k_crit. Any stencil of springs
// (dx, dy, k_s) on a grid of nx x rows gives mode (q_x, q_y) the stiffness
//   k + sum_s 2 k_s [1 - cos(dx th_x + dy th_y)],  th = pi q/n on free edges, 2 pi q/n periodic:
// exact on periodic edges and for nearest neighbours on free ones (the chain's mu_q, and a
// lattice's sum of its two axes' mu); for longer springs on free edges the sum is the stencil's
// Fourier symbol at the free chain's wavenumbers, an approximation near the edges.
//
// Per-block laws (a, b_rsf, D_c varying along the chain or lattice) break the modal reduction:
// the modes are no longer plane waves. Steady sliding at V_pl with theta_j = D_cj/V_pl is still
// a fixed point (every block slides at V_pl, no spring is stretched further), and its
// linearisation in x_j = ln(V_j/V_pl), phi_j = ln(theta_j V_pl/D_cj) and, for inertia,
// xi_j = slip_j/V_pl - t (the slip's offset in seconds of plate motion) reads, with
// omega_j = V_pl/D_cj, K = k I + the springs' Laplacian (the integrator's neighbour lists),
// S_j = sigma f_lnv,j and T_j = sigma f_lntheta,j (sigma a_j and sigma b_j for the log form):
//   phi_j' = -omega_j (x_j + phi_j)                                           (both state laws)
//   quasi-dynamic  (S_j + eta V_pl) x_j' = -V_pl (K x)_j + T_j omega_j (x_j + phi_j)
//   inertial       xi_j' = x_j,   m V_pl x_j' = -V_pl (K xi)_j - (S_j + eta V_pl) x_j - T_j phi_j
// a dense 2N x 2N (3N x 3N) matrix whose eigenvalues GSL's gsl_eigen_nonsymmv gives in O(N^3).
// For one law it has the modal reduction's roots, mode by mode.
#pragma once

#include <complex>
#include <vector>

#include "engine/rsf_cycle.hpp"

namespace bkq {

// The roots s of the characteristic polynomial of block 0's law at spring stiffness k (2 for
// quasi-dynamic, 3 for inertial), ordered by decreasing real part.
std::vector<std::complex<double>> rsf_eigenvalues(const RsfModel& m, double k);
// k_crit with the model's radiation damping and, for inertial dynamics, its mass.
double rsf_critical_stiffness(const RsfModel& m);
// Omega/(2 pi) at k = k_crit [Hz] (NaN when k_crit <= 0: stable at every stiffness).
double rsf_critical_frequency(const RsfModel& m);
// mu_q of the chain's nearest-neighbour Laplacian (q = 0..N-1).
double rsf_chain_laplacian(int n, bool periodic, int q);
// The springs' stiffness of mode (qx, qy), qx < m.nx(), qy < m.rows (see above).
double rsf_mode_stiffness(const RsfModel& m, int qx, int qy);

// Whether every block has block 0's law (a, b_rsf, D_c, mu*, V*): the modal analysis above
// describes the chain only then.
bool rsf_homogeneous(const RsfModel& m);
// The most blocks rsf_dense_eigenvalues takes: O(N^3), half a minute of CPU for a quasi-dynamic
// 2000 x 2000 matrix, minutes for an inertial 3000 x 3000 one.
inline constexpr int kRsfDenseLimit = 1000;
// The per-block linearisation above as a dense row-major d x d matrix, d = 2N (quasi-dynamic)
// or 3N (inertial), in the order (x_0..x_N-1, phi_0..phi_N-1[, xi_0..xi_N-1]).
std::vector<double> rsf_linearisation(const RsfModel& m);
// Every eigenvalue of the per-block linearisation above (2N quasi-dynamic, 3N inertial), complex
// pairs both listed, ordered by decreasing real part (then decreasing imaginary part).
std::vector<std::complex<double>> rsf_dense_eigenvalues(const RsfModel& m);

}  // namespace bkq
