// Recurrence of large events; see recurrence.hpp.
#include "stats/seismicity/recurrence.hpp"

#include <algorithm>
#include <cmath>

namespace bkq::seis {

BinnedData Intervals::binned(const LogBins& bins) const {
  BinnedData d;
  std::size_t first = counts.size(), last = 0;
  for (std::size_t i = 0; i < counts.size(); ++i)
    if (counts[i] > 0) {
      first = std::min(first, i);
      last = i;
    }
  if (first > last) return d;
  // The whole axis is in the likelihood (the laws' tails are part of the fit); the empty
  // stretches below and above the filled range are one bin each (exact for grouped data).
  auto put = [&](double lo, double hi, double c) {
    d.lo.push_back(lo);
    d.hi.push_back(hi);
    d.count.push_back(c);
    d.exposure.push_back(1);
  };
  if (bins.low(first) > 0) put(0, bins.low(first), 0);
  for (std::size_t i = first; i <= last; ++i)
    put(bins.low(i), bins.high(i), static_cast<double>(counts[i]));
  if (std::isfinite(bins.high(last))) put(bins.high(last), INFINITY, 0);
  return d;
}

Recurrence::Recurrence(int blocks)
    : last_block_(static_cast<std::size_t>(std::max(0, blocks)), NAN) {
  system_.counts.assign(bins_.size(), 0);
  block_.counts.assign(bins_.size(), 0);
}

void Recurrence::add(const Quake& q) {
  if (!q.mainshock) return;
  if (!std::isnan(last_)) {
    system_.moments.add(q.t - last_);
    ++system_.counts[bins_.index(q.t - last_)];
  }
  last_ = q.t;
  if (!q.has_extent() || last_block_.empty()) return;
  const int hi = std::min(q.last, static_cast<int>(last_block_.size()) - 1);
  for (int j = std::max(0, q.first); j <= hi; ++j) {
    double& l = last_block_[static_cast<std::size_t>(j)];
    if (!std::isnan(l)) {
      block_.moments.add(q.t - l);
      ++block_.counts[bins_.index(q.t - l)];
    }
    l = q.t;
  }
}

}  // namespace bkq::seis
