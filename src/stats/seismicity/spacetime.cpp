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

SpaceTime::SpaceTime(int blocks)
    : n_(std::max(1, blocks)),
      band_(std::max(1, (n_ + kBands - 1) / kBands)),
      bands_((n_ + band_ - 1) / band_) {
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
  const int h = std::clamp(q.trigger, 0, n_ - 1);
  lookback.for_each([&](const PastEvent& e) {
    const std::size_t i = bins_.index(q.t - e.t);
    const int d = std::abs(e.trigger - h) / band_;
    if (d < bands_) count_[i][static_cast<std::size_t>(d)] += 1;
    before_[i].add(e.mu);
  });
  // Blocks of the chain in each band of distance from the hypocentre h.
  std::vector<double> blocks(static_cast<std::size_t>(bands_), 0.0);
  for (int j = 0; j < n_; ++j) blocks[static_cast<std::size_t>(std::abs(j - h) / band_)] += 1;
  const double length = q.t - lookback.window_start();
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    const double part = bins_.covered(i, length);
    if (!(part > 0)) continue;
    const double cover = part * bins_.width(i);
    for (std::size_t d = 0; d < blocks.size(); ++d) exposure_[i][d] += cover * blocks[d];
  }
}

}  // namespace bkq::seis
