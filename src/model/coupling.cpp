// The coupling stencil's springs; see coupling.hpp for the normalisation.
#include "model/coupling.hpp"

#include <cmath>
#include <utility>

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

LatticeStencil lattice_stencil(const ModelParams& p) {
  if (!p.has_neighbours() || !p.lattice()) return {};
  const int R = p.reach();
  if (R == 1) {
    LatticeStencil s;
    if (p.k_c != 0) s.push_back({1, 0, p.k_c});
    if (p.k_c_y != 0) s.push_back({0, 1, p.k_c_y});
    return s;
  }
  auto weight = [&](int r2) {
    return p.coupling == Coupling::Power ? std::pow(std::sqrt(double(r2)), -p.coupling_exponent)
                                         : 1.0;
  };
  // The half disc, dx = 0 .. R and dy = -R .. R, in that order.
  double norm = 0;
  std::vector<std::pair<int, int>> half;
  for (int dx = 0; dx <= R; ++dx)
    for (int dy = -R; dy <= R; ++dy) {
      const int r2 = dx * dx + dy * dy;
      if (r2 == 0 || r2 > R * R || (dx == 0 && dy < 0)) continue;
      half.emplace_back(dx, dy);
      norm += weight(r2) * dx * dx / r2;
    }
  LatticeStencil s;
  s.reserve(half.size());
  for (const auto& [dx, dy] : half) {
    const int r2 = dx * dx + dy * dy;
    s.push_back({dx, dy, weight(r2) * (p.k_c * dx * dx + p.k_c_y * dy * dy) / r2 / norm});
  }
  return s;
}

CouplingStencil damper_stencil(const ModelParams& p) {
  if (!p.viscous()) return {};
  return stencil_of(p, p.viscosity);
}

}  // namespace bkq
