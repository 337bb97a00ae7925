// Event-driven runs (quasistatic loading, Carlson & Langer 1989), fresh or continued from a
// checkpoint: the loop runs the transient events, then the recorded ones, and notifies the
// observers it attaches (catalog, histogram, summary, checkpoint timing, progress). Checkpoints are
// written when the timer asks, on SIGINT/SIGTERM (then exit 130/143) and before a failed event
// propagates its error; each observer puts its own state into them.
#pragma once

#include "app/run.hpp"
#include "integrate/stepper.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"

namespace bkq {

class OutputFolder;
struct Checkpoint;

// Returns the exit status: 0 when finished, 128 + signal when stopped by one.
int run_events(const RunRequest& req, const Settings& settings, const OutputFolder& out,
               const ChainForces& forces, Stepper& stepper, const Checkpoint* resumed);
// The same loop, observers and checkpoints for model.kind = ofc (engine/ofc.hpp).
int run_ofc_events(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                   const Checkpoint* resumed);

}  // namespace bkq
