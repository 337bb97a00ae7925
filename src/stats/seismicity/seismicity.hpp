// Every seismicity statistic of a catalogue in one pass: the accumulators of this folder fed
// one event at a time (memory flat in the number of events), and at the end the fits that
// need all of it (Weibull and lognormal recurrence laws, Omori-Utsu after and before
// mainshocks, Båth's difference, the b-values before mainshocks).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "stats/seismicity/fits.hpp"
#include "stats/seismicity/geometry.hpp"
#include "stats/seismicity/interevent.hpp"
#include "stats/seismicity/lookback.hpp"
#include "stats/seismicity/moment_rate.hpp"
#include "stats/seismicity/omori.hpp"
#include "stats/seismicity/quake.hpp"
#include "stats/seismicity/recurrence.hpp"
#include "stats/seismicity/scaling.hpp"
#include "stats/seismicity/spacetime.hpp"

namespace bkq::seis {

// Which events are mainshocks (also the large events whose recurrence is measured): those
// with mu >= mu when given, else those whose slipped extent spans more than half the chain
// (last_block - first_block + 1 > N/2: the delocalised events of Carlson & Langer 1989).
struct MainshockRule {
  std::optional<double> mu;
  int blocks = 0;  // N
  bool is_main(const Quake& q) const {
    if (mu) return q.mu >= *mu;
    return 2 * q.length() > blocks;
  }
  std::string describe() const;
};

struct SeismicityOptions {
  int blocks = 0;  // N (a lattice's columns along strike)
  // Where the events are; a chain of `blocks` when left as it is (nx = 0).
  Geometry geometry{0, 1, false, false};
  Geometry where() const { return geometry.nx > 0 ? geometry : Geometry::chain(blocks); }
  MainshockRule mainshock;
  std::vector<double> interevent_mu = {-4, -2, 0, 2};
  std::optional<double> b_mu_min;  // lower magnitude of the b-values (default: MAXC)
  std::size_t lookback = Lookback::kDefaultCapacity;
};

// The Omori-Utsu fits take the times up to this fraction of the mean sequence window.
inline constexpr double kOmoriFitFraction = 0.1;

// Båth's law read at one aftershock window.
struct Bath {
  double delta_mu = NAN, delta_mu_err = NAN;
  std::int64_t sequences = 0;
  double window = NAN;  // aftershocks within this time of their mainshock
  std::string window_rule;
  double delta_mw() const { return delta_mu / kMuPerMw; }
};

class Seismicity {
 public:
  explicit Seismicity(const SeismicityOptions& options);
  // Events in time order (the catalogue's order); sets q.mainshock by the rule.
  void add(Quake q);
  // Closes the last aftershock sequence and fits; call once after the last event.
  void finish();

  const SeismicityOptions& options() const { return opt_; }
  std::int64_t events() const { return events_; }
  std::int64_t mainshocks() const { return mainshocks_; }
  double min_mainshock_mu() const { return min_main_mu_; }
  double t_first() const { return t_first_; }
  double t_last() const { return t_last_; }
  bool time_ordered() const { return ordered_; }

  const InterEvent& interevent() const { return interevent_; }
  const Recurrence& recurrence() const { return recurrence_; }
  const OmoriStack& omori() const { return omori_; }
  const MomentRate& moment_rate() const { return moment_rate_; }
  const Scaling& scaling() const { return scaling_; }
  const SpaceTime& spacetime() const { return spacetime_; }

  // After finish().
  const WeibullFit& weibull() const { return weibull_; }
  const LognormalFit& lognormal() const { return lognormal_; }
  const WeibullFit& block_weibull() const { return block_weibull_; }
  const LognormalFit& block_lognormal() const { return block_lognormal_; }
  const OmoriFit& aftershocks() const { return after_fit_; }
  const OmoriFit& foreshocks() const { return before_fit_; }
  const Bath& bath() const { return bath_; }
  double b_mu_min() const { return b_mu_min_; }

 private:
  SeismicityOptions opt_;
  std::int64_t events_ = 0, mainshocks_ = 0;
  double min_main_mu_ = INFINITY, t_first_ = NAN, t_last_ = NAN;
  bool ordered_ = true;
  Lookback lookback_;
  InterEvent interevent_;
  Recurrence recurrence_;
  OmoriStack omori_;
  MomentRate moment_rate_;
  Scaling scaling_;
  SpaceTime spacetime_;
  WeibullFit weibull_, block_weibull_;
  LognormalFit lognormal_, block_lognormal_;
  OmoriFit after_fit_, before_fit_;
  Bath bath_;
  double b_mu_min_ = NAN;
};

}  // namespace bkq::seis
