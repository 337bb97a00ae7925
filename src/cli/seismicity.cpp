// `bkquake seismicity RUN_DIR|CATALOG`: parses the arguments and calls app/seismicity.hpp
// for the run folder, each point of a sweep folder, or the catalogue file.
#include <cmath>
#include <iostream>
#include <sstream>

#include "app/seismicity.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/readme_tables.hpp"
#include "io/seismicity_csv.hpp"

namespace bkq {

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

// The statistics' own thresholds, as --interevent-mu would give them.
std::string default_interevent_mu() {
  std::string text;
  for (const double mu : seis::SeismicityOptions().interevent_mu) {
    if (!text.empty()) text += ',';
    text += format_real(mu);
  }
  return text;
}

int cmd_seismicity(const Args& args) {
  // Hidden: the docs page's column tables (docs/explanation/seismicity.md), with their
  // markers, from the schemas; tests/regression/test_seismicity.cpp checks the page.
  if (args.has("doc-tables")) {
    for (const auto& [name, schema] : seismicity_schemas())
      std::cout << readme_begin_marker(name) << "\n"
                << column_table(*schema) << readme_end_marker(name) << "\n\n";
    return 0;
  }
  if (args.operands().empty())
    throw Error("seismicity: missing RUN_DIR or CATALOG (see bkquake seismicity --help)");
  SeismicityRequest req;
  req.input = args.operands().front();
  if (args.has("out")) req.out = args.text("out");
  if (args.has("mainshock-mu")) {
    req.mainshock_mu = args.real("mainshock-mu");
    if (!std::isfinite(*req.mainshock_mu)) throw Error("seismicity: --mainshock-mu must be finite");
  }
  if (args.has("blocks")) {
    req.blocks = args.integer("blocks");
    if (*req.blocks < 1)
      throw Error("seismicity: --blocks = " + std::to_string(*req.blocks) +
                  ": expected at least 1");
  }
  if (args.has("b-mu-min")) req.b_mu_min = args.real("b-mu-min");
  if (args.has("interevent-mu")) req.interevent_mu = parse_list(args.text("interevent-mu"));
  if (args.has("export")) req.export_file = args.text("export");
  req.mw_offset = args.real("mw-offset");
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

}  // namespace

Command seismicity_command_row() {
  return {"seismicity",
          "waiting times, aftershocks, Båth's law, moment rate, rupture scaling",
          "RUN_DIR|SWEEP_DIR|CATALOG",
          1,
          "Seismicity statistics of an event catalogue (waiting times, recurrence, Omori-Utsu\n"
          "aftershocks and foreshocks, Båth's law, moment rate, rupture scaling, the Mogi\n"
          "picture); writes RUN_DIR/seismicity/ (interevent.csv, recurrence.csv, omori.csv,\n"
          "moment_rate.csv, scaling.csv, spacetime.csv, seismicity.json).\n",
          {opt::text("out", "DIR",
                     "output folder (default: RUN_DIR/seismicity, or seismicity/ beside the "
                     "catalogue)"),
           opt::real("mainshock-mu", "X",
                     "mainshocks (and the large events whose recurrence is measured) are events "
                     "with mu >= X (default: events spanning more than half the chain)"),
           opt::integer("blocks", "N",
                        "chain length N when no scene.ini is beside the catalogue (default: "
                        "scene.ini's model.blocks, else max(last_block) + 1)"),
           opt::real("b-mu-min", "MU",
                     "lower magnitude of the b-values before mainshocks (default: the lower end of "
                     "the fit window in the summary.json beside the catalogue, else maximum "
                     "curvature)"),
           opt::text("interevent-mu", "LIST",
                     "comma-separated magnitude thresholds of the waiting-time subsets (default: " +
                         default_interevent_mu() + ")"),
           opt::text("export", "FILE",
                     "also write the catalogue as FILE in seismology's conventions (time, Mw, x "
                     "along strike)"),
           opt::real("mw-offset", "C", "C of Mw = (2/3) log10 M + C in the export", "0"),
           opt::flag("doc-tables", "print the docs page's column tables").hidden()},
          cmd_seismicity};
}

}  // namespace bkq
