// The coupling between blocks as a stencil: a list of (offset, spring) pairs, each a spring
// k_r between every block and the block `offset` away on either side (the stencil is
// symmetric, so only the positive offsets are listed). Nearest neighbours are the stencil
// {(1, k_c)}; model.coupling = range couples each block to all blocks within R = model.range
// by equal springs, model.coupling = power by springs decaying as r^-p (p =
// model.coupling_exponent), cut off at R. The normalisation keeps the springs' sum at k_c:
//   range  k_r = k_c / R                          (Xia, Gould, Klein & Rundle 2005, PRL 95 248501)
//   power  k_r = k_c r^-p / sum_{s=1..R} s^-p
// so both give k_c at R = 1 and an interior block feels a total neighbour stiffness 2 k_c for
// every R (the uniform mode's and the fastest mode's bounds do not move with R). Free ends
// drop the springs that would reach past the chain; a periodic chain needs 2R < N so that no
// two offsets reach the same block. The viscous coupling (model.viscosity = eta) puts a
// dashpot beside every spring, with the same shape and their sum eta.
#pragma once

#include <vector>

#include "model/parameters.hpp"

namespace bkq {

struct CouplingSpring {
  int offset;  // r >= 1: block j is coupled to j - r and j + r
  double k;    // the spring's stiffness
};
using CouplingStencil = std::vector<CouplingSpring>;

// The scene's stencil: empty without neighbour springs, {(1, k_c)} for nearest neighbours.
CouplingStencil coupling_stencil(const ModelParams& p);
// A lattice's springs (ModelParams::lattice): site (x, y) is coupled to (x - dx, y - dy) and
// (x + dx, y + dy) by k; one of each pair is listed (dx > 0, or dx = 0 and dy > 0). Nearest
// neighbours are {(1, 0, k_c), (0, 1, k_c_y)} (springs of 0 left out). range and power couple
// every site within the disc 0 < r <= R, r^2 = dx^2 + dy^2, by
//   k = w(r) (k_c dx^2 + k_c_y dy^2) / r^2 / sum_{half disc} w(r) dx^2 / r^2,
// w = 1 (range) or r^-p (power): the springs sum to k_c + k_c_y, as nearest neighbours' do
// (R = 1 gives them), so an interior site feels 2 (k_c + k_c_y) for every R and the fastest
// mode's bound does not move; with k_c = k_c_y their projections along and across are k_c each.
// Free edges drop the springs that would reach past them; periodic edges need 2R < the sites along
// that axis.
struct LatticeSpring {
  int dx, dy;
  double k;
};
using LatticeStencil = std::vector<LatticeSpring>;
LatticeStencil lattice_stencil(const ModelParams& p);

// The dashpots of model.viscosity = eta on the same stencil (Myers & Langer 1993): eta_r =
// eta k_r / k_c in the stencil's shape, {(1, eta)} for nearest neighbours; empty when off.
CouplingStencil damper_stencil(const ModelParams& p);

}  // namespace bkq
