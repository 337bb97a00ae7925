// Moment released per time bin, and the moment budget. Bins are equal and cover the
// catalogue from its first event; their width doubles (neighbours merged, exactly) whenever
// the span needs more than 2 * kMaxBins / 2 of them, so memory stays flat and the series
// ends with between kMaxBins / 2 and kMaxBins bins.
// Budget: the moment of the events after the first over N times the load between the first
// and the last event. A chain that slips on average as much as it is loaded (the
// substrate's displacement, per block) has budget 1 in the long run, whatever its springs.
#pragma once

#include <cstdint>
#include <vector>

#include "stats/seismicity/quake.hpp"

namespace bkq::seis {

class MomentRate {
 public:
  static constexpr std::size_t kMaxBins = 2048;
  void add(const Quake& q);
  double t0() const { return t0_; }
  double width() const { return w_; }
  const std::vector<double>& moment() const { return moment_; }
  const std::vector<std::int64_t>& events() const { return events_; }
  // NaN with fewer than 2 events or no elapsed time.
  double budget(int blocks) const;
  double total_moment() const { return total_; }
  double span() const { return t_last_ - t0_; }

 private:
  bool started_ = false;
  double t0_ = 0, t_last_ = 0, w_ = 0x1p-40, total_ = 0, after_first_ = 0;
  std::vector<double> moment_;
  std::vector<std::int64_t> events_;
};

}  // namespace bkq::seis
