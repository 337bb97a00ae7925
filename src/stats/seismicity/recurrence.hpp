// Recurrence of large events (the mainshocks): the intervals between consecutive ones
// system-wide, and per block the interval until the block is inside a large event's slipped
// extent again. Kept as histograms on fine log bins (50 a decade), so the maximum-likelihood
// Weibull and lognormal fits (stats/seismicity/fits.hpp) and the conditional probability of
// the next large event against the time since the last (the discrete hazard of each bin)
// come from flat memory.
#pragma once

#include <cstdint>
#include <vector>

#include "stats/seismicity/fits.hpp"
#include "stats/seismicity/log_bins.hpp"
#include "stats/seismicity/moments.hpp"
#include "stats/seismicity/quake.hpp"

namespace bkq::seis {

struct Intervals {
  Moments moments;
  std::vector<std::int64_t> counts;
  BinnedData binned(const LogBins& bins) const;  // the filled range
};

class Recurrence {
 public:
  static constexpr int kPerDecade = 50;
  // `blocks`: the chain length, for the per-block intervals (0: none kept).
  explicit Recurrence(int blocks);
  void add(const Quake& q);
  const LogBins& bins() const { return bins_; }
  const Intervals& system() const { return system_; }
  const Intervals& per_block() const { return block_; }

 private:
  LogBins bins_ = time_bins(kPerDecade);
  Intervals system_, block_;
  double last_ = NAN;
  std::vector<double> last_block_;
};

}  // namespace bkq::seis
