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

}  // namespace bkq
