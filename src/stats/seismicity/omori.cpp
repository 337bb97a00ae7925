// Rates stacked around mainshocks; see omori.hpp.
#include "stats/seismicity/omori.hpp"

#include <algorithm>
#include <limits>

namespace bkq::seis {

BinnedData Stack::binned(const LogBins& bins) const {
  BinnedData d;
  for (std::size_t i = 0; i < count.size(); ++i) {
    if (!(exposure[i] > 0)) continue;
    d.lo.push_back(bins.low(i));
    d.hi.push_back(bins.high(i));
    d.count.push_back(count[i]);
    d.exposure.push_back(exposure[i]);
  }
  return d;
}

OmoriStack::OmoriStack() {
  const std::size_t n = bins_.size();
  after_.count.assign(n, 0);
  after_.exposure.assign(n, 0);
  before_.count.assign(n, 0);
  before_.exposure.assign(n, 0);
  seq_max_.assign(n, -std::numeric_limits<double>::infinity());
  bath_n_.assign(n, 0);
  bath_sum_.assign(n, 0);
  bath_sum2_.assign(n, 0);
}

void OmoriStack::close(double t_end) {
  const double length = t_end - t_main_;
  for (std::size_t i = 0; i < bins_.size(); ++i) after_.exposure[i] += bins_.covered(i, length);
  ++after_.sequences;
  double running = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    running = std::max(running, seq_max_[i]);
    seq_max_[i] = -std::numeric_limits<double>::infinity();
    if (running == -std::numeric_limits<double>::infinity()) continue;
    const double d = mu_main_ - running;
    ++bath_n_[i];
    bath_sum_[i] += d;
    bath_sum2_[i] += d * d;
  }
  open_ = false;
}

void OmoriStack::add(const Quake& q, const Lookback& lookback) {
  if (!q.mainshock) {
    if (open_) {
      const std::size_t i = bins_.index(q.t - t_main_);
      after_.count[i] += 1;
      seq_max_[i] = std::max(seq_max_[i], q.mu);
    }
    return;
  }
  if (open_) close(q.t);
  // Foreshocks: the look-back's events, whose window starts at its window_start().
  if (lookback.started()) {
    const double length = q.t - lookback.window_start();
    lookback.for_each([&](const PastEvent& e) { before_.count[bins_.index(q.t - e.t)] += 1; });
    for (std::size_t i = 0; i < bins_.size(); ++i) before_.exposure[i] += bins_.covered(i, length);
    ++before_.sequences;
  }
  open_ = true;
  t_main_ = q.t;
  mu_main_ = q.mu;
}

void OmoriStack::finish(double t_end) {
  if (open_ && !finished_) close(t_end);
  finished_ = true;
}

}  // namespace bkq::seis
