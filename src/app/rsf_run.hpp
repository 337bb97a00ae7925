// A rate-and-state run (friction.law = rsf): the cycle integrator (engine/rsf_cycle.hpp) from
// t = 0 to run.duration, its events (engine/rsf_events.hpp) written through the catalogue,
// histogram and summary observers every other run uses.
#pragma once

#include <string>

#include "app/run.hpp"
#include "io/output.hpp"
#include "io/settings.hpp"

namespace bkq {

int run_rsf(const RunRequest& req, const Settings& settings, const OutputFolder& out);

// `bkquake stability` of a rate-and-state scene (stats/rsf_stability.hpp): stability.csv's rows
// (one per chain mode q: its leading root at stiffness k + k_c mu_q), rsf_stability.csv (k,
// the critical stiffnesses, the frequency at k_crit, the unstable modes) and the lines printed.
// Per-block laws (rsf.blocks, rsf.pattern) get app/rsf_stability.hpp's dense analysis instead.
struct RsfStabilityReport {
  std::string modes_csv, summary_csv, text;
};
RsfStabilityReport rsf_stability(const Settings& settings);

}  // namespace bkq
