// The coupling stencil's springs; see coupling.hpp for the normalisation.
#include "model/coupling.hpp"

#include <cmath>

namespace bkq {

namespace {

// The stencil's shape (range or power, reach R) with the elements summing to `total`.
CouplingStencil stencil_of(const ModelParams& p, double total) {
  const int R = p.reach();
  if (R == 1) return {{1, total}};
  CouplingStencil s;
  s.reserve(R);
  double norm = 0;
  for (int r = 1; r <= R; ++r)
    norm += p.coupling == Coupling::Power ? std::pow(r, -p.coupling_exponent) : 1.0;
  for (int r = 1; r <= R; ++r) {
    const double weight = p.coupling == Coupling::Power ? std::pow(r, -p.coupling_exponent) : 1.0;
    s.push_back({r, total * weight / norm});
  }
  return s;
}

}  // namespace

CouplingStencil coupling_stencil(const ModelParams& p) {
  if (!p.has_neighbours()) return {};
  return stencil_of(p, p.k_c);
}

CouplingStencil damper_stencil(const ModelParams& p) {
  if (!p.viscous()) return {};
  return stencil_of(p, p.viscosity);
}

}  // namespace bkq
