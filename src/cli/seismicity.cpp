// `bkquake seismicity RUN_DIR|CATALOG`: parses the arguments and calls app/seismicity.hpp
// for the run folder, each point of a sweep folder, or the catalogue file.
#include <boost/program_options.hpp>
#include <iostream>
#include <sstream>

#include "app/seismicity.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"
#include "io/readme_tables.hpp"
#include "io/seismicity_csv.hpp"

namespace bkq {

namespace po = boost::program_options;

namespace {

std::vector<double> parse_list(const std::string& text) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v))
      throw Error("seismicity: --interevent-mu = " + text +
                  ": expected a comma-separated list of magnitudes, e.g. -2,0,2");
    out.push_back(v);
  }
  return out;
}

}  // namespace

int cmd_seismicity(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake seismicity RUN_DIR|SWEEP_DIR|CATALOG [options]\n"
      "Seismicity statistics of an event catalogue (waiting times, recurrence, Omori-Utsu\n"
      "aftershocks and foreshocks, Båth's law, moment rate, rupture scaling, the Mogi\n"
      "picture); writes RUN_DIR/seismicity/ (interevent.csv, recurrence.csv, omori.csv,\n"
      "moment_rate.csv, scaling.csv, spacetime.csv, seismicity.json)");
  // clang-format off
  opts.add_options()
    ("help,h", "show this help")
    ("out", po::value<std::string>(), "output folder (default RUN_DIR/seismicity, or "
                                      "seismicity/ beside the catalogue)")
    ("mainshock-mu", po::value<double>(), "mainshocks (and the large events whose recurrence "
                                          "is measured) are events with mu >= X (default: "
                                          "events spanning more than half the chain)")
    ("blocks", po::value<int>(), "chain length N when no scene.ini is beside the catalogue "
                                 "(default: max(last_block) + 1)")
    ("b-mu-min", po::value<double>(), "lower magnitude of the b-values before mainshocks "
                                      "(default: maximum curvature)")
    ("interevent-mu", po::value<std::string>(), "magnitude thresholds of the waiting-time "
                                                "subsets (default -4,-2,0,2)")
    ("export", po::value<std::string>(), "also write the catalogue as FILE in seismology's "
                                         "conventions (time, Mw, x along strike)")
    ("mw-offset", po::value<double>()->default_value(0.0), "C of Mw = (2/3) log10 M + C in "
                                                           "the export");
  // clang-format on
  // Hidden: the docs page's column tables (docs/explanation/seismicity.md), with their
  // markers, from the schemas; tests/regression/test_seismicity.cpp checks the page.
  if (args.size() == 1 && args[0] == "--doc-tables") {
    for (const auto& [name, schema] : seismicity_schemas())
      std::cout << readme_begin_marker(name) << "\n"
                << column_table(*schema) << readme_end_marker(name) << "\n\n";
    return 0;
  }
  const po::variables_map vm = parse_command_line("seismicity", args, opts, "input", 1);
  if (printed_help(vm, opts)) return 0;
  if (!vm.count("input"))
    throw Error("seismicity: missing RUN_DIR or CATALOG (see bkquake seismicity --help)");
  SeismicityRequest req;
  req.input = vm["input"].as<std::string>();
  if (vm.count("out")) req.out = vm["out"].as<std::string>();
  if (vm.count("mainshock-mu")) {
    req.mainshock_mu = vm["mainshock-mu"].as<double>();
    if (!std::isfinite(*req.mainshock_mu)) throw Error("seismicity: --mainshock-mu must be finite");
  }
  if (vm.count("blocks")) {
    req.blocks = vm["blocks"].as<int>();
    if (*req.blocks < 1)
      throw Error("seismicity: --blocks = " + std::to_string(*req.blocks) +
                  ": expected at least 1");
  }
  if (vm.count("b-mu-min")) req.b_mu_min = vm["b-mu-min"].as<double>();
  if (vm.count("interevent-mu"))
    req.interevent_mu = parse_list(vm["interevent-mu"].as<std::string>());
  if (vm.count("export")) req.export_file = vm["export"].as<std::string>();
  req.mw_offset = vm["mw-offset"].as<double>();
  const auto inputs = seismicity_inputs(req.input);
  if (inputs.size() > 1 && (!req.out.empty() || !req.export_file.empty()))
    throw Error("seismicity: " + req.input + " is a sweep folder (" +
                std::to_string(inputs.size()) +
                " replicas with a catalogue): --out and --export take one catalogue; each "
                "replica's results go into its own seismicity/ (points/pNNNN/rNN/seismicity)");
  for (const auto& in : inputs) {
    SeismicityRequest one = req;
    one.input = in;
    seismicity_of(one, std::cout);
  }
  return 0;
}

}  // namespace bkq
