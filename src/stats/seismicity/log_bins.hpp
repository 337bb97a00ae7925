// Fixed logarithmic bins on [0, inf) for times and intervals whose scale is not known in
// advance (a streamed catalogue is read once): bin 0 is [0, t0), then `per_decade` bins a
// decade up to t0 * 10^decades, and a last bin [t_max, inf). Fixed edges make every
// accumulator's memory independent of the number of events.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace bkq::seis {

class LogBins {
 public:
  LogBins(double t0, int per_decade, int decades) : t0_(t0), per_(per_decade), dec_(decades) {}
  std::size_t size() const { return static_cast<std::size_t>(per_ * dec_ + 2); }
  // The bin of t >= 0 (negative t counts as 0).
  std::size_t index(double t) const {
    if (!(t >= t0_)) return 0;
    const double k = std::floor(std::log10(t / t0_) * per_);
    const double top = static_cast<double>(per_) * dec_;
    std::size_t i = static_cast<std::size_t>(std::clamp(k, 0.0, top)) + 1;
    // log10 rounding at an edge: keep t inside [low(i), high(i)).
    while (i > 1 && t < low(i)) --i;
    while (i + 1 < size() && t >= high(i)) ++i;
    return i;
  }
  double low(std::size_t i) const {
    return i == 0 ? 0.0 : t0_ * std::pow(10.0, static_cast<double>(i - 1) / per_);
  }
  double high(std::size_t i) const {
    return i + 1 >= size() ? std::numeric_limits<double>::infinity()
                           : t0_ * std::pow(10.0, static_cast<double>(i) / per_);
  }
  double width(std::size_t i) const { return high(i) - low(i); }
  // The fraction of bin i inside [0, length] (a window that ends at `length`).
  double covered(std::size_t i, double length) const {
    const double lo = low(i), hi = high(i);
    if (!(length > lo)) return 0;
    if (length >= hi) return 1;
    return (length - lo) / (hi - lo);
  }

 private:
  double t0_;
  int per_, dec_;
};

// The bins every time axis of the seismicity statistics uses: 1e-12 .. 1e12 of the clock.
inline LogBins time_bins(int per_decade) {
  return LogBins(1e-12, per_decade, 24);
}

}  // namespace bkq::seis
