// Moment against rupture length (blocks from the first to the last that slipped) and
// against duration: the mean of ln M on log bins of each, and the exponents of M ~ L^a and
// M ~ T^g by least squares of the bins' mean ln M on their mean ln L (ln T), one point a
// bin, so every scale counts alike (the many one-block events would otherwise set the
// slope alone); the same over every event is kept beside it.
#pragma once

#include <cstdint>
#include <vector>

#include "stats/seismicity/log_bins.hpp"
#include "stats/seismicity/moments.hpp"
#include "stats/seismicity/quake.hpp"

namespace bkq::seis {

struct ScalingAxis {
  std::vector<std::int64_t> events;
  std::vector<double> sum_log_moment, sum_moment, sum_log_x;
  LineFit fit;  // over every event
  // Over the bins' means (bins with at least `min_events`).
  LineFit binned_fit(std::int64_t min_events = 3) const;
};

class Scaling {
 public:
  Scaling();
  void add(const Quake& q);
  // Lengths: 10 bins a decade from 1 block; durations: the shared time bins.
  const LogBins& length_bins() const { return lbins_; }
  const LogBins& duration_bins() const { return tbins_; }
  const ScalingAxis& length() const { return length_; }
  const ScalingAxis& duration() const { return duration_; }

 private:
  LogBins lbins_{1.0, 10, 9};
  LogBins tbins_ = time_bins(10);
  ScalingAxis length_, duration_;
};

}  // namespace bkq::seis
