// `bkquake special-law BK_RUN_DIR... > law.csv` (app/special_law.hpp).
#include <iostream>

#include "app/special_law.hpp"
#include "bkquake_version.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

namespace {

int cmd_special_law(const Args& args) {
  if (args.operands().empty()) throw Error("special-law: give at least one BK run folder");
  const auto runs = args.operands();
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

}  // namespace

Command special_law_command_row() {
  return {"special-law",
          "the friction a held pad feels in BK runs (Ferre 2018 Fig. 4.8)",
          "BK_RUN_DIR...",
          -1,
          "Tabulates the friction the held pad feels in continuous bk runs: per segment speed,\n"
          "-pad_friction_mean / (N m_u) from segments.csv (Ferre 2018 Fig. 4.8); CSV on stdout\n"
          "(bkquake special-law BK_RUN_DIR... > law.csv).\n",
          {},
          cmd_special_law};
}

}  // namespace bkq
