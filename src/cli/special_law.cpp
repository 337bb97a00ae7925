// `bkquake special-law BK_RUN_DIR... > law.csv` (app/special_law.hpp).
#include <boost/program_options.hpp>
#include <iostream>

#include "app/special_law.hpp"
#include "bkquake_version.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

int cmd_special_law(const std::vector<std::string>& args) {
  boost::program_options::options_description opts(
      "bkquake special-law BK_RUN_DIR... > law.csv\n"
      "Tabulates the friction the held pad feels in continuous bk runs: per segment speed,\n"
      "-pad_friction_mean / (N m_u) from segments.csv (Ferre 2018 Fig. 4.8); CSV on stdout");
  opts.add_options()("help,h", "show this help");
  const auto vm = parse_command_line("special-law", args, opts, "runs", -1);
  if (printed_help(vm, opts)) return 0;
  if (!vm.count("runs")) throw Error("special-law: give at least one BK run folder");
  const auto runs = vm["runs"].as<std::vector<std::string>>();
  const auto law = special_law(runs);
  std::vector<std::string> comments = {std::string("bkquake ") + kVersion + " (git " +
                                       kGitRevision +
                                       ") special-law: -pad_friction_mean / (N m_u) "
                                       "per segment speed of:"};
  for (const auto& r : runs) comments.push_back("  " + r);
  std::cout << special_law_csv(law, comments);
  std::cerr << "special-law: " << law.size() << " speeds from " << law.front().speed << " to "
            << law.back().speed << "\n";
  return 0;
}

}  // namespace bkq
