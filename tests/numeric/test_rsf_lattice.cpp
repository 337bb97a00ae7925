// Rate-and-state on lattices and with range and power coupling (engine/rsf_cycle.hpp): the
// neighbour lists the coupling sums run over, the springs' action and reaction, a lattice of
// identical rows that moves as its chain, and the stability of a lattice's modes.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "engine/rsf_cycle.hpp"
#include "engine/rsf_events.hpp"
#include "model/coupling.hpp"
#include "stats/rsf_stability.hpp"
#include "support/qdyn_stickslip.hpp"

namespace bkq {
namespace {

// QDYN's stick-slip block (test_rsf.cpp) on every site of an nx x rows grid.
RsfModel grid(int nx, int rows) {
  RsfModel m = test::qdyn_stickslip(nx * rows);
  m.rows = rows;
  return m;
}

// A rough start: every block's slip rate different.
std::vector<double> rough(int n) {
  std::vector<double> v(n);
  for (int j = 0; j < n; ++j) v[j] = 1e-6 * (1 + 0.5 * std::sin(1.3 * j + 0.2 * j * j));
  return v;
}

// The neighbour lists: a nearest-neighbour lattice's interior site has four, a free edge's
// three, a free corner's two, a periodic axis none missing; every spring is listed from both
// ends with the same stiffness.
TEST(RsfLattice, NeighbourListsFollowTheEdges) {
  RsfModel m = grid(5, 4);
  m.springs = {{1, 0, 3e8}, {0, 1, 7e8}};
  const auto count = [](const RsfNeighbours& nb, int j) { return nb.start[j + 1] - nb.start[j]; };
  RsfNeighbours nb = rsf_neighbours(m);
  EXPECT_EQ(count(nb, 0), 2);      // corner (0, 0)
  EXPECT_EQ(count(nb, 2), 3);      // edge (2, 0)
  EXPECT_EQ(count(nb, 5 + 2), 4);  // interior (2, 1)
  m.periodic = true;
  nb = rsf_neighbours(m);
  EXPECT_EQ(count(nb, 0), 3);  // periodic along x, free across
  m.periodic_y = true;
  nb = rsf_neighbours(m);
  for (int j = 0; j < m.n(); ++j) EXPECT_EQ(count(nb, j), 4);
  // Symmetric: k_ij = k_ji, summed over the list.
  for (bool px : {false, true}) {
    m.periodic = m.periodic_y = px;
    nb = rsf_neighbours(m);
    std::vector<double> dense(m.n() * m.n(), 0.0);
    for (int j = 0; j < m.n(); ++j)
      for (int e = nb.start[j]; e < nb.start[j + 1]; ++e) dense[j * m.n() + nb.index[e]] += nb.k[e];
    for (int i = 0; i < m.n(); ++i)
      for (int j = 0; j < m.n(); ++j) EXPECT_EQ(dense[i * m.n() + j], dense[j * m.n() + i]);
  }
}

// Range and power chains: 2R partners inside, springs summing to 2 k_c (model/coupling.hpp's
// normalisation); the chain's ends drop those that would reach past it.
TEST(RsfLattice, RangeAndPowerChainsHaveTheirStencil) {
  for (Coupling kind : {Coupling::Range, Coupling::Power}) {
    ModelParams p;
    p.n = 40;
    p.k_c = 2e9;
    p.coupling = kind;
    p.range = 5;
    p.coupling_exponent = 2;
    RsfModel m = grid(40, 1);
    for (const CouplingSpring& c : coupling_stencil(p)) m.springs.push_back({c.offset, 0, c.k});
    const RsfNeighbours nb = rsf_neighbours(m);
    double interior = 0;
    for (int e = nb.start[20]; e < nb.start[21]; ++e) interior += nb.k[e];
    EXPECT_EQ(nb.start[21] - nb.start[20], 10);
    EXPECT_NEAR(interior, 4e9, 1e-3);
    EXPECT_EQ(nb.start[1] - nb.start[0], 5);  // the first block: only the right side
  }
}

// Action and reaction: the springs' stresses sum to zero over the blocks, on every edge kind
// and stencil, after a rough stretch of cycles.
TEST(RsfLattice, SpringStressesSumToZero) {
  for (int variant = 0; variant < 3; ++variant) {
    RsfModel m = grid(6, 5);
    m.periodic = variant > 0;
    m.periodic_y = variant > 1;
    ModelParams p;
    p.n = 30;
    p.rows = 5;
    p.k_c = 1e9;
    p.k_c_y = 1e9;
    p.coupling = variant == 2 ? Coupling::Power : Coupling::Nearest;
    p.range = 2;
    m.springs = lattice_stencil(p);
    RsfCycle c(m, 1e-8, rough(m.n()), {10});
    c.advance_to(500);
    // The springs' share of block j's stress is tau_j - k (V_pl t - slip_j) - tau0_j, tau0_j
    // the start stress (a fresh cycle's at t = 0); over all blocks the shares cancel.
    RsfCycle fresh(m, 1e-8, rough(m.n()), {10});
    double sum = 0, scale = 0;
    for (int j = 0; j < m.n(); ++j) {
      sum += c.elastic_stress(j) - m.k * (m.v_pl * c.t() - c.slip(j)) - fresh.elastic_stress(j);
      scale += std::fabs(c.slip(j));
    }
    EXPECT_GT(scale, 0);
    EXPECT_NEAR(sum, 0, 1e-9 * m.n() * 5e6) << "variant " << variant;
  }
}

// A lattice whose rows start alike moves as its chain: the across-strike springs are never
// stretched, bit for bit (the chain's sums are the lattice's with zero terms added).
TEST(RsfLattice, IdenticalRowsMoveAsTheirChain) {
  const int nx = 8, rows = 3;
  RsfModel chain = grid(nx, 1);
  chain.springs = {{1, 0, 2e9}};
  RsfModel lattice = grid(nx, rows);
  lattice.springs = {{1, 0, 2e9}, {0, 1, 5e9}};
  std::vector<double> v0 = rough(nx), v(nx * rows);
  for (int j = 0; j < nx * rows; ++j) v[j] = v0[j % nx];
  RsfCycle a(chain, 1e-8, v0, {10}), b(lattice, 1e-8, v, {10});
  RsfEventDetector ea(1e-3), eb(1e-3);
  int events = 0;
  while (a.t() < 3000) {
    a.step(3000);
    b.step(3000);
    ASSERT_EQ(a.t(), b.t());
    const auto x = ea.observe(a);
    const auto y = eb.observe(b);
    ASSERT_EQ(x.has_value(), y.has_value());
    if (x) {
      ++events;
      EXPECT_EQ(y->blocks, rows * x->blocks);
      EXPECT_EQ(y->first_block, x->first_block);
      EXPECT_EQ(y->last_block, x->last_block);
      EXPECT_EQ(y->first_row, 0);
      EXPECT_EQ(y->last_row, rows - 1);
      EXPECT_DOUBLE_EQ(y->moment, rows * x->moment);
    }
  }
  EXPECT_GT(events, 2);
  for (int j = 0; j < nx * rows; ++j) EXPECT_EQ(b.ln_v(j), a.ln_v(j % nx)) << j;
}

// The lattice's modes: mode (q_x, q_y) has the stiffness of its two axes' Laplacians, and a
// periodic lattice's stencil symbol is the dense stiffness matrix's eigenvalue.
TEST(RsfLattice, ModeStiffnessOfTheLattice) {
  RsfModel m = grid(6, 4);
  m.springs = {{1, 0, 3e8}, {0, 1, 7e8}};
  for (int qx = 0; qx < 6; ++qx)
    for (int qy = 0; qy < 4; ++qy)
      EXPECT_NEAR(rsf_mode_stiffness(m, qx, qy),
                  3e8 * rsf_chain_laplacian(6, false, qx) + 7e8 * rsf_chain_laplacian(4, false, qy),
                  1e-6);
  // Periodic, a longer stencil: apply the dense matrix to the mode's plane wave.
  m.periodic = m.periodic_y = true;
  m.law.assign(8 * 8, m.law[0]);
  m.rows = 8;
  ModelParams p;
  p.n = 64;
  p.rows = 8;
  p.k_c = 1e9;
  p.k_c_y = 1e9;
  p.coupling = Coupling::Range;
  p.range = 2;
  m.springs = lattice_stencil(p);
  const RsfNeighbours nb = rsf_neighbours(m);
  for (int qx : {0, 1, 3})
    for (int qy : {0, 2}) {
      const auto wave = [&](int j) {
        return std::cos(2 * std::numbers::pi * (qx * (j % 8) + qy * (j / 8)) / 8.0);
      };
      const int j = 8 * 3 + 5;
      double applied = 0;  // -(sum_i k_ji (u_i - u_j)) = mu u_j
      for (int e = nb.start[j]; e < nb.start[j + 1]; ++e)
        applied -= nb.k[e] * (wave(nb.index[e]) - wave(j));
      if (std::fabs(wave(j)) > 0.1) {
        EXPECT_NEAR(applied / wave(j), rsf_mode_stiffness(m, qx, qy), 1e-3 * 4e9);
      }
    }
}

}  // namespace
}  // namespace bkq
