// Rupture scaling; see scaling.hpp.
#include "stats/seismicity/scaling.hpp"

namespace bkq::seis {

namespace {

void init(ScalingAxis& a, std::size_t n) {
  a.events.assign(n, 0);
  a.sum_log_moment.assign(n, 0);
  a.sum_moment.assign(n, 0);
  a.sum_log_x.assign(n, 0);
}

void take(ScalingAxis& a, const LogBins& bins, double x, const Quake& q) {
  const std::size_t i = bins.index(x);
  ++a.events[i];
  a.sum_log_moment[i] += q.mu;
  a.sum_moment[i] += q.moment;
  a.sum_log_x[i] += std::log(x);
  a.fit.add(std::log(x), q.mu);
}

}  // namespace

LineFit ScalingAxis::binned_fit(std::int64_t min_events) const {
  LineFit f;
  for (std::size_t i = 0; i < events.size(); ++i)
    if (events[i] >= min_events) {
      const double n = static_cast<double>(events[i]);
      f.add(sum_log_x[i] / n, sum_log_moment[i] / n);
    }
  return f;
}

Scaling::Scaling() {
  init(length_, lbins_.size());
  init(duration_, tbins_.size());
}

void Scaling::add(const Quake& q) {
  const int l = q.length();
  if (l > 0) take(length_, lbins_, l, q);
  if (q.duration > 0) take(duration_, tbins_, q.duration, q);
}

}  // namespace bkq::seis
