// The event-driven earthquake engine (SPEC §2): a quasistatic loader and a dynamic
// relaxation with the full BK–Pad equations.
//
// Loading. Between events every block is stuck and the pad is at rest, so each stuck
// block's spring force grows at the same rate per unit substrate displacement
// (ModelParams::loading_rate). The loader asks the ForceTree for the largest force and
// jumps the substrate so that block sits exactly at the threshold; no steps are spent.
//
// Relaxation. The substrate is frozen. The scene's stepper advances only the sliding
// blocks plus one stuck block on either side (the "covered" ranges); those neighbours
// are checked after every step and join when their force exceeds the threshold. With an
// event-locating stepper two stuck blocks are covered on each side: it locates a
// neighbour's release inside its step, and that neighbour's own neighbour must then be
// integrated too (one further release within the same step is only seen at its end). Stuck
// blocks elsewhere only feel the pad, uniformly, so with a moving pad the ForceTree is
// asked each step whether any of them has failed. When every block is stuck the pad is a
// damped linear oscillator; it is advanced in closed form to the first instant it pushes
// a stuck block over the threshold (located by bisection to ~1e-13 in time; that block
// then joins the same event), or, if no block can fail any more, to its rest position.
//
// Two fast paths give the same events bit for bit (tests/regression/test_cluster.cpp), and
// the whole engine gives the events of the straightforward engine that steps every block
// (engine/reference_events.hpp; tests/regression/test_reference_events.cpp), except for
// the replay of event starts below:
// while the sliding blocks lie within one covered range of at most kMaxCluster interior
// blocks with the pad held (most events never leave that shape) the stepper's
// fixed-size form steps the range with its state in registers (integrate/cluster.hpp);
// and with the pad held and every covered range ending in stuck blocks, the ranges
// cannot interact, so the stepper may fuse its stages over each of them
// (Stepper::step_held).
//
// A third path changes rounding, not decisions: every event starts with its trigger at
// the threshold, at rest, between stuck blocks, so the start is the same slide every time
// in coordinates relative to the trigger; it is integrated once and replayed
// (engine/lone_slip.hpp) until the block sticks or a neighbour breaks loose, wherever the
// rounding difference between the replay and a direct integration cannot change which.
// The events are then the same as direct integration's, with moments and speeds that
// differ by rounding (tests/regression/test_lone_slip.cpp); like any change in the
// order of the arithmetic, that lets a long chaotic run drift away from the direct one
// event by event. EventEngine::lone_slip_path turns it off.
//
// End of an event: every block stuck (by the stepper's stick rule) and the pad at rest —
// exactly at rest, since the pad's remaining free oscillation is removed in closed form
// once its amplitude can no longer break any block (with an undamped pad, zeta = 0, this
// discards the pad's free oscillation between events). The duration is the time from the
// trigger until the last block re-stuck.
//
// Energy balance of an event (EventRecord::energy_residual). Loading happens before the
// event, so over the relaxation nothing does work on the chain: the energy stored in the
// springs can only go into friction and the dampers, and the chain is at rest at both
// ends. The engine accumulates W, the work done against friction (and the 1DOF damper),
// by the trapezoidal rule on each step, plus the pad damper's (trapezoidal while blocks
// slide; exact in the closed-form pad phase, where the pad's energy lost is the damper's
// work, and where the free oscillation removed at the end counts as dissipated — for an
// undamped pad that energy is discarded, not dissipated). The change of stored energy
// dE is computed from the blocks that slipped and the pad alone (O(event), not O(N)).
// The residual is (dE + W)/W: zero for an exact integration; with the crossing rule its
// size is set by the step (the quadrature is second order and a re-sticking block's last
// step leaves an O(dt) kinetic remainder that the rule zeroes).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/contacts.hpp"
#include "engine/event_record.hpp"
#include "engine/force_tree.hpp"
#include "engine/lone_slip.hpp"
#include "integrate/cluster.hpp"
#include "integrate/stepper.hpp"
#include "model/chain.hpp"

namespace bkq {

struct EngineCounters {
  std::int64_t events = 0;
  std::int64_t steps = 0;                // relaxation steps
  std::int64_t block_steps = 0;          // blocks advanced, summed over steps
  std::int64_t sliding_block_steps = 0;  // of which sliding
  std::int64_t releases = 0;             // stuck -> sliding transitions (chattering shows here)
};

// What an engine needs to continue exactly where it stopped: the state between two
// events (every block stuck, pad at rest) and the counters. Everything else the engine
// holds (the force tree, the covered ranges) is rebuilt from it bit for bit.
struct EngineSnapshot {
  ChainState state;
  EngineCounters counters;
};

class EventEngine {
 public:
  // A fresh start: all blocks stuck, velocities zeroed, the pad put at its static balance.
  EventEngine(const ChainForces& forces, Stepper& stepper, double dt, ChainState state);
  // Continue from a snapshot taken between events; nothing is recomputed, so the events
  // that follow are the same, bit for bit, as those of the engine that was snapshotted.
  EventEngine(const ChainForces& forces, Stepper& stepper, double dt, const EngineSnapshot& saved);

