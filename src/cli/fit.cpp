// `bkquake fit CATALOG|HISTOGRAM|RUN_DIR|MERGED_DIR|SWEEP_DIR`: parses the arguments and
// calls app/fit.hpp, which fits the Gutenberg-Richter law, prints a short table and, with
// --json, writes the same as JSON; --scan writes b_scan.csv; a sweep folder gets
// sweep_fit.csv.
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>

#include "app/fit.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace {

int cmd_fit(const Args& args) {
  if (args.operands().empty())
    throw Error("fit: missing CATALOG, histogram.csv or a folder (see bkquake fit --help)");
  // Each option is checked against the scene key it stands for (one declaration each).
  const auto real_option = [&](const char* name, const char* key) -> std::optional<double> {
    if (!args.has(name)) return std::nullopt;
    const std::string v = option_value(std::string("fit: --") + name, key, args.text(name));
    if (v == "auto") return std::nullopt;
    return std::strtod(v.c_str(), nullptr);
  };
  const double w = *real_option("bin-width", "stats.bin_width");
  const std::optional<double> mu_min = window_option(args, "mu-min", "stats.mu_min");
  const std::optional<double> mu_max = window_option(args, "mu-max", "stats.mu_max");
  if (mu_min && mu_max && !(*mu_max > *mu_min))
    throw Error("fit: --mu-max must be greater than --mu-min");

  FitRequest request;
  request.catalog = args.operands().front();
  request.bin_width = w;
  request.bin_width_given = args.given("bin-width");
  request.mu_min = mu_min;
  request.mu_max = mu_max;
  if (args.has("blocks")) {
    // N, or NXxNY: each part checked as the scene key it stands for.
    const std::string text = args.text("blocks");
    const auto x = text.find('x');
    request.blocks = std::stoi(option_value("fit: --blocks", "model.blocks", text.substr(0, x)));
    if (x != std::string::npos)
      request.rows = std::stoi(option_value("fit: --blocks", "model.rows", text.substr(x + 1)));
  }
  if (args.has("boundary")) request.boundary = args.text("boundary");
  if (args.has("json")) request.json = args.text("json");
  request.scan = args.has("scan");
  request.measure = args.text("measure");
  if (request.measure != "moment" && request.measure != "blocks" &&
      request.measure != "topplings" && request.measure != "area" && request.measure != "duration")
    throw Error("fit: --measure: expected one of moment, blocks, topplings, area, duration, got '" +
                request.measure + "'");
  if (args.has("out")) request.out = args.text("out");
  fit_catalog(request, std::cout);
  return 0;
}

}  // namespace

Command fit_command_row() {
  return {
      "fit",
      "fit the Gutenberg-Richter law to a catalogue, histogram or run folder",
      "CATALOG.csv|CATALOG.h5|histogram.csv|RUN_DIR|MERGED_DIR|SWEEP_DIR",
      1,
      "Fits R(mu) = A exp(-b mu), mu = ln(moment), to anything that holds events; b is per\n"
      "unit of mu, b_mw = 1.5 b per unit of moment magnitude Mw = (2/3) log10 M + const.\n",
      {opt::text("mu-min", "MU",
                 "lower end of the fit window, in [-50, 50], or auto (default: auto, by b-value "
                 "stability)"),
       opt::text("mu-max", "MU",
                 "upper end of the fit window, in [-50, 50], or auto; truncates the likelihood "
                 "(default: auto, where the events above depart from the power law)"),
       opt::text("bin-width", "W",
                 "magnitude bin width, in (0, 10]; a histogram.csv keeps its own bins",
                 format_real(MagnitudeHistogram::kDefaultBinWidth)),
       opt::text("blocks", "N|NXxNY",
                 "chain length N for the event classes, or a lattice's shape NXxNY (columns x "
                 "rows) (default: scene.ini beside the catalogue)"),
       opt::text("boundary", "free|periodic", "the chain's ends (default: scene.ini, else free)"),
       opt::text("json", "FILE", "also write the result as JSON to this file"),
       opt::flag("scan",
                 "also write b_scan.csv: b on every window, and the windows of its systematic "
                 "error (into the folder fitted, or --out)"),
       opt::text("out", "DIR", "folder for b_scan.csv (default: the folder fitted)"),
       opt::text("measure", "moment|blocks|topplings|area|duration",
                 "size measure: moment is the b of mu = ln moment; the others fit a catalogue's "
                 "sizes by a power law x^-tau as well (Clauset et al. 2009)",
                 "moment")},
      cmd_fit};
}

}  // namespace bkq
