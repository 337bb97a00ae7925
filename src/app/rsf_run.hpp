// A rate-and-state run (friction.law = rsf): the cycle integrator (engine/rsf_cycle.hpp) from
// t = 0 to run.duration, its events (engine/rsf_events.hpp) written through the catalogue,
// histogram and summary observers every other run uses.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "app/run.hpp"
#include "io/checkpoint.hpp"
#include "io/output.hpp"
#include "io/settings.hpp"

namespace bkq {

// A finished run's extension (`run --resume` with a larger run.events or run.duration): its
// final state, checked against the scene (app/run.cpp), the file it came from, and `adopt`,
// called on it once the output files are checked too, which makes the folder an interrupted
// run of the longer scene and returns the checkpoint's file.
struct RsfExtension {
  Checkpoint saved;
  std::string from;
  std::function<std::string(Checkpoint&)> adopt;
};

// A run from t = 0, or with req.resume the interrupted run in `out` continued (or the finished
// one extended, given `extension`).
int run_rsf(const RunRequest& req, const Settings& settings, const OutputFolder& out,
            std::optional<RsfExtension> extension = std::nullopt);

// `bkquake stability` of a rate-and-state scene (stats/rsf_stability.hpp): stability.csv's rows
// (one per chain mode q: its leading root at stiffness k + k_c mu_q), rsf_stability.csv (k,
// the critical stiffnesses, the frequency at k_crit, the unstable modes) and the lines printed.
// Per-block laws (rsf.blocks, rsf.pattern) get app/rsf_stability.hpp's dense analysis instead.
struct RsfStabilityReport {
  std::string modes_csv, summary_csv, text;
};
RsfStabilityReport rsf_stability(const Settings& settings);

}  // namespace bkq
