// Moment-rate series; see moment_rate.hpp.
#include "stats/seismicity/moment_rate.hpp"

#include <cmath>

namespace bkq::seis {

void MomentRate::add(const Quake& q) {
  if (!started_) {
    started_ = true;
    t0_ = q.t;
  } else {
    after_first_ += q.moment;
  }
  t_last_ = q.t;
  total_ += q.moment;
  double k = std::floor((q.t - t0_) / w_);
  while (k >= static_cast<double>(kMaxBins)) {
    const std::size_t half = (moment_.size() + 1) / 2;
    for (std::size_t i = 0; i < half; ++i) {
      const std::size_t a = 2 * i, b = a + 1;
      moment_[i] = moment_[a] + (b < moment_.size() ? moment_[b] : 0.0);
      events_[i] = events_[a] + (b < events_.size() ? events_[b] : 0);
    }
    moment_.resize(half);
    events_.resize(half);
    w_ *= 2;
    k = std::floor((q.t - t0_) / w_);
  }
  const std::size_t i = k > 0 ? static_cast<std::size_t>(k) : 0;
  if (i >= moment_.size()) {
    moment_.resize(i + 1, 0.0);
    events_.resize(i + 1, 0);
  }
  moment_[i] += q.moment;
  events_[i] += 1;
}

double MomentRate::budget(int blocks) const {
  const double span = t_last_ - t0_;
  if (!(span > 0) || blocks <= 0) return NAN;
  return after_first_ / (static_cast<double>(blocks) * span);
}

}  // namespace bkq::seis
