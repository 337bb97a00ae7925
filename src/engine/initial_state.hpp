// The starting configuration of a run: block displacements drawn uniformly from
// ±disorder·D0 (D0 = F0 m_u/k_p, the slip that unloads a pulling spring; Ferre 2018 §3.4 uses
// ±0.75), all blocks stuck, the substrate at 0. The generator is std::mt19937_64 with our
// own conversion to [0, 1), so a seed gives the same chain on every platform.
#pragma once

#include <cstdint>
#include <random>

#include "model/chain.hpp"

namespace bkq {

inline double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// pad_at_rest: put the pad at its static balance (event-driven mode); otherwise at 0.
inline ChainState initial_state(const ChainForces& forces, std::uint64_t seed, double disorder,
                                bool pad_at_rest) {
  const ModelParams& p = forces.params();
  ChainState st;
  st.resize(p.n);
  std::mt19937_64 rng(seed);
  const double amplitude = disorder * p.F0 * p.m_u / p.k_p;
  for (int j = 0; j < p.n; ++j) st.w[j] = amplitude * (2.0 * uniform01(rng) - 1.0);
  if (law_traits(p.law).frictionless) st.mobile.assign(p.n, 1.0);
  st.recompute_sum_w();
  if (p.pad_moves() && pad_at_rest) st.x = forces.pad_equilibrium(st.sum_w, st.s);
  return st;
}

}  // namespace bkq
