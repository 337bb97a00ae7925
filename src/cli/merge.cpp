// `bkquake merge RUN_DIR... --out DIR`: parses the arguments and calls app/merge.hpp, which
// merges the runs' histograms exactly and writes DIR/histogram.csv, DIR/summary.json and
// DIR/scene.ini (the scene they share and the seeds merged).
#include <boost/program_options.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "app/merge.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

namespace po = boost::program_options;

int cmd_merge(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake merge RUN_DIR... --out DIR\n"
      "Merges the histograms of runs of the same scene and fits the result");
  // clang-format off
  opts.add_options()
    ("help,h", "show this help")
    ("out", po::value<std::string>(), "output folder (created if missing)")
    ("force", "write into an output folder that already holds files")
    ("mu-min", po::value<std::string>(), "lower end of the fit window, in [-50, 50] (default "
                                         "or auto: automatic)")
    ("mu-max", po::value<std::string>(), "upper end of the fit window, in [-50, 50] (default "
                                         "or auto: automatic)");
  // clang-format on
  const po::variables_map vm = parse_command_line("merge", args, opts, "runs", -1);
  if (printed_help(vm, opts)) return 0;
  if (!vm.count("runs")) throw Error("merge: no RUN_DIR given (see bkquake merge --help)");
  if (!vm.count("out")) throw Error("merge: --out DIR is required");
  MergeRequest request{vm["runs"].as<std::vector<std::string>>(), vm["out"].as<std::string>(),
                       vm.count("force") > 0};
  request.mu_min = window_option(vm, "merge", "mu-min", "stats.mu_min");
  request.mu_max = window_option(vm, "merge", "mu-max", "stats.mu_max");
  if (request.mu_min && request.mu_max && !(*request.mu_max > *request.mu_min))
    throw Error("merge: --mu-max must be greater than --mu-min");
  merge_runs(request, std::cout);
  return 0;
}

}  // namespace bkq
