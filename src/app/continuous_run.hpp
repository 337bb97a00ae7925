// Continuously driven runs (SPEC §3): the loop steps the driver to run.duration, samples
// it every output.every and notifies the observers it attaches (time series, block
// trajectories, episode catalog, magnitude histogram, pad-friction statistics, summary
// with the Gutenberg-Richter fit of the episodes, progress).
#pragma once

#include "app/run.hpp"
#include "integrate/stepper.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"

namespace bkq {

class OutputFolder;

// Returns 0; throws bkq::Error when the integration turns non-finite.
int run_continuous(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                   const ChainForces& forces, Stepper& stepper);

}  // namespace bkq
