// `bkquake sweep SWEEP.ini [--set key=value]... --out DIR [--resume]`: parses the arguments
// and calls app/sweep.hpp, which runs every point of the sweep on this process's ranks
// (one, or an MPI job's under mpirun).
#include <boost/program_options.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "app/sweep.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

namespace po = boost::program_options;

int cmd_sweep(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake sweep SWEEP.ini [--set section.key=value]... --out DIR [--resume | --force]\n"
      "Runs every point of a sweep file (also as 'mpirun -n K bkquake sweep ...')");
  add_scene_options(opts);
  opts.add_options()("out", po::value<std::string>(), "output folder (required)")(
      "resume",
      "finish the sweep in the output folder: only points not done run (with a larger "
      "run.events or run.duration: every point is extended)")(
      "force", "write over the output folder (an earlier sweep's points and files go)")(
      "help,h", "this help");
  const po::variables_map vm = parse_command_line("sweep", args, opts, "sweep", 1);
  if (printed_help(vm, opts)) return 0;
  if (!vm.count("sweep")) throw Error("sweep: no SWEEP.ini given (see bkquake sweep --help)");
  if (!vm.count("out")) throw Error("sweep: --out DIR is required");
  SweepRequest req;
  req.sweep_file = vm["sweep"].as<std::string>();
  if (vm.count("set")) req.overrides = vm["set"].as<std::vector<std::string>>();
  req.out_dir = vm["out"].as<std::string>();
  req.resume = vm.count("resume") > 0;
  req.force = vm.count("force") > 0;
  if (req.resume && req.force) throw Error("sweep: --resume and --force exclude each other");
  return run_sweep(req);
}

}  // namespace bkq
