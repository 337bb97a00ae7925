// Event rates stacked around mainshocks: after each one (aftershocks) and before it
// (foreshocks), on log bins of the time since (before) the mainshock, each sequence with its
// own window: the aftershocks of a mainshock are the events until the next mainshock (or the
// catalogue's end), its foreshocks the events since the previous one (or the catalogue's
// start, or the oldest event the look-back keeps). The exposure of a bin is the number of
// windows that cover it, so stacked rate = count / (exposure * bin width) and the Omori-Utsu
// law with a background is fitted to it by Ogata's maximum likelihood (fits.hpp).
// Båth's law from the same sequences: the mainshock's mu minus the largest aftershock's,
// for aftershocks within each bin's upper time (so the difference can be read at any window).
#pragma once

#include <cstdint>
#include <vector>

#include "stats/seismicity/fits.hpp"
#include "stats/seismicity/log_bins.hpp"
#include "stats/seismicity/lookback.hpp"
#include "stats/seismicity/quake.hpp"

namespace bkq::seis {

struct Stack {
  std::vector<double> count, exposure;
  std::int64_t sequences = 0;
  BinnedData binned(const LogBins& bins) const;
};

class OmoriStack {
 public:
  static constexpr int kPerDecade = 10;
  OmoriStack();
  // Before lookback.add(q).
  void add(const Quake& q, const Lookback& lookback);
  // Closes the open aftershock sequence at the catalogue's end (time of the last event).
  void finish(double t_end);
  const LogBins& bins() const { return bins_; }
  const Stack& after() const { return after_; }
  const Stack& before() const { return before_; }
  // Båth: per bin, the sequences with an aftershock by the bin's upper edge and the sum of
  // their differences mu_main - max mu_after.
  const std::vector<std::int64_t>& bath_sequences() const { return bath_n_; }
  const std::vector<double>& bath_sum() const { return bath_sum_; }
  const std::vector<double>& bath_sum2() const { return bath_sum2_; }

 private:
  void close(double t_end);
  LogBins bins_ = time_bins(kPerDecade);
  Stack after_, before_;
  bool open_ = false, finished_ = false;
  double t_main_ = 0, mu_main_ = 0;
  std::vector<double> seq_max_;  // the open sequence's largest mu per bin
  std::vector<std::int64_t> bath_n_;
  std::vector<double> bath_sum_, bath_sum2_;
};

}  // namespace bkq::seis
