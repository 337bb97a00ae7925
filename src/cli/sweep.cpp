// `bkquake sweep SWEEP.ini [--set key=value]... --out DIR [--resume]`: parses the arguments
// and calls app/sweep.hpp, which runs every point of the sweep on this process's ranks
// (one, or an MPI job's under mpirun).
#include <iostream>
#include <string>
#include <vector>

#include "app/sweep.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

namespace {

int cmd_sweep(const Args& args) {
  if (args.operands().empty()) throw Error("sweep: no SWEEP.ini given (see bkquake sweep --help)");
  if (!args.has("out")) throw Error("sweep: --out DIR is required");
  SweepRequest req;
  req.sweep_file = args.operands().front();
  req.overrides = args.texts("set");
  req.out_dir = args.text("out");
  req.resume = args.has("resume");
  req.force = args.has("force");
  if (req.resume && req.force) throw Error("sweep: --resume and --force exclude each other");
  return run_sweep(req);
}

}  // namespace

Command sweep_command_row() {
  return {
      "sweep",
      "run every point of a sweep file (also under mpirun), write sweep.csv",
      "SWEEP.ini",
      1,
      "Runs every point of a sweep file (also as 'mpirun -n K bkquake sweep ...').\n",
      {scene_set_option(), opt::text("out", "DIR", "output folder").required(),
       opt::flag("resume",
                 "finish the sweep in the output folder: only points not done run (with a "
                 "larger run.events or run.duration: every point is extended)"),
       opt::flag("force",
                 "write over the output folder (an earlier sweep's points and files go; not with "
                 "--resume)")},
      cmd_sweep};
}

}  // namespace bkq
