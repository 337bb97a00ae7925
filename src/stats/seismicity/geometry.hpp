// Where events happen, for the statistics that measure distances (the Mogi picture of
// spacetime.hpp): a chain of N blocks, or a lattice of nx columns along strike by ny rows
// across it. A hypocentre is the trigger site (x, y); the distance between two is the
// Euclidean one in site spacings, sqrt(dx^2 + dy^2), where along a periodic axis dx is the
// shorter way round, min(|x - x'|, nx - |x - x'|). A chain (ny = 1) keeps the plain
// |x - x'| along it (no wrap), as its statistics always had.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace bkq::seis {

struct Geometry {
  int nx = 1, ny = 1;  // columns along strike (model.blocks), rows across (model.rows)
  bool periodic_x = false, periodic_y = false;

  static Geometry chain(int blocks) { return {std::max(1, blocks), 1, false, false}; }
  bool lattice() const { return ny > 1; }
  int sites() const { return nx * ny; }
  // The separation along one axis of n sites.
  static int separation(int a, int b, int n, bool periodic) {
    const int d = std::abs(a - b);
    return periodic ? std::min(d, n - d) : d;
  }
  double distance(int x1, int y1, int x2, int y2) const {
    if (!lattice()) return std::abs(x1 - x2);
    const double dx = separation(x1, x2, nx, periodic_x);
    const double dy = separation(y1, y2, ny, periodic_y);
    return std::sqrt(dx * dx + dy * dy);
  }
  // The largest distance two sites can have.
  double max_distance() const {
    if (!lattice()) return nx - 1;
    const double dx = periodic_x ? nx / 2 : nx - 1;
    const double dy = periodic_y ? ny / 2 : ny - 1;
    return std::sqrt(dx * dx + dy * dy);
  }
};

}  // namespace bkq::seis
