// `bkquake merge RUN_DIR... --out DIR`: parses the arguments and calls app/merge.hpp, which
// merges the runs' histograms exactly and writes DIR/histogram.csv and DIR/summary.json.
#include <boost/program_options.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "app/merge.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"

namespace bkq {

namespace po = boost::program_options;

int cmd_merge(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake merge RUN_DIR... --out DIR\n"
      "Merges the histograms of runs of the same scene and fits the result");
  opts.add_options()("help,h", "show this help")("out", po::value<std::string>(),
                                                 "output folder (created if missing)");
  po::options_description hidden;
  hidden.add_options()("runs", po::value<std::vector<std::string>>());
  po::options_description all;
  all.add(opts).add(hidden);
  po::positional_options_description pos;
  pos.add("runs", -1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(all).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    throw Error(std::string("merge: ") + e.what());
  }
  if (vm.count("help")) {
    std::cout << opts << "\n";
    return 0;
  }
  if (!vm.count("runs")) throw Error("merge: no RUN_DIR given (see bkquake merge --help)");
  if (!vm.count("out")) throw Error("merge: --out DIR is required");
  merge_runs({vm["runs"].as<std::vector<std::string>>(), vm["out"].as<std::string>()}, std::cout);
  return 0;
}

}  // namespace bkq
