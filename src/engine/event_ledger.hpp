// The one place where what the relaxation did is booked: the paths' reports
// (engine/relaxation.hpp) go to the run's counters, the event's energy books and its record
// (the blocks that slipped, where each started, the largest speed, when the last one stuck).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "engine/event_record.hpp"
#include "engine/relaxation.hpp"
#include "model/chain.hpp"

namespace bkq {

struct EngineCounters {
  std::int64_t events = 0;
  std::int64_t steps = 0;                // relaxation steps
  std::int64_t block_steps = 0;          // blocks advanced, summed over steps
  std::int64_t sliding_block_steps = 0;  // of which sliding
  std::int64_t releases = 0;             // stuck -> sliding transitions (chattering shows here)
};

class EventLedger {
 public:
  explicit EventLedger(int n_blocks);

  const EngineCounters& counters() const { return counters_; }
  void set_counters(const EngineCounters& c) { counters_ = c; }
  // Keep the slip of every block of each event (EventEngine::keep_slips).
  bool keep_slips = false;
  const std::vector<std::pair<int, double>>& slips() const { return slips_; }

  // A new event: numbers it (into e) and clears the event's books.
  void open(EventRecord& e);
  // Block j broke loose at position w (its first release in the event fixes where its
  // slip starts).
  void note_release(int j, double w);
  // Applies a path's report: the counters, the blocks it released (release(j) sets each
  // one's flags and covers it; the ledger notes it), the sliding count and the largest speed.
  template <class Release>
  void apply(const PathReport& r, const ChainState& st, Release&& release) {
    event_steps_ += r.steps;
    counters_.steps += r.steps;
    counters_.block_steps += r.block_steps;
    counters_.sliding_block_steps += r.sliding_block_steps;
    for (const Stepper::Release& q : r.released_inside) note_release(q.block, q.w);
    sliding_ = r.sliding;
    for (int j : r.released) {
      note_release(j, st.w[j]);
      release(j);
    }
    if (!(r.max_speed <= max_speed_)) max_speed_ = r.max_speed;
  }
  // After the step's other releases (the pad's far failures): with every block stuck, the
  // event's duration is the located instant of the last stick when it lies in the last
  // step, else the step's end t.
  void end_of_step(double stick_time, double t, double dt) {
    if (sliding_ == 0) last_stick_time_ = stick_time > t - dt && stick_time <= t ? stick_time : t;
  }
  // Sliding blocks now; a block that broke loose outside a path's step adds one.
  int sliding() const { return sliding_; }
  void add_sliding() { ++sliding_; }
  std::int64_t event_steps() const { return event_steps_; }
  double max_speed() const { return max_speed_; }
  // The event's energy book: work against friction and dampers (the paths add to it).
  double& dissipated() { return dissipated_; }
  // The books summed over the closed events since construction (not part of snapshots).
  double dissipated_total() const { return dissipated_total_; }

  // Closes the event into e: the slipped blocks, moment, magnitude, duration, largest
  // speed, the pad's displacement (from x0) and the energy balance.
  void close(EventRecord& e, const ChainForces& forces, const ChainState& st, double x0);

 private:
  // Change of the energy stored in the springs since the event started (pad at x0 then).
  double stored_energy_change(const ChainForces& forces, const ChainState& st, double x0) const;

  EngineCounters counters_;
  std::vector<unsigned char> slipped_;
  std::vector<int> slipped_list_;
  std::vector<double> w_before_;
  std::vector<std::pair<int, double>> slips_;
  std::int64_t event_steps_ = 0;
  double max_speed_ = 0, last_stick_time_ = 0, dissipated_ = 0, dissipated_total_ = 0;
  int sliding_ = 0;
};

}  // namespace bkq
