// Continuously driven runs (Ferre 2018 ch. 4), fresh or continued from a checkpoint: the loop
// steps the driver to run.duration, samples it every output.every and notifies the
// observers it attaches (time series, block trajectories, episode catalog, magnitude
// histogram, pad-friction statistics, summary with the Gutenberg-Richter fit of the
// episodes, checkpoint timing, progress). Checkpoints are written between two time steps
// when the timer asks and on SIGINT/SIGTERM (then exit 130/143); they hold the driver's
// state (the stepper's carried state included) and each observer's, so a resumed run
// writes the files of a run that never stopped, byte for byte.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "app/run.hpp"
#include "integrate/stepper.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"

namespace bkq {

class OutputFolder;
struct Checkpoint;

// The time steps a continuous run of these settings takes: ceil(run.duration /
// integrator.dt), fixed up front so the end does not depend on the rounding of t += dt.
std::int64_t continuous_steps(const Settings& settings);

// Returns the exit status: 0 when finished, 128 + signal when stopped by one; throws
// bkq::Error when the integration turns non-finite.
int run_continuous(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                   const ChainForces& forces, Stepper& stepper);
// Continues the run of checkpoint `saved` (read from the file `from`, already checked
// against the scene, and the catalog against it): checks the sampled files, cuts every
// file back to the checkpoint (nothing is changed when a check fails) and runs on.
// `adopt`, when given, is called once every check has passed and before any file is cut
// back (an extension makes the finished run an interrupted run of the longer scene there).
int resume_continuous(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                      const ChainForces& forces, Stepper& stepper, const Checkpoint& saved,
                      const std::string& from, const std::function<void()>& adopt = {});

}  // namespace bkq
