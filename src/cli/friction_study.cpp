// `bkquake friction-study`: Ferre (2018, MSc thesis, NTNU) Fig. 4.6 (app/friction_study.hpp).
#include <boost/program_options.hpp>
#include <iostream>

#include "app/friction_study.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

int cmd_friction_study(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  po::options_description opts(
      "bkquake friction-study [options]\n"
      "Runs the configurations of Ferre (2018) Fig. 4.6 (scenes DIR/<config>.ini) over the speed\n"
      "grid 0.005..1 (five runs of speed segments) and writes OUT/friction_study.csv;\n"
      "plot it with analysis/plot_brake.py study OUT");
  // clang-format off
  opts.add_options()
    ("help,h", "show this help")
    ("out", po::value<std::string>()->default_value("friction_study"), "output folder (new or empty)")
    ("force", "write over the files of an existing output folder")
    ("scenes", po::value<std::string>()->default_value("data/scenes/brake"),
               "folder of the configurations' scenes")
    ("configs", po::value<std::string>()->default_value("bkp,bk,1dof,special-1dof"),
                "comma-separated configurations")
    ("seeds", po::value<int>()->default_value(1), "run bkp and bk with this many seeds")
    ("jobs", po::value<int>()->default_value(2), "runs in parallel")
    ("segment", po::value<double>()->default_value(2000), "time units per speed segment "
                                                          "(Ferre 2018: 2000)")
    ("quiet", "no progress lines");
  // clang-format on
  const auto vm = parse_command_line("friction-study", args, opts, "unused", 0);
  if (printed_help(vm, opts)) return 0;
  StudyRequest req;
  req.out = vm["out"].as<std::string>();
  req.scenes_dir = vm["scenes"].as<std::string>();
  req.configs.clear();
  const std::string list = vm["configs"].as<std::string>();
  for (std::size_t a = 0; a <= list.size();) {
    const std::size_t b = std::min(list.find(',', a), list.size());
    const std::string c = list.substr(a, b - a);
    if (c != "bkp" && c != "bk" && c != "1dof" && c != "special-1dof")
      throw Error("friction-study: --configs: unknown configuration '" + c +
                  "'; allowed: bkp, bk, 1dof, special-1dof");
    req.configs.push_back(c);
    a = b + 1;
  }
  req.seeds = vm["seeds"].as<int>();
  if (req.seeds < 1) throw Error("friction-study: --seeds must be >= 1");
  req.jobs = vm["jobs"].as<int>();
  if (req.jobs < 1) throw Error("friction-study: --jobs must be >= 1");
  req.segment = vm["segment"].as<double>();
  if (!(req.segment > 0)) throw Error("friction-study: --segment must be > 0");
  req.quiet = vm.count("quiet") > 0;
  req.force = vm.count("force") > 0;
  std::cout << run_friction_study(req) << "\n";
  return 0;
}

}  // namespace bkq
