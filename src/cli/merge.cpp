// `bkquake merge RUN_DIR... --out DIR`: parses the arguments and calls app/merge.hpp, which
// merges the runs' histograms exactly and writes DIR/histogram.csv, DIR/summary.json and
// DIR/scene.ini (the scene they share and the seeds merged).
#include <iostream>
#include <string>
#include <vector>

#include "app/merge.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

namespace {

int cmd_merge(const Args& args) {
  if (args.operands().empty()) throw Error("merge: no RUN_DIR given (see bkquake merge --help)");
  if (!args.has("out")) throw Error("merge: --out DIR is required");
  MergeRequest request{args.operands(), args.text("out"), args.has("force")};
  request.mu_min = window_option(args, "mu-min", "stats.mu_min");
  request.mu_max = window_option(args, "mu-max", "stats.mu_max");
  if (request.mu_min && request.mu_max && !(*request.mu_max > *request.mu_min))
    throw Error("merge: --mu-max must be greater than --mu-min");
  merge_runs(request, std::cout);
  return 0;
}

}  // namespace

Command merge_command_row() {
  return {"merge",
          "merge the histograms of runs of the same scene and fit the result",
          "RUN_DIR...",
          -1,
          "Merges the histograms of runs of the same scene and fits the result.\n",
          {opt::text("out", "DIR", "output folder (created if missing)").required(),
           opt::flag("force", "write into an output folder that already holds files"),
           opt::text("mu-min", "MU",
                     "lower end of the fit window, in [-50, 50], or auto (default: auto)"),
           opt::text("mu-max", "MU",
                     "upper end of the fit window, in [-50, 50], or auto (default: auto)")},
          cmd_merge};
}

}  // namespace bkq
