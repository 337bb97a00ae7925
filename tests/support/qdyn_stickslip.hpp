// QDYN's regression case "stickslip" (one quasi-dynamic spring-block, aging law) on each of
// `n` blocks, for the rate-and-state tests and bench: G = 2e10 Pa, L = 10 m, k = G/L,
// sigma = 5e6 Pa, a = 0.01, b = 0.025, D_c = 1e-5 m, mu* = 0.6, V* = V_pl = 1e-6 m/s,
// c_s = 3000 m/s, eta = G/(2 c_s). No coupling and one row unless the caller sets them.
#pragma once

#include "engine/rsf_cycle.hpp"
#include "model/rsf_nucleation.hpp"

namespace bkq::test {

inline RsfModel qdyn_stickslip(int n = 1) {
  RsfModel m;
  rsf::Params p;
  p.a = 0.01;
  p.b_rsf = 0.025;
  p.dc = 1e-5;
  p.mu0 = 0.6;
  p.v0 = 1e-6;
  m.law.assign(n, rsf::Law(p));
  m.sigma = 5e6;
  m.k = 2e10 / 10;
  m.v_pl = 1e-6;
  m.eta = 2e10 / (2 * 3000.0);
  return m;
}

// The same block as one slider of the closed forms: QDYN's a, b, D_c and sigma, k = 2e9 Pa/m,
// stressing rate k V_pl with V_pl = 1e-6 m/s.
inline rsf::Slider qdyn_slider() {
  rsf::Slider s;
  s.a = 0.01;
  s.b_rsf = 0.025;
  s.dc = 1e-5;
  s.sigma = 5e6;
  s.k_eff = 2e9;
  s.stressing_rate = 2e9 * 1e-6;
  return s;
}

// One block under the full aging law with slider s's a, b, unloading stiffness and stressing
// rate (QDYN's block otherwise, no radiation damping), for the cycle integrator.
inline RsfModel full_law_block(const rsf::Slider& s) {
  RsfModel m = qdyn_stickslip(1);
  rsf::Params p = m.law[0].params();
  p.a = s.a;
  p.b_rsf = s.b_rsf;
  m.law[0] = rsf::Law(p);
  m.eta = 0;
  m.k = s.k_eff;
  m.v_pl = s.stressing_rate / s.k_eff;
  return m;
}

}  // namespace bkq::test
