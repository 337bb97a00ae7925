// QDYN's regression case "stickslip" (one quasi-dynamic spring-block, aging law) on each of
// `n` blocks, for the rate-and-state tests and bench: G = 2e10 Pa, L = 10 m, k = G/L,
// sigma = 5e6 Pa, a = 0.01, b = 0.025, D_c = 1e-5 m, mu* = 0.6, V* = V_pl = 1e-6 m/s,
// c_s = 3000 m/s, eta = G/(2 c_s). No coupling and one row unless the caller sets them.
#pragma once

#include "engine/rsf_cycle.hpp"

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

}  // namespace bkq::test
