// The parts of an event's relaxation (docs/explanation/event-engine.md, "The driver"): the
// driver asks its paths, in order, which one applies to the state; the first that does
// advances the relaxation by one or more steps and reports what it did (PathReport), and
// the ledger (engine/event_ledger.hpp) applies the report to the counters, the energy books
// and the event record. A path sees the relaxation through Relaxation and changes only the
// state, the time and the event's energy book.
//
// The paths (each the same events bit for bit as the general step, from the same states):
//   replay   the start of an event from the lone block's recorded slide (replay_path.hpp)
//   cluster  a few blocks between two that hold, in the scheme's fixed-size kernel
//            (cluster_path.hpp)
//   stencil  a lattice's or a long-range chain's covered sites, in the scheme's kernel over
//            a run-time neighbour structure (stencil_path.hpp)
//   general  one step of the covered ranges, fused over held ranges where the scheme can
//            (general_path.hpp); it always applies and is asked last.
// A new path is a class deriving from RelaxationPath and one EventEngine::add_path call.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>

#include "engine/active_set.hpp"
#include "integrate/stepper.hpp"
#include "model/chain.hpp"

namespace bkq {

// Ranges are re-fitted to the sliding blocks every this many steps of an event.
inline constexpr int kShrinkEvery = 16;

// What a path did in one call.
struct PathReport {
  const char* path = "";                 // the path's name
  std::int64_t steps = 0;                // steps taken
  std::int64_t block_steps = 0;          // blocks advanced, summed over the steps
  std::int64_t sliding_block_steps = 0;  // blocks sliding after each step, summed
  // Work done against friction and the dampers: the change of the event's energy book,
  // which the path adds to piece by piece in the order the general step always did (so
  // the book's rounding is the same on every path); set by the driver.
  double work = 0;
  double max_speed = 0;  // largest sliding speed after the steps; NaN if a speed was NaN
  int sliding = 0;       // blocks sliding after the last step (releases included)
  // The located instant of the last stick, where the path knows one (NaN: the end of the
  // last step, unless it lies within it).
  double stick_time = std::nan("");
  // Blocks that broke loose at the end of the last step, in the order the ledger releases
  // them (it sets their flags and covers them).
  std::span<const int> released;
  // Blocks the stepper released inside its step, with their positions then (flags set and
  // covered already, since the step's contact pass reads them): the ledger notes them.
  std::span<const Stepper::Release> released_inside;
};

// The relaxation as the paths see it.
struct Relaxation {
  const ChainForces& forces;
  Stepper& stepper;
  const SchemeTraits& traits;  // the stepper's
  double dt;
  ChainState& st;
  ActiveSet& active;           // the covered ranges, the force tree over the others
  double& dissipated;          // the event's energy book
  bool pad;                    // the pad moves
  int trigger = 0;             // the block that started the event
  std::int64_t steps = 0;      // steps of the event so far
  std::int64_t max_steps = 0;  // the event gives up after this many
  // The optional paths' switches (EventEngine::lone_slip_path, ...).
  bool replay = true, cluster = true, held_ranges = true, stencil = true;

  double anchor() const { return st.s + (pad ? st.x : 0.0); }
};

class RelaxationPath {
 public:
  virtual ~RelaxationPath() = default;
  virtual const char* name() const = 0;
  // Advances the relaxation and fills `out` if this path applies to its state; returns
  // false, having changed nothing, if not.
  virtual bool advance(Relaxation& rx, PathReport& out) = 0;
};

}  // namespace bkq
