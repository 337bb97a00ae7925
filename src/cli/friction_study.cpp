// `bkquake friction-study`: Ferre (2018, MSc thesis, NTNU) Fig. 4.6 (app/friction_study.hpp).
#include <algorithm>
#include <iostream>
#include <thread>

#include "app/friction_study.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"

namespace bkq {

namespace {

// The default of --jobs: the cores this machine reports (1 when it reports none).
int machine_cores() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

int cmd_friction_study(const Args& args) {
  StudyRequest req;
  req.out = args.text("out");
  req.scenes_dir = args.text("scenes");
  req.configs.clear();
  const std::string list = args.text("configs");
  for (std::size_t a = 0; a <= list.size();) {
    const std::size_t b = std::min(list.find(',', a), list.size());
    const std::string c = list.substr(a, b - a);
    if (c != "bkp" && c != "bk" && c != "1dof" && c != "special-1dof")
      throw Error("friction-study: --configs: unknown configuration '" + c +
                  "'; allowed: bkp, bk, 1dof, special-1dof");
    req.configs.push_back(c);
    a = b + 1;
  }
  req.seeds = args.integer("seeds");
  if (req.seeds < 1) throw Error("friction-study: --seeds must be >= 1");
  req.jobs = args.has("jobs") ? args.integer("jobs") : machine_cores();
  if (req.jobs < 1) throw Error("friction-study: --jobs must be >= 1");
  req.segment = args.real("segment");
  if (!(req.segment > 0)) throw Error("friction-study: --segment must be > 0");
  req.quiet = args.has("quiet");
  req.force = args.has("force");
  std::cout << run_friction_study(req) << "\n";
  return 0;
}

}  // namespace

Command friction_study_command_row() {
  return {
      "friction-study",
      "the four configurations of Ferre 2018 Fig. 4.6 over the speed grid",
      "",
      0,
      "Runs the configurations of Ferre (2018) Fig. 4.6 (scenes DIR/<config>.ini) over the\n"
      "speed grid 0.005..1 (five runs of speed segments) and writes OUT/friction_study.csv;\n"
      "plot it with analysis/plot_brake.py study OUT.\n",
      {opt::text("out", "OUT", "output folder (new or empty)", "friction_study"),
       opt::flag("force", "write over the files of an existing output folder"),
       opt::text("scenes", "DIR", "folder of the configurations' scenes", "data/scenes/brake"),
       opt::text("configs", "LIST", "comma-separated configurations: bkp, bk, 1dof, special-1dof",
                 "bkp,bk,1dof,special-1dof"),
       opt::integer("seeds", "N", "run bkp and bk with this many seeds", "1"),
       opt::integer("jobs", "J", "runs in parallel (default: the machine's cores)"),
       opt::real("segment", "T", "time units per speed segment (Ferre 2018: 2000)", "2000"),
       opt::flag("quiet", "no progress lines")},
      cmd_friction_study};
}

}  // namespace bkq
