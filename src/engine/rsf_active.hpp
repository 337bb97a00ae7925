// An event of the event-driven rate-and-state engine (engine/rsf_loader.hpp) integrated on its
// active blocks only: the cost of a step scales with the blocks that move, not with N.
//
// Active blocks are integrated as the cycle integrator integrates the whole grid (Dormand-
// Prince 5(4) over (slip, ln V, ln theta), the full aging law, the scene's dynamics, the same
// error control); every other block stays with its closed form in the loader. Slip is counted
// from the integration's start in one coordinate per block, held while the block is not active.
//   - An inactive neighbour's slip is held at its value (its spring pulls an active block back
//     with -k_ji V_j, an extra unloading stiffness). Its closed-form creep meanwhile reaches the
//     active block through the loader's quanta, each a stress step on the block's integrated
//     state as it comes (the direct effect, theta kept); what the loader sums for the block
//     otherwise (a neighbour's creep settled as that neighbour joins) is passed on as one
//     stress step when the block leaves (RsfLoader::hold/release).
//   - Activation: after every accepted step each inactive neighbour i of an active block gets
//     the stress the active blocks' slip has put on it since its last update, sum k_ij
//     (delta_j - passed_ij), as the direct effect on its closed form, V_i exp(dtau/(a sigma))
//     at constant theta; where that reaches V_h, the stress is passed to it (a stress step), its
//     unsynced creep is settled and it joins the integration from its closed-form state. A
//     block whose own closed form reaches V_h or a creep quantum meanwhile is taken in time
//     order: the steps are clipped at the loader's next time.
//   - Hand-back: a block that passes the engine's hand-back test (at least one step after it
//     joined) goes back to its closed form from its slip rate and state, its position moves by
//     its slip since it joined, the stress summed for it is passed on, and the stress its slip
//     puts on its inactive neighbours (k_ij delta_j less what they have had) is passed to them.
// The integration ends when no block is active and no event is open (or at t_end, where every
// active block goes back). The seismic detector reads the active slots (RsfStepSpan).
//
// Groups (set_groups(true)): active blocks joined by a spring are integrated together, and
// groups that share none each with their own step size and clock, so that a nucleation far
// from an event is not carried at the event's steps. What they share goes through the loader,
// in time order: a group's step is taken (its stress passed on, its blocks handed back) only
// when no other group's step or loader item comes before its end, and a group is first
// brought to the time of a loader item that touches its active blocks or their neighbours
// (a block joining it, a neighbour's creep quantum), so that its steps stop at those only
// (without groups every step stops at every item). A block joining two groups merges them
// there. Each group has its own seismic detector; events of different groups that overlap in
// time are one event (one interval with some block above V_th, as the whole grid's detector
// counts them), the slip of its blocks counted over their own group's part of it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "engine/dormand_prince.hpp"
#include "engine/event_record.hpp"
#include "engine/rsf_cycle.hpp"
#include "engine/rsf_events.hpp"

namespace bkq {

class RsfLoader;

// The events the groups' detectors found (times on one clock), in order of their hypocentres,
// those that overlap in time joined into one: the earlier one's trigger, blocks and moments
// summed, the union of their bounding boxes, the higher peak, from the first hypocentre to the
// last end.
std::vector<EventRecord> join_overlapping(std::vector<EventRecord> found);

class RsfActiveIntegration {
 public:
  RsfActiveIntegration(const RsfModel& m, double tolerance, double v_threshold);
  // Groups of active blocks integrated apart (see above); off until called.
  void set_groups(bool on) { grouped_ = on; }
  bool groups() const { return grouped_; }

  // What the engine's hand-back test reads, by block: the cycle integrator's accessors for
  // the active blocks (y() and dy() in its layout, slip at j, ln V at n + j, ln theta at 2n + j).
  struct Column {
    const RsfActiveIntegration* a;
    int comp0;  // 0: y, 3: dy
    double operator[](int i) const { return a->value(i, comp0); }
  };
  int n() const { return m_.n(); }
  const RsfModel& model() const { return m_; }
  // The clock of the group being handed back (the run's, from its start).
  double t() const { return g_[cur_]->dp.t; }
  double slip(int j) const { return dp_of(j).y[3 * slot_[j]]; }
  double ln_v(int j) const { return dp_of(j).y[3 * slot_[j] + 1]; }
  double ln_theta(int j) const { return dp_of(j).y[3 * slot_[j] + 2]; }
  Column y() const { return {this, 0}; }
  Column dy() const { return {this, 3}; }
  double friction_stress(int j) const;
  // Whether the group being handed back is in an event.
  bool in_event() const { return g_[cur_]->detector.in_event(); }

