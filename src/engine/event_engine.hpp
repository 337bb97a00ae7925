// The event-driven earthquake engine (Carlson & Langer 1989): a quasistatic loader and a
// dynamic relaxation with the full BK–Pad equations. docs/explanation/event-engine.md: the paths.
//
// Loading: every stuck block's force grows at one rate (ModelParams::loading_rate); the
// ForceTree gives the largest, and the substrate jumps so that block sits at the threshold.
// Relaxation: the substrate frozen, the stepper advances the sliding blocks plus one stuck
// neighbour each side (two for an event-locating stepper); neighbours join when their force
// passes the threshold; with a moving pad the tree is asked each step about far blocks;
// with every block stuck the pad is advanced in closed form (damped_oscillator.hpp).
// The relaxation asks its paths (engine/relaxation.hpp: the replayed start, the cluster
// kernel, the general step) which one applies; the one that does advances and reports, and
// the ledger (engine/event_ledger.hpp) books the report. The fast paths give the same
// events bit for bit as the general step (test_cluster, test_pad_paths); the replayed
// event start (lone_slip.hpp) changes rounding, not decisions (test_lone_slip); otherwise
// the events are the straightforward engine's (test_reference_events).
// End of an event: every block stuck by the stick rule and the pad at rest (its free
// oscillation removed in closed form once it can break no block).
// Energy balance (EventRecord::energy_residual): over an event nothing does work on the
// chain, so (dE_stored + W_friction+dampers)/W is zero for an exact integration; W by the
// trapezoidal rule per step, exact in the pad phase; dE from the slipped blocks and the pad.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "engine/active_set.hpp"
#include "engine/cluster_path.hpp"
#include "engine/event_ledger.hpp"
#include "engine/event_record.hpp"
#include "engine/general_path.hpp"
#include "engine/relaxation.hpp"
#include "engine/replay_path.hpp"
#include "engine/stencil_path.hpp"
#include "integrate/stepper.hpp"
#include "model/chain.hpp"

namespace bkq {

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

  EngineSnapshot snapshot() const { return EngineSnapshot{st_, ledger_.counters()}; }
  // The snapshot without a copy of the chain: the state moves into it, and the engine
  // must not be used until take_back() returns it (unchanged).
  EngineSnapshot lend_snapshot() { return EngineSnapshot{std::move(st_), ledger_.counters()}; }
  void take_back(EngineSnapshot&& lent) { st_ = std::move(lent.state); }

  // Load to the next failure and relax it; returns the event (numbered from 1).
  EventRecord next_event();

  const ChainState& state() const { return st_; }
  const EngineCounters& counters() const { return ledger_.counters(); }
  // Work done against friction and dampers, summed over the events of this engine (not
  // part of snapshots).
  double dissipated_total() const { return ledger_.dissipated_total(); }
  // Keep the slip of every block of each event (output.event_slip): after next_event(),
  // slips() holds (block, slip) for the blocks that slipped, by block. Off: nothing kept.
  void keep_slips(bool on) { ledger_.keep_slips = on; }
  const std::vector<std::pair<int, double>>& slips() const { return ledger_.slips(); }
  double load() const { return st_.s; }
  // Throws bkq::Error when the model cannot be driven event by event (no friction, no
  // drop from static to kinetic friction, or Rayleigh block damping).
  static void check_model(const ModelParams& p);
  // Largest spring force among stuck blocks beyond the threshold (<= 0 when all hold).
  double worst_stuck_excess() const;
  // Give up on an event after this many steps (a runaway means dt or the scene is wrong).
  std::int64_t max_steps_per_event = 200'000'000;
  // The optional paths (engine/relaxation.hpp), each the same events as the general step;
  // off only to test exactly that. The cluster kernel (cluster_path.hpp); the fused step
  // over held ranges (general_path.hpp); the replayed event start (replay_path.hpp); the
  // stencil kernel of lattices and long-range chains (stencil_path.hpp).
  bool cluster_path = true;
  bool held_ranges_path = true;
  bool lone_slip_path = true;
  bool stencil_path = true;

  // A further path, asked after the shipped fast paths and before the general step.
  void add_path(std::unique_ptr<RelaxationPath> path);
  // Hears every path's report before the ledger books it (tests and studies).
  void observe_reports(std::function<void(const PathReport&)> observer) {
    observer_ = std::move(observer);
  }
  // The paths' study counts (not part of snapshots).
  using ClusterSteps = ClusterPath::Steps;
  using LoneSlipStarts = ReplayPath::Starts;
  const ClusterSteps& cluster_steps() const { return cluster_.steps(); }
  const LoneSlipStarts& lone_slip_starts() const { return replay_.starts(); }
  std::int64_t pad_held_steps() const { return general_.pad_held_steps(); }
  std::int64_t stencil_steps() const { return stencil_.steps(); }
  StencilPath& stencil_kernel_path() { return stencil_; }

 private:
  double anchor() const { return st_.s + (pad_ ? st_.x : 0.0); }
  // The loader: moves the substrate until the most loaded block fails, opens the event
  // and releases that block; returns the pad's position then.
  double load_to_failure(EventRecord& e);
  // One call of the first path that applies, booked.
  void relax_step(Relaxation& rx);
  // Block j breaks loose: booked, its flags set, covered.
  void release(int j);
  void set_sliding(int j);
  bool query_tree_failures();
  bool pad_phase();  // true if a block failed while the pad swung
  void check_finite() const;

  const ChainForces& forces_;
  Stepper& stepper_;
  double dt_;
  ChainState st_;
  bool pad_;
  ActiveSet active_;
  EventLedger ledger_;
  ReplayPath replay_;
  ClusterPath cluster_;
  StencilPath stencil_;
  GeneralStepPath general_;
  std::vector<std::unique_ptr<RelaxationPath>> added_;
  // The paths in the order asked: replay, cluster, stencil, the added ones, general.
  std::vector<RelaxationPath*> paths_;
  std::function<void(const PathReport&)> observer_;
};

}  // namespace bkq
