// The coupling stencil's springs; see coupling.hpp for the normalisation.
#include "model/coupling.hpp"

#include <cmath>

namespace bkq {

CouplingStencil coupling_stencil(const ModelParams& p) {
  if (!p.has_neighbours()) return {};
  const int R = p.reach();
  if (R == 1) return {{1, p.k_c}};
  CouplingStencil s;
  s.reserve(R);
  double norm = 0;
  for (int r = 1; r <= R; ++r)
    norm += p.coupling == Coupling::Power ? std::pow(r, -p.coupling_exponent) : 1.0;
  for (int r = 1; r <= R; ++r) {
    const double weight = p.coupling == Coupling::Power ? std::pow(r, -p.coupling_exponent) : 1.0;
    s.push_back({r, p.k_c * weight / norm});
  }
  return s;
}

}  // namespace bkq
