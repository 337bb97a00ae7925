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
// two offsets reach the same block. A lattice would list offsets in the plane (one of each
// pair +-d) with the same meaning. The viscous coupling (model.viscosity = eta) puts a
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
// The dashpots of model.viscosity = eta on the same stencil (Myers & Langer 1993): eta_r =
// eta k_r / k_c in the stencil's shape, {(1, eta)} for nearest neighbours; empty when off.
CouplingStencil damper_stencil(const ModelParams& p);

}  // namespace bkq
