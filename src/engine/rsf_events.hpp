// Events of a rate-and-state cycle run (engine/rsf_cycle.hpp): an event is an interval in
// which some block slips faster than the seismic threshold V_th. The detector watches each
// accepted step and returns the finished event's record (engine/event_record.hpp) with the
// catalogue's common columns:
//   load        plate displacement V_pl t at the hypocentre time (the first crossing of V_th,
//               on the Hermite cubic of ln V over the step, so load/V_pl is that time)
//   trigger     the block that crossed first; blocks, first_block, last_block: those above V_th
//   moment      sum over those blocks of their slip from the event's start to its end [m]
//   magnitude   ln moment; duration: from the first upward to the last downward crossing
//   max_speed   the peak slip rate (located inside the step like the crossings) [m/s]
// plus the hypocentre time and the time of the peak slip rate (RsfEventTimes, and the record's
// hypocentre_time and peak_time). On a lattice (model rows > 1) the trigger and the bounding box
// are read as (x along strike, y across), with the row columns.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/event_record.hpp"
#include "engine/rsf_cycle.hpp"

namespace bkq {

// One step of the active-block integrator (engine/rsf_active.hpp) as the detector reads it:
// `count` slots, slot s holding block id[s] with (slip, ln V, ln theta) at y[3s..3s+2] and
// their rates in d, at the step's start (y0, d0, t0) and end (y1, d1, t1); slot[j] is block
// j's slot or -1, and a block in none has its slip held at held_slip[j].
struct RsfStepSpan {
  const RsfModel* model = nullptr;
  int n = 0, count = 0;
  const int *id = nullptr, *slot = nullptr;
  const double *y0 = nullptr, *d0 = nullptr, *y1 = nullptr, *d1 = nullptr;
  const double* held_slip = nullptr;
  double t0 = 0, t1 = 0;
};

struct RsfEventTimes {
  double hypocentre = 0;  // t at the first crossing of V_th
  double peak = 0;        // t of the peak slip rate
};

class RsfEventDetector {
 public:
  explicit RsfEventDetector(double v_threshold) : ln_vth_(std::log(v_threshold)) {}
  // After every accepted step of `c`: the record of an event that ended in it.
  std::optional<EventRecord> observe(const RsfCycle& c);
  // The same for a step of the active-block integrator: only its slots are read, and a block
  // that joins it during an event must be announced (activated(), with its slip then, which it
  // has held since the event's start unless it was integrated then).
  std::optional<EventRecord> observe(const RsfStepSpan& span);
  void activated(int j, double slip);
  // Two groups of the active-block integration merged at a time both have reached: `theirs`
  // (other's blocks) join `mine`. An event open in either goes on as one, from the earlier
  // hypocentre; a block whose group was not in it counts its slip from now (slip(j)).
  template <class Slip>
  void absorb(const RsfEventDetector& other, const std::vector<int>& mine,
              const std::vector<int>& theirs, const Slip& slip);
  bool in_event() const { return in_event_; }
  void forget_event() { in_event_ = false; }  // an open event dropped (a group's, reused)
  const RsfEventTimes& times() const { return times_; }
  std::int64_t events() const { return events_; }

  // Starts the current interval afresh at time t inside the last step (an afterslip episode
  // after the seismic event that ended at t): slips, peak and blocks are counted from t on.
  void restart(const RsfCycle& c, double t);

  // The detector's state as numbers (a checkpoint's), and back.
  std::vector<double> snapshot() const;
  void restore(const std::vector<double>& s);

 private:
  double ln_vth_;
  bool in_event_ = false;
  std::int64_t events_ = 0;
  int trigger_ = 0;
  RsfEventTimes times_;
  double ln_peak_ = 0;
  std::vector<double> slip0_;              // every block's slip at the event's start
  std::vector<char> seismic_;              // blocks above V_th during the event
  std::vector<int> seismic_ids_;           // the same, as a list
  std::vector<std::int64_t> slip0_event_;  // the event whose start slip0_[j] is (activated())

  template <class Ends>
  std::optional<EventRecord> observe_ends(const Ends& s, const RsfModel& m);
};

template <class Slip>
void RsfEventDetector::absorb(const RsfEventDetector& o, const std::vector<int>& mine,
                              const std::vector<int>& theirs, const Slip& slip) {
  if (!o.in_event_) {
    for (const int j : theirs) activated(j, slip(j));
    return;
  }
  const std::size_t n = o.seismic_.size();
  if (seismic_.size() != n) seismic_.assign(n, 0);
  slip0_.resize(n);
  slip0_event_.resize(n, 0);
  const std::int64_t mark = events_ + 1;
  if (!in_event_) {
    in_event_ = true;
    trigger_ = o.trigger_;
    times_ = o.times_;
    ln_peak_ = o.ln_peak_;
    for (const int j : seismic_ids_) seismic_[j] = 0;
    seismic_ids_.clear();
    for (const int j : mine) {
      slip0_[j] = slip(j);
      slip0_event_[j] = mark;
    }
  } else {
    const double h = o.times_.hypocentre;
    if (h < times_.hypocentre || (h == times_.hypocentre && o.trigger_ < trigger_))
      times_.hypocentre = h, trigger_ = o.trigger_;
    if (o.ln_peak_ > ln_peak_) ln_peak_ = o.ln_peak_, times_.peak = o.times_.peak;
  }
  for (const int j : theirs) {
    slip0_[j] = o.slip0_event_[j] == o.events_ + 1 ? o.slip0_[j] : slip(j);
    slip0_event_[j] = mark;
    if (o.seismic_[j] && !seismic_[j]) {
      seismic_[j] = 1;
      seismic_ids_.push_back(j);
    }
  }
}

// Slow-slip and afterslip episodes: intervals in which some block slips faster than V_slow
// (V_pl < V_slow < V_th) without any block reaching the seismic V_th. An interval that holds a
// seismic event is not one; what follows the event's end while some block is still above
// V_slow is an afterslip episode, counted from the event's end. The record has the event
// record's columns (load = V_pl x start, moment, blocks, duration, max_speed = peak slip rate).
struct RsfSlowEpisode {
  EventRecord record;
  bool afterslip = false;  // follows a seismic event; otherwise a slow-slip episode
};

class RsfSlowSlipDetector {
 public:
  RsfSlowSlipDetector(double v_slow, double v_threshold)
      : slow_(v_slow), ln_vth_(std::log(v_threshold)) {}
  // After every accepted step, before the seismic detector sees it.
  std::optional<RsfSlowEpisode> observe(const RsfCycle& c);
  // A seismic event ended at t (inside the last step).
  void event_ended(const RsfCycle& c, double t);
  std::int64_t episodes() const { return episodes_; }

  std::vector<double> snapshot() const;
  void restore(const std::vector<double>& s);

 private:
  RsfEventDetector slow_;
  double ln_vth_;
  bool afterslip_ = false;
  std::int64_t episodes_ = 0;
};

}  // namespace bkq
