// Waiting times between consecutive events, for the whole catalogue and for the events of
// a few subsets (above magnitude thresholds, the mainshocks): their distribution on log
// bins beside the exponential law of a Poisson process with the same mean, and the mean and
// coefficient of variation (1 for Poisson, below 1 for quasi-periodic, above for clustered
// events).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "stats/seismicity/log_bins.hpp"
#include "stats/seismicity/moments.hpp"
#include "stats/seismicity/quake.hpp"

namespace bkq::seis {

struct WaitingTimes {
  std::string subset;  // "all", "mu>=2", "mainshocks"
  Moments moments;
  std::vector<std::int64_t> counts;  // per time bin
  double last = NAN;                 // time of the subset's last event
};

class InterEvent {
 public:
  static constexpr int kPerDecade = 10;
  // Subsets: every event, each mu >= threshold, the mainshocks.
  explicit InterEvent(const std::vector<double>& mu_thresholds);
  void add(const Quake& q);
  const LogBins& bins() const { return bins_; }
  const std::vector<WaitingTimes>& subsets() const { return sets_; }
  const WaitingTimes& all() const { return sets_.front(); }

 private:
  LogBins bins_ = time_bins(kPerDecade);
  std::vector<double> thresholds_;
  std::vector<WaitingTimes> sets_;
};

}  // namespace bkq::seis
