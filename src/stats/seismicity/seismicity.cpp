// The one-pass seismicity analysis; see seismicity.hpp.
#include "stats/seismicity/seismicity.hpp"

#include "core/format.hpp"

namespace bkq::seis {

std::string MainshockRule::describe() const {
  if (mu) return "events with mu >= " + format_real(*mu) + " (--mainshock-mu)";
  return "events whose slipped extent spans more than half the chain (more than " +
         std::to_string(blocks / 2) + " of " + std::to_string(blocks) + " blocks)";
}

Seismicity::Seismicity(const SeismicityOptions& options)
    : opt_(options),
      lookback_(options.lookback),
      interevent_(options.interevent_mu),
      recurrence_(options.blocks),
      spacetime_(options.where()) {}

void Seismicity::add(Quake q) {
  q.mainshock = opt_.mainshock.is_main(q);
  if (events_ == 0) t_first_ = q.t;
  if (events_ > 0 && q.t < t_last_) ordered_ = false;
  t_last_ = q.t;
  ++events_;
  if (q.mainshock) {
    ++mainshocks_;
    min_main_mu_ = std::min(min_main_mu_, q.mu);
  }
  interevent_.add(q);
  recurrence_.add(q);
  omori_.add(q, lookback_);
  moment_rate_.add(q);
  scaling_.add(q);
  spacetime_.add(q, lookback_);
  lookback_.add(q);
}

void Seismicity::finish() {
  omori_.finish(t_last_);
  weibull_ = fit_weibull(recurrence_.system().binned(recurrence_.bins()));
  lognormal_ = fit_lognormal(recurrence_.system().binned(recurrence_.bins()));
  block_weibull_ = fit_weibull(recurrence_.per_block().binned(recurrence_.bins()));
  block_lognormal_ = fit_lognormal(recurrence_.per_block().binned(recurrence_.bins()));
  // Ogata's model has a stationary background; a chain's background follows its loading
  // cycle (quiet after a mainshock, busier towards the next), so the fit keeps to the times
  // short against the cycle: a tenth of the mean sequence window.
  auto fit = [&](const Stack& st) {
    const BinnedData d = st.binned(omori_.bins());
    double exposure_time = 0;
    for (std::size_t b = 0; b < d.lo.size(); ++b)
      if (std::isfinite(d.hi[b])) exposure_time += d.exposure[b] * (d.hi[b] - d.lo[b]);
    const double mean_window =
        st.sequences > 0 ? exposure_time / static_cast<double>(st.sequences) : 0.0;
    return fit_omori(d, kOmoriFitFraction * mean_window);
  };
  after_fit_ = fit(omori_.after());
  before_fit_ = fit(omori_.before());

  // Båth: aftershocks until the fitted Omori term falls to the background rate
  // (K / (t + c)^p = mu), or within the whole sequence window without an excess.
  const auto& n = omori_.bath_sequences();
  std::size_t at = n.size();
  for (std::size_t i = 0; i < n.size(); ++i)
    if (n[i] > 0) at = i;  // the last bin: the whole windows
  bath_.window_rule = "the whole window (until the next mainshock)";
  if (after_fit_.excess && at < n.size()) {
    const auto& f = after_fit_;
    const double t = std::pow(f.K.value / f.background.value, 1.0 / f.p.value) - f.c.value;
    if (t > 0) {
      const std::size_t i = omori_.bins().index(t);
      if (i < at && n[i] > 0) at = i;
      bath_.window_rule = "until the fitted Omori term falls to the background rate";
    }
  }
  if (at < n.size() && n[at] > 0) {
    const double k = static_cast<double>(n[at]);
    bath_.sequences = n[at];
    bath_.window = omori_.bins().high(at);
    bath_.delta_mu = omori_.bath_sum()[at] / k;
    const double var = omori_.bath_sum2()[at] / k - bath_.delta_mu * bath_.delta_mu;
    bath_.delta_mu_err = k > 1 ? std::sqrt(std::max(0.0, var) / (k - 1)) : NAN;
  }
  b_mu_min_ = opt_.b_mu_min ? *opt_.b_mu_min : spacetime_.all().max_curvature();
}

}  // namespace bkq::seis
