// Seismicity before mainshocks in space and time: the density of events (per block, or per
// site of a lattice, per unit time) against the distance of their hypocentre from the next
// mainshock's (geometry.hpp: along the chain, or Euclidean in the lattice's plane) and the time
// before it (the Mogi doughnut: quiet near the coming rupture, active around it; Mogi 1969,
// Bull. Earthquake Res. Inst. 47, 395), and the b-value (Aki 1965, Bull. Earthquake Res.
// Inst. 43, 237: b = 1 / (mean mu - mu_c) over the events with mu >= mu_c, error b / sqrt n,
// Shi & Bolt 1982) of the events before mainshocks against the time before them, beside the
// b of every event that is not a mainshock.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "stats/seismicity/fits.hpp"
#include "stats/seismicity/geometry.hpp"
#include "stats/seismicity/log_bins.hpp"
#include "stats/seismicity/lookback.hpp"
#include "stats/seismicity/quake.hpp"

namespace bkq::seis {

// Events and the sum of their magnitudes per magnitude bin of width 0.2 (mu in [-40, 40),
// clamped), so Aki's b above any bin edge mu_c is exact: n = events with mu >= mu_c,
// b = n / sum(mu - mu_c).
struct MagSums {
  static constexpr double kWidth = 0.2;
  static constexpr int kBins = 400, kOffset = 200;
  std::vector<double> count = std::vector<double>(kBins, 0.0),
                      sum = std::vector<double>(kBins, 0.0);
  static int bin(double mu) {
    return std::clamp(static_cast<int>(std::floor(mu / kWidth)) + kOffset, 0, kBins - 1);
  }
  static double low(int k) { return (k - kOffset) * kWidth; }
  void add(double mu) {
    const auto k = static_cast<std::size_t>(bin(mu));
    count[k] += 1;
    sum[k] += mu;
  }
  double events() const;
  // Aki's b and its error above mu_c (rounded down to a bin edge); NaN with fewer than 2.
  Estimate b(double mu_c) const;
  // The lower edge of the fullest bin: the magnitude of completeness by maximum curvature
  // (Wiemer & Wyss 2000, Bull. Seismol. Soc. Am. 90, 859), where D(mu) turns over.
  double max_curvature() const;
};

class SpaceTime {
 public:
  static constexpr int kPerDecade = 2;
  static constexpr int kBands = 10;
  // Bands of distance of width band_width() from 0 to the geometry's largest distance; a
  // distance d falls in band floor(d) / band_width().
  explicit SpaceTime(const Geometry& geometry);
  void add(const Quake& q, const Lookback& lookback);  // before lookback.add(q)
  const LogBins& bins() const { return bins_; }
  int band_width() const { return band_; }
  int bands() const { return bands_; }
  // [time bin][band]
  const std::vector<std::vector<double>>& count() const { return count_; }
  const std::vector<std::vector<double>>& exposure() const { return exposure_; }
  // Magnitudes of the events before mainshocks per time bin, and of every event that is not
  // a mainshock.
  const std::vector<MagSums>& before() const { return before_; }
  const MagSums& all() const { return all_; }
  std::int64_t mainshocks() const { return mainshocks_; }

 private:
  LogBins bins_ = time_bins(kPerDecade);
  Geometry geo_;
  int band_, bands_;
  std::vector<std::vector<double>> count_, exposure_;
  std::vector<MagSums> before_;
  MagSums all_;
  std::int64_t mainshocks_ = 0;
};

}  // namespace bkq::seis