  using HandBack = std::function<bool(const RsfActiveIntegration&, int)>;
  // One integration from block `first` reaching V_h at t0 (absolute times) until no block is
  // active and no event is open, or t_end; the loader keeps the other blocks and gets every
  // block back. Returns the end time; the events are in events(), their times from t0.
  double run(RsfLoader& loader, int first, double t0, double t_end, const HandBack& handed_back);
  const std::vector<EventRecord>& events() const { return events_; }

  std::int64_t accepted() const { return accepted_; }      // steps, all integrations
  std::int64_t slot_steps() const { return slot_steps_; }  // sum of active blocks per step
  std::int64_t activations() const { return activations_; }
  std::int64_t syncs() const { return syncs_; }    // quanta passed on during integrations
  std::int64_t resets() const { return resets_; }  // barriers started at steady state

 private:
  // A group of active blocks: its slots (block id[s], its (slip, ln V, ln theta) at 3s in dp's
  // state), their tau0, their springs (the neighbour's slot, -1 where it is held, its block and
  // k), its detector, and its step proposed but not yet taken (dp.proposed_t).
  struct Group {
    explicit Group(double v_threshold) : detector(v_threshold) {}
    dopri::Adaptive<> dp;
    std::vector<int> id;
    std::vector<double> tau0;
    mutable std::vector<double> v;  // rhs's slip rates
    std::vector<int> cstart, cslot, cblock;
    std::vector<double> ck;
    RsfEventDetector detector;
    bool live = false, proposed = false, parked = false, stale = false;
  };

  const dopri::Adaptive<>& dp_of(int j) const { return g_[group_[j]]->dp; }
  // Block j's t_a = a sigma/(k V_pl): the run's length at which the hand-back test cuts.
  double t_a(int j) const { return m_.law[j].params().a * m_.sigma / (m_.k * m_.v_pl); }
  // Block j's slip coordinate: integrated while active, held while not.
  double slip_or_held(int j) const { return slot_[j] >= 0 ? slip(j) : held_[j]; }
  double value(int i, int comp0) const;
  int new_group(double t);
  void retire(int g);
  void rebuild_stale();
  void activate(RsfLoader& loader, int j, int g, double t_abs, double dtau);
  void release(RsfLoader& loader, int j, double t_abs);
  void merge(int into, int from);
  void rebuild(int g);  // the slots' neighbour lists, and the FSAL derivative
  void rhs(const Group& g, double t, const double* y, double* dy);
  void propose(int g, double t_max);
  // The groups with an active block next to block b (the one group, without groups).
  void concerned(int b);
  // Loader items due by run time t whose groups are all there: processed; returns whether any
  // was.
  bool take_due(RsfLoader& loader, double t, double t0);
  // Processes the loader's next item at run time t; its groups (concerned_) are there.
  void process_item(RsfLoader& loader, double t0, double t);
  // Takes group g's proposed step and what follows it (the stress passed on, hand-backs).
  void commit(RsfLoader& loader, int g, double t0, const HandBack& handed_back);
  bool any_in_event() const;
  bool all_parked() const;  // every live group at the stop
  // The stress the active blocks' slip has put on inactive block i since it last had it.
  double owed(int i) const;
  RsfStepSpan span(const Group& g) const;

  RsfModel m_;
  double tol_, v_th_;
  RsfNeighbours nb_;
  bool grouped_ = false;
  // Per block (N): group and slot in it or -1, slip coordinate (held while inactive), slip when
  // it joined, whether it joined since its group's last step, and a stamp for visiting
  // neighbours once.
  std::vector<int> group_, slot_, stamp_;
  std::vector<char> fresh_;
  std::vector<double> held_, slip_at_join_;
  std::vector<double> passed_;  // per spring e of block i's row: slip of index[e] i has had
  std::vector<int> touched_;    // blocks that joined in this integration
  int stamp_now_ = 0;
  std::vector<std::unique_ptr<Group>> g_;  // groups, live or free for reuse
  std::vector<int> live_;                  // the live groups, by index
  std::vector<int> concerned_;             // concerned()'s answer
  int cur_ = 0;                            // the group being stepped or handed back
  double t_stop_ = 0;  // run time at which the groups stop (t_end, or a t_a cut)
  double t_end_ = 0;   // the run's t_end on its clock
  std::vector<char> in_touched_;
  std::int64_t accepted_ = 0;
  std::int64_t slot_steps_ = 0, activations_ = 0, syncs_ = 0, resets_ = 0;
  std::vector<int> leaving_;        // commit()'s blocks handed back, kept for its storage
  std::vector<EventRecord> found_;  // the groups' records, before overlapping ones are joined
  std::vector<EventRecord> events_;
};

}  // namespace bkq
