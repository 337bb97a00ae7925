// The rate-and-state event detector; see rsf_events.hpp.
#include "engine/rsf_events.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bkq {

namespace {

// Where the Hermite cubic of x over the step [t0, t1] crosses `level` between lo and hi (on
// either side of it there), by bisection.
double crossing(double t0, double x0, double d0, double t1, double x1, double d1, double level,
                double lo, double hi) {
  const bool below_at_lo = (lo == t0 ? x0 : hermite_value(t0, x0, d0, t1, x1, d1, lo)) < level;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((hermite_value(t0, x0, d0, t1, x1, d1, mid) < level) == below_at_lo ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The cycle's last step: its two ends (each block's slip at j, ln V at n + j, ln theta at
// 2n + j, and their rates) and the Hermite cubic of a component between them.
struct StepEnds {
  explicit StepEnds(const RsfCycle& c)
      : n(c.n()),
        y0(c.y_prev()),
        d0(c.dy_prev()),
        y1(c.y()),
        d1(c.dy()),
        t0(c.t_prev()),
        t1(c.t()) {}
  // Component k at time t of the step.
  double at(int k, double t) const { return hermite_value(t0, y0[k], d0[k], t1, y1[k], d1[k], t); }
  // When component k crosses `level` between lo and hi (on either side of it there).
  double crossing_of(int k, double level, double lo, double hi) const {
    return crossing(t0, y0[k], d0[k], t1, y1[k], d1[k], level, lo, hi);
  }
  double crossing_of(int k, double level) const { return crossing_of(k, level, t0, t1); }

  const int n;
  const std::vector<double>&y0, &d0, &y1, &d1;
  const double t0, t1;
};

}  // namespace

std::optional<EventRecord> RsfEventDetector::observe(const RsfCycle& c) {
  const StepEnds s(c);
  const int n = s.n;
  const auto& y0 = s.y0;
  const auto& d0 = s.d0;
  const auto& y1 = s.y1;
  const auto& d1 = s.d1;
  const double t0 = s.t0, t1 = s.t1;
  // Block j's largest ln V in the step (inside it where ln V turns over) and when.
  const auto peak_of = [&](int j) {
    const double a = y0[n + j], b = y1[n + j];
    Extremum p = a > b ? Extremum{t0, a} : Extremum{t1, b};
    if (d0[n + j] > 0 && d1[n + j] <= 0) {
      const Extremum e = hermite_extremum(t0, a, d0[n + j], t1, b, d1[n + j]);
      if (e.x > p.x) p = e;
    }
    return p;
  };
  if (!in_event_) {
    int first = -1;
    double t_first = t1;
    for (int j = 0; j < n; ++j) {
      const double a = y0[n + j];
      const Extremum p = peak_of(j);
      if (p.x < ln_vth_) continue;
      // Up to the peak: a block whose ln V rises above V_th and falls back inside the step.
      const double tc = a >= ln_vth_           ? t0
                        : y1[n + j] >= ln_vth_ ? s.crossing_of(n + j, ln_vth_)
                                               : s.crossing_of(n + j, ln_vth_, t0, p.t);
      if (first < 0 || tc < t_first) first = j, t_first = tc;
    }
    if (first < 0) return std::nullopt;
    in_event_ = true;
    times_.hypocentre = t_first;
    trigger_ = first;
    ln_peak_ = -HUGE_VAL;
    seismic_.assign(n, 0);
    slip0_.resize(n);
    for (int j = 0; j < n; ++j) slip0_[j] = s.at(j, t_first);
  }
  double top = -HUGE_VAL;
  for (int j = 0; j < n; ++j) {
    top = std::max(top, y1[n + j]);
    const Extremum p = peak_of(j);
    if (p.x < ln_vth_) continue;
    seismic_[j] = 1;
    if (p.x > ln_peak_) ln_peak_ = p.x, times_.peak = p.t;
  }
  if (top >= ln_vth_) return std::nullopt;
  // Every block is below V_th again: the event ends at the last downward crossing (after the
  // step's peak for a block that rose above V_th and fell back inside the step).
  double t_end = t0;
  for (int j = 0; j < n; ++j) {
    if (!seismic_[j]) continue;
    const Extremum p = peak_of(j);
    if (y0[n + j] >= ln_vth_)
      t_end = std::max(t_end, s.crossing_of(n + j, ln_vth_));
    else if (p.x >= ln_vth_)
      t_end = std::max(t_end, s.crossing_of(n + j, ln_vth_, p.t, t1));
  }
  EventRecord e;
  e.event = ++events_;
  e.load = c.model().v_pl * times_.hypocentre;
  e.trigger = trigger_;
  e.first_block = n;
  e.last_block = -1;
  std::vector<int> slipped;
  for (int j = 0; j < n; ++j) {
    if (!seismic_[j]) continue;
    ++e.blocks;
    e.moment += s.at(j, t_end) - slip0_[j];
    e.first_block = std::min(e.first_block, j);
    e.last_block = std::max(e.last_block, j);
    slipped.push_back(j);
  }
  // A lattice's event: the trigger and the bounding box as (x along strike, y across).
  if (c.model().rows > 1) place_on_lattice(e, trigger_, slipped, c.model().nx());
  e.magnitude = std::log(e.moment);
  e.duration = t_end - times_.hypocentre;
  e.max_speed = std::exp(ln_peak_);
  e.hypocentre_time = times_.hypocentre;
  e.peak_time = times_.peak;
  in_event_ = false;
  return e;
}

void RsfEventDetector::restart(const RsfCycle& c, double t) {
  if (!in_event_) return;
  const StepEnds s(c);
  const int n = s.n;
  times_ = {t, t};
  // The peak counts from the next step on (this step's holds the event's); the trigger is the
  // fastest block at t.
  ln_peak_ = -HUGE_VAL;
  double fastest = -HUGE_VAL;
  for (int j = 0; j < n; ++j) {
    slip0_[j] = s.at(j, t);
    const double ln_v = s.at(n + j, t);
    seismic_[j] = ln_v >= ln_vth_ ? 1 : 0;
    if (ln_v > fastest) fastest = ln_v, trigger_ = j;
  }
}

std::optional<RsfSlowEpisode> RsfSlowSlipDetector::observe(const RsfCycle& c) {
  std::optional<EventRecord> e = slow_.observe(c);
  if (!e) return std::nullopt;
  const bool afterslip = afterslip_;
  afterslip_ = false;
  // It held a seismic event, or it was an afterslip that had ended with the event.
  if (std::log(e->max_speed) >= ln_vth_ || e->blocks == 0 || !(e->moment > 0)) return std::nullopt;
  e->event = ++episodes_;
  return RsfSlowEpisode{*e, afterslip};
}

void RsfSlowSlipDetector::event_ended(const RsfCycle& c, double t) {
  if (!slow_.in_event()) return;
  slow_.restart(c, t);
  afterslip_ = true;
}

std::vector<double> RsfSlowSlipDetector::snapshot() const {
  std::vector<double> s = {afterslip_ ? 1.0 : 0.0, static_cast<double>(episodes_)};
  const std::vector<double> inner = slow_.snapshot();
  s.insert(s.end(), inner.begin(), inner.end());
  return s;
}

void RsfSlowSlipDetector::restore(const std::vector<double>& s) {
  afterslip_ = s.at(0) != 0;
  episodes_ = static_cast<std::int64_t>(s.at(1));
  slow_.restore(std::vector<double>(s.begin() + 2, s.end()));
}

std::vector<double> RsfEventDetector::snapshot() const {
  std::vector<double> s = {in_event_ ? 1.0 : 0.0,
                           static_cast<double>(events_),
                           static_cast<double>(trigger_),
                           times_.hypocentre,
                           times_.peak,
                           ln_peak_};
  s.insert(s.end(), slip0_.begin(), slip0_.end());
  for (char x : seismic_) s.push_back(x);
  return s;
}

void RsfEventDetector::restore(const std::vector<double>& s) {
  in_event_ = s.at(0) != 0;
  events_ = static_cast<std::int64_t>(s.at(1));
  trigger_ = static_cast<int>(s.at(2));
  times_ = {s.at(3), s.at(4)};
  ln_peak_ = s.at(5);
  const std::size_t n = (s.size() - 6) / 2;
  slip0_.assign(s.begin() + 6, s.begin() + 6 + static_cast<std::ptrdiff_t>(n));
  seismic_.clear();
  for (std::size_t i = 0; i < n; ++i) seismic_.push_back(s[6 + n + i] != 0 ? 1 : 0);
}

}  // namespace bkq
