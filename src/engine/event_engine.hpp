// The event-driven earthquake engine (Carlson & Langer 1989): a quasistatic loader and a
// dynamic relaxation with the full BK–Pad equations. docs/explanation/event-engine.md: the paths.
//
// Loading: every stuck block's force grows at one rate (ModelParams::loading_rate); the
// ForceTree gives the largest, and the substrate jumps so that block sits at the threshold.
// Relaxation: the substrate frozen, the stepper advances the sliding blocks plus one stuck
// neighbour each side (two for an event-locating stepper); neighbours join when their force
// passes the threshold; with a moving pad the tree is asked each step about far blocks;
// with every block stuck the pad is advanced in closed form (damped_oscillator.hpp).
// Fast paths (cluster in registers, fused held ranges) give the same events bit for bit
// (test_cluster); the replayed event start (lone_slip.hpp) changes rounding, not decisions
// (test_lone_slip); otherwise the events are the straightforward engine's (test_reference_events).
// End of an event: every block stuck by the stick rule and the pad at rest (its free
// oscillation removed in closed form once it can break no block).
// Energy balance (EventRecord::energy_residual): over an event nothing does work on the
// chain, so (dE_stored + W_friction+dampers)/W is zero for an exact integration; W by the
// trapezoidal rule per step, exact in the pad phase; dE from the slipped blocks and the pad.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "engine/contacts.hpp"
#include "engine/event_record.hpp"
#include "engine/force_tree.hpp"
#include "engine/lone_slip.hpp"
#include "integrate/block_window.hpp"
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
  // The snapshot without a copy of the chain: the state moves into it, and the engine
  // must not be used until take_back() returns it (unchanged).
  EngineSnapshot lend_snapshot() { return EngineSnapshot{std::move(st_), counters_}; }
  void take_back(EngineSnapshot&& lent) { st_ = std::move(lent.state); }

  // Load to the next failure and relax it; returns the event (numbered from 1).
  EventRecord next_event();

  const ChainState& state() const { return st_; }
  const EngineCounters& counters() const { return counters_; }
  // Keep the slip of every block of each event (output.event_slip): after next_event(),
  // slips() holds (block, slip) for the blocks that slipped, by block. Off: nothing kept.
  void keep_slips(bool on) { keep_slips_ = on; }
  const std::vector<std::pair<int, double>>& slips() const { return slips_; }
  double load() const { return st_.s; }
  // Throws bkq::Error when the model cannot be driven event by event (no friction, no
  // drop from static to kinetic friction, or Rayleigh block damping).
  static void check_model(const ModelParams& p);
  // Largest spring force among stuck blocks beyond the threshold (<= 0 when all hold).
  double worst_stuck_excess() const;
  // Give up on an event after this many steps (a runaway means dt or the scene is wrong).
  std::int64_t max_steps_per_event = 200'000'000;
  // While the sliding blocks lie within one range of at most kMaxCluster interior blocks
  // (a Crossing stepper or located transitions; the pad held or moving), step it with the
  // stepper's fixed-size form (integrate/cluster.hpp; located: up to the step before a
  // transition, which the general path takes): the same events bit for bit, in less time.
  // Off only to test exactly that.
  bool cluster_path = true;
  // With every covered range ending in stuck blocks (the pad held or moving), use the stepper's
  // step_held() (again the same events bit for bit).
  bool held_ranges_path = true;
  // Steps this engine took with the pad moving on the fused held-range path (not part of
  // snapshots).
  std::int64_t pad_held_steps() const { return pad_held_steps_; }
  // Steps this engine took on the cluster path (not part of snapshots): all of them,
  // those with more than one block between the ends, and those at a free chain end.
  struct ClusterSteps {
    std::int64_t all = 0, multi_block = 0, left_end = 0, right_end = 0;
  };
  const ClusterSteps& cluster_steps() const { return cluster_steps_; }
  // Start each event from the lone block's recorded slide (engine/lone_slip.hpp) where
  // rounding cannot change the outcome; off, every step is integrated directly. Chains with
  // nearest-neighbour springs and lattices (any stencil in the plane: a record per stiffness
  // of a site, its partners tested each with its spring); no dashpots, no moving pad.
  bool lone_slip_path = true;
  // Events this engine started from the record (not part of snapshots): all of them, those
  // it finished there (no neighbour broke loose), the steps it took from it, and the
  // events it could have started there but integrated directly because a decision lay
  // within the rounding bound; located, also those where a neighbour fails in the first step
  // (nothing to replay: the general path locates the failure).
  struct LoneSlipStarts {
    std::int64_t replayed = 0, finished = 0, steps = 0, declined = 0, immediate = 0;
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
  // The stepper's cluster form with the pad moving (engine/pad_paths.cpp): r as for
  // Stepper::relax_cluster, completed with what the pad's form needs.
  bool relax_pad_cluster(ClusterRelaxation& r);
  // Takes the start of the event triggered by block j from the lone slip's record, up to
  // the step at which the block sticks or a neighbour breaks loose; false, having done
  // nothing, when the record does not apply or rounding could decide.
  bool replay_start(int j, std::int64_t& steps, ContactScan& scan);
  // The record for block j of a chain or site j of a lattice (built when first needed), with
  // partners_ set to the blocks its slide pulls on.
  const LoneSlip& chain_lone_slip(int j);
  const LoneSlip& lattice_lone_slip(int j);

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
  // Velocities, stick flags and positions at the start of a step (the last two for
  // steppers that resolve transitions themselves), over the blocks of the step's ranges.
  enum { kWdOld, kMobileOld, kWOld };
  RangeArrays old_{3};
  std::vector<int> released_now_;

  // Per-event bookkeeping.
  std::vector<unsigned char> slipped_;
  std::vector<int> slipped_list_;
  std::vector<double> w_before_;
  bool keep_slips_ = false;
  std::vector<std::pair<int, double>> slips_;
  double max_speed_ = 0, last_stick_time_ = 0;
  // The located stick of an event the lone slip's record finished (NaN otherwise).
  double replayed_stick_time_ = 0;
  double dissipated_ = 0;  // work done against friction and dampers during the event
  int sliding_ = 0;

  EngineCounters counters_;
  ClusterSteps cluster_steps_;
  std::int64_t pad_held_steps_ = 0;
  // The lone slip of an interior block [0] and of a block at a free chain end [1], built
  // when first needed.
  LoneSlip lone_[2];
  bool lone_built_[2] = {false, false};
  // A lattice's records, one per stiffness met (interior, edge and corner sites), and the
  // largest sum of a site's springs (the rounding bound's, lone_slip_tolerance).
  std::vector<LoneSlip> lattice_lone_;
  double lattice_coupled_ = 0;
  // The blocks a lone block's slide pulls on, the spring to each and the step at which each
  // breaks loose (past the record: never).
  struct Partner {
    int site = 0;
    double k = 0;
    std::int64_t breaks_at = 0;
  };
  std::vector<Partner> partners_;
  LoneSlipStarts lone_starts_;
};

}  // namespace bkq
