// Waiting times; see interevent.hpp.
#include "stats/seismicity/interevent.hpp"

#include "core/format.hpp"

namespace bkq::seis {

InterEvent::InterEvent(const std::vector<double>& mu_thresholds) : thresholds_(mu_thresholds) {
  sets_.push_back({"all", {}, std::vector<std::int64_t>(bins_.size()), NAN});
  for (double m : thresholds_)
    sets_.push_back({"mu>=" + format_real(m), {}, std::vector<std::int64_t>(bins_.size()), NAN});
  sets_.push_back({"mainshocks", {}, std::vector<std::int64_t>(bins_.size()), NAN});
}

void InterEvent::add(const Quake& q) {
  auto take = [&](WaitingTimes& w) {
    if (!std::isnan(w.last)) {
      const double dt = q.t - w.last;
      w.moments.add(dt);
      ++w.counts[bins_.index(dt)];
    }
    w.last = q.t;
  };
  take(sets_.front());
  for (std::size_t i = 0; i < thresholds_.size(); ++i)
    if (q.mu >= thresholds_[i]) take(sets_[i + 1]);
  if (q.mainshock) take(sets_.back());
}

}  // namespace bkq::seis
