// Seismicity before mainshocks; see spacetime.hpp.
#include "stats/seismicity/spacetime.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace bkq::seis {

double MagSums::events() const {
  double n = 0;
  for (double c : count) n += c;
  return n;
}

Estimate MagSums::b(double mu_c) const {
  const int k0 = bin(mu_c + 1e-9 * kWidth);
  const double edge = low(k0);
  double n = 0, s = 0;
  for (int k = k0; k < kBins; ++k) {
    n += count[static_cast<std::size_t>(k)];
    s += sum[static_cast<std::size_t>(k)];
  }
  const double excess = s - n * edge;
  if (n < 2 || !(excess > 0)) return {};
  const double b = n / excess;
  return {b, b / std::sqrt(n)};
}

double MagSums::max_curvature() const {
  const auto it = std::max_element(count.begin(), count.end());
  if (*it <= 0) return NAN;
  return low(static_cast<int>(it - count.begin()));
}

namespace {
// Distances 0 .. floor(largest): on a chain of N blocks, N of them.
int distances(const Geometry& g) {
  return static_cast<int>(std::floor(g.max_distance())) + 1;
}
}  // namespace

SpaceTime::SpaceTime(const Geometry& geometry)
    : geo_(geometry),
      band_(std::max(1, (distances(geo_) + kBands - 1) / kBands)),
      bands_((distances(geo_) + band_ - 1) / band_) {
  count_.assign(bins_.size(), std::vector<double>(static_cast<std::size_t>(bands_), 0.0));
  exposure_ = count_;
  before_.resize(bins_.size());
}

void SpaceTime::add(const Quake& q, const Lookback& lookback) {
  if (!q.mainshock) {
    all_.add(q.mu);
    return;
  }
  if (!lookback.started()) return;
  ++mainshocks_;
  const int hx = std::clamp(q.trigger, 0, geo_.nx - 1);
  const int hy = std::clamp(q.trigger_row, 0, geo_.ny - 1);
  const auto band = [&](int x, int y) {
    return static_cast<int>(std::floor(geo_.distance(x, y, hx, hy))) / band_;
  };
  lookback.for_each([&](const PastEvent& e) {
    const std::size_t i = bins_.index(q.t - e.t);
    const int d = band(e.trigger, e.trigger_row);
    if (d < bands_) count_[i][static_cast<std::size_t>(d)] += 1;
    before_[i].add(e.mu);
  });
  // Sites (blocks of a chain) in each band of distance from the hypocentre.
  std::vector<double> blocks(static_cast<std::size_t>(bands_), 0.0);
  for (int y = 0; y < geo_.ny; ++y)
    for (int x = 0; x < geo_.nx; ++x) blocks[static_cast<std::size_t>(band(x, y))] += 1;
  const double length = q.t - lookback.window_start();
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    const double part = bins_.covered(i, length);
    if (!(part > 0)) continue;
    const double cover = part * bins_.width(i);
    for (std::size_t d = 0; d < blocks.size(); ++d) exposure_[i][d] += cover * blocks[d];
  }
}

}  // namespace bkq::seis
