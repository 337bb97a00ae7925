// The straightforward event engine, kept as a yardstick: what EventEngine must agree with
// and what its speed is measured against (a straightforward engine's rate is the usual yardstick).
//
// It does what the quasistatic model says (Carlson & Langer 1989) and nothing clever. The loader
// scans every block for the largest spring force and moves the substrate until that block sits at
// the threshold (ties to the lowest index); the relaxation steps the whole chain, [0, N), with the
// stepper's general step() and the Crossing rule (settle_contacts) until every block is
// stuck. Stuck blocks have zero acceleration and zero velocity, so stepping them changes
// nothing: EventEngine, which steps only the sliding blocks and their stuck neighbours,
// must give the same events bit for bit when its lone-slip replay is off
// (tests/regression/test_reference_events.cpp).
//
// BK chains only (the pad held) and Crossing steppers (rk2, rk4, verlet): with a moving
// pad the all-stuck phase is solved in closed form by EventEngine, which a stepper cannot
// reproduce bit for bit. No energy balance is kept (energy_residual is 0).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/event_record.hpp"
#include "integrate/stepper.hpp"
#include "model/chain.hpp"

namespace bkq {

class ReferenceEventEngine {
 public:
  // Throws bkq::Error for a moving pad or a stepper that is not a Crossing one. The state's
  // blocks are all made stuck and at rest, as EventEngine does.
  ReferenceEventEngine(const ChainForces& forces, Stepper& stepper, double dt,
                       const ChainState& state);

  // Load to the next failure and relax it; returns the event (numbered from 1).
  EventRecord next_event();

  const ChainState& state() const { return st_; }
  // Replaces the state between events (every block stuck, at rest).
  void set_state(const ChainState& state);

  std::int64_t steps = 0;                // relaxation steps, summed over events
  std::int64_t block_steps = 0;          // N per step
  std::int64_t sliding_block_steps = 0;  // blocks sliding after each step, summed
  std::int64_t max_steps_per_event = 200'000'000;

 private:
  const ChainForces& forces_;
  Stepper& stepper_;
  double dt_;
  ChainState st_;
  std::int64_t events_ = 0;
  std::vector<double> w_before_, wd_old_;
  std::vector<unsigned char> slipped_;
};

}  // namespace bkq