  EngineSnapshot snapshot() const { return EngineSnapshot{st_, counters_}; }

  // Load to the next failure and relax it; returns the event (numbered from 1).
  EventRecord next_event();

  const ChainState& state() const { return st_; }
  const EngineCounters& counters() const { return counters_; }
  double load() const { return st_.s; }
  // Throws bkq::Error when the model cannot be driven event by event (no friction, or no
  // drop from static to kinetic friction).
  static void check_model(const ModelParams& p);
  // Largest spring force among stuck blocks beyond the threshold (<= 0 when all hold).
  double worst_stuck_excess() const;
  // Give up on an event after this many steps (a runaway means dt or the scene is wrong).
  std::int64_t max_steps_per_event = 200'000'000;
  // While the sliding blocks lie within one range of at most kMaxCluster interior blocks
  // (pad held, a Crossing stepper), step it with the stepper's fixed-size form
  // (integrate/cluster.hpp): the same events bit for bit, in less time. Off only to test
  // exactly that.
  bool cluster_path = true;
  // With the pad held and every covered range ending in stuck blocks, use the stepper's
  // step_held() (again the same events bit for bit).
  bool held_ranges_path = true;
  // Steps this engine took on the cluster path (not part of snapshots): all of them,
  // those with more than one block between the ends, and those at a free chain end.
  struct ClusterSteps {
    std::int64_t all = 0, multi_block = 0, left_end = 0, right_end = 0;
  };
  const ClusterSteps& cluster_steps() const { return cluster_steps_; }
  // Start each event from the lone block's recorded slide (engine/lone_slip.hpp) where
  // rounding cannot change the outcome; off, every step is integrated directly.
  bool lone_slip_path = true;
  // Events this engine started from the record (not part of snapshots): all of them, those
  // it finished there (no neighbour broke loose), the steps it took from it, and the
  // events it could have started there but integrated directly because a decision lay
  // within the rounding bound.
  struct LoneSlipStarts {
    std::int64_t replayed = 0, finished = 0, steps = 0, declined = 0;
  };
  const LoneSlipStarts& lone_slip_starts() const { return lone_starts_; }

 private:
  double anchor() const { return st_.s + (pad_ ? st_.x : 0.0); }
  void allocate_bookkeeping();  // per-block flags and scratch, all clear
  void rebuild_tree();
  void release(int j);
  // Records block j as slipped in this event, at position w_at_release (first time only).
  void note_slipped(int j, double w_at_release);
  void cover(int j);
  void add_to_ranges(int k);
  void shrink_ranges();
  void uncover_all();
  bool query_tree_failures();
  bool pad_phase();              // true if a block failed while the pad swung
  void note_released_in_step();  // bookkeeping for blocks a Projection/Located stepper released
  // Change of the energy stored in the springs since the event started (pad at x0 then).
  double stored_energy_change(double x0) const;
  void check_finite() const;
  // Whether the covered blocks form a cluster (integrate/cluster.hpp); if so, sets its
  // shape in r.
  bool cluster_ready(ClusterRelaxation& r) const;
  bool held_ranges() const;
  // Steps the cluster; false when the stepper has no fixed-size form.
  bool relax_cluster(ClusterRelaxation& r, std::int64_t& steps, ContactScan& scan);
  // Takes the start of the event triggered by block j from the lone slip's record, up to
  // the step at which the block sticks or a neighbour breaks loose; false, having done
  // nothing, when the record does not apply or rounding could decide.
  bool replay_start(int j, std::int64_t& steps, ContactScan& scan);

  const ChainForces& forces_;
  Stepper& stepper_;
  double dt_;
  ChainState st_;
  bool pad_;
  int n_;
  int margin_;  // stuck neighbours integrated on each side of a sliding block

  ForceTree tree_;
  std::vector<Range> ranges_;
  std::vector<unsigned char> covered_, need_;
  std::vector<double> wd_old_, mobile_old_, w_old_;  // at the start of a step
  std::vector<int> released_now_;

  // Per-event bookkeeping.
  std::vector<unsigned char> slipped_;
  std::vector<int> slipped_list_;
  std::vector<double> w_before_;
  double max_speed_ = 0, last_stick_time_ = 0;
  double dissipated_ = 0;  // work done against friction and dampers during the event
  int sliding_ = 0;

  EngineCounters counters_;
  ClusterSteps cluster_steps_;
  // The lone slip of an interior block [0] and of a block at a free chain end [1], built
  // when first needed.
  LoneSlip lone_[2];
  bool lone_built_[2] = {false, false};
  LoneSlipStarts lone_starts_;
};

}  // namespace bkq
