// The rate-and-state event detector; see rsf_events.hpp.
#include "engine/rsf_events.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bkq {

namespace {

// Where the Hermite cubic of x over the step [t0, t1] crosses `level` inside [lo, hi], the
// cubic lying on either side of it at lo and hi, by bisection.
double crossing(double t0, double x0, double d0, double t1, double x1, double d1, double level,
                double lo, double hi) {
  const bool below_at_lo = hermite_value(t0, x0, d0, t1, x1, d1, lo) < level;
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
  // When component k crosses `level` between lo and hi (it lies on either side there).
  double crossing_of(int k, double level, double lo, double hi) const {
    return crossing(t0, y0[k], d0[k], t1, y1[k], d1[k], level, lo, hi);
  }

  // What observe() reads, by slot s (here every block, slot s = block s).
  int count() const { return n; }
  int id(int s) const { return s; }
  double lnv0(int s) const { return y0[n + s]; }
  double lnv1(int s) const { return y1[n + s]; }
  double dlnv0(int s) const { return d0[n + s]; }
  double dlnv1(int s) const { return d1[n + s]; }
  double lnv_crossing(int s, double level, double lo, double hi) const {
    return crossing_of(n + s, level, lo, hi);
  }
  double slip_of(int j, double t) const { return at(j, t); }

  const int n;
  const std::vector<double>&y0, &d0, &y1, &d1;
  const double t0, t1;
};

// The active-block integrator's last step: slot s is block id[s], 3 numbers a slot; a block
// not integrated has its slip held.
struct SpanEnds {
  explicit SpanEnds(const RsfStepSpan& p) : p(p), n(p.n), t0(p.t0), t1(p.t1) {}
  int count() const { return p.count; }
  int id(int s) const { return p.id[s]; }
  double lnv0(int s) const { return p.y0[3 * s + 1]; }
  double lnv1(int s) const { return p.y1[3 * s + 1]; }
  double dlnv0(int s) const { return p.d0[3 * s + 1]; }
  double dlnv1(int s) const { return p.d1[3 * s + 1]; }
  double lnv_crossing(int s, double level, double lo, double hi) const {
    const int k = 3 * s + 1;
    return crossing(t0, p.y0[k], p.d0[k], t1, p.y1[k], p.d1[k], level, lo, hi);
  }
  double slip_of(int j, double t) const {
    const int s = p.slot[j];
    if (s < 0) return p.held_slip[j];
    const int k = 3 * s;
    return hermite_value(t0, p.y0[k], p.d0[k], t1, p.y1[k], p.d1[k], t);
  }

  const RsfStepSpan& p;
  const int n;
  const double t0, t1;
};

}  // namespace

std::optional<EventRecord> RsfEventDetector::observe(const RsfCycle& c) {
  return observe_ends(StepEnds(c), c.model());
}

std::optional<EventRecord> RsfEventDetector::observe(const RsfStepSpan& span) {
  return observe_ends(SpanEnds(span), *span.model);
}

void RsfEventDetector::activated(int j, double slip) {
  if (!in_event_ || slip0_event_[j] == events_ + 1) return;
  slip0_[j] = slip;
  slip0_event_[j] = events_ + 1;
}

template <class Ends>
std::optional<EventRecord> RsfEventDetector::observe_ends(const Ends& s, const RsfModel& m) {
  const int n = s.n, count = s.count();
  const double t0 = s.t0, t1 = s.t1;
  // Slot k's largest ln V in the step (inside it where ln V turns over) and when.
  const auto peak_of = [&](int k) {
    const double a = s.lnv0(k), b = s.lnv1(k);
    Extremum p = a > b ? Extremum{t0, a} : Extremum{t1, b};
    if (s.dlnv0(k) > 0 && s.dlnv1(k) <= 0) {
      const Extremum e = hermite_extremum(t0, a, s.dlnv0(k), t1, b, s.dlnv1(k));
      if (e.x > p.x) p = e;
    }
    return p;
  };
  if (!in_event_) {
    int first = -1;
    double t_first = t1;
    for (int k = 0; k < count; ++k) {
      const double a = s.lnv0(k);
      const Extremum p = peak_of(k);
      if (p.x < ln_vth_) continue;
      // Up through V_th; before the step's peak where the step ends below it again.
      const double up_by = s.lnv1(k) >= ln_vth_ ? t1 : p.t;
      const double tc = a >= ln_vth_ ? t0 : s.lnv_crossing(k, ln_vth_, t0, up_by);
      // Ties go to the lower block (the slots need not be in block order).
      if (first < 0 || tc < t_first || (tc == t_first && s.id(k) < first))
        first = s.id(k), t_first = tc;
    }
    if (first < 0) return std::nullopt;
    in_event_ = true;
    times_.hypocentre = t_first;
    trigger_ = first;
    ln_peak_ = -HUGE_VAL;
    for (const int j : seismic_ids_) seismic_[j] = 0;
    seismic_ids_.clear();
    if (seismic_.size() != static_cast<std::size_t>(n)) seismic_.assign(n, 0);
    slip0_.resize(n);
    slip0_event_.resize(n, 0);
    for (int k = 0; k < count; ++k) {
      slip0_[s.id(k)] = s.slip_of(s.id(k), t_first);
      slip0_event_[s.id(k)] = events_ + 1;
    }
  }
  double top = -HUGE_VAL;
  for (int k = 0; k < count; ++k) {
    top = std::max(top, s.lnv1(k));
    const Extremum p = peak_of(k);
    if (p.x < ln_vth_) continue;
    const int j = s.id(k);
    if (!seismic_[j]) seismic_ids_.push_back(j);
    seismic_[j] = 1;
    if (p.x > ln_peak_) ln_peak_ = p.x, times_.peak = p.t;
  }
  if (top >= ln_vth_) return std::nullopt;
  // Every block is below V_th again: the event ends at the last downward crossing, after the
  // step's peak for a block that rose above V_th and fell back inside this step.
  double t_end = std::max(t0, times_.hypocentre);
  for (int k = 0; k < count; ++k) {
    if (!seismic_[s.id(k)]) continue;
    const Extremum p = peak_of(k);
    if (p.x < ln_vth_) continue;
    const double from = s.lnv0(k) >= ln_vth_ ? t0 : p.t;
    t_end = std::max(t_end, s.lnv_crossing(k, ln_vth_, from, t1));
  }
  EventRecord e;
  e.event = ++events_;
  e.load = m.v_pl * times_.hypocentre;
  e.trigger = trigger_;
  e.first_block = n;
  e.last_block = -1;
  std::sort(seismic_ids_.begin(), seismic_ids_.end());
  for (const int j : seismic_ids_) {
    ++e.blocks;
    e.moment += s.slip_of(j, t_end) - slip0_[j];
    e.first_block = std::min(e.first_block, j);
    e.last_block = std::max(e.last_block, j);
  }
  // A lattice's event: the trigger and the bounding box as (x along strike, y across).
  if (m.rows > 1) place_on_lattice(e, trigger_, seismic_ids_, m.nx());
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
  seismic_ids_.clear();
  for (int j = 0; j < n; ++j)
    if (seismic_[j]) seismic_ids_.push_back(j);
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
  seismic_ids_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    seismic_.push_back(s[6 + n + i] != 0 ? 1 : 0);
    if (seismic_.back()) seismic_ids_.push_back(static_cast<int>(i));
  }
}

}  // namespace bkq
