// `bkquake fit CATALOG|HISTOGRAM|RUN_DIR|MERGED_DIR|SWEEP_DIR`: parses the arguments and
// calls app/fit.hpp, which fits the Gutenberg-Richter law, prints a short table and, with
// --json, writes the same as JSON; --scan writes b_scan.csv; a sweep folder gets
// sweep_fit.csv.
#include <boost/program_options.hpp>
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

namespace po = boost::program_options;

int cmd_fit(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake fit CATALOG.csv|CATALOG.h5|histogram.csv|RUN_DIR|MERGED_DIR|SWEEP_DIR [options]\n"
      "Fits R(mu) = A exp(-b mu), mu = ln(moment), to anything that holds events; b is per\n"
      "unit of mu, b_mw = 1.5 b per unit of moment magnitude Mw = (2/3) log10 M + const");
  // clang-format off
  opts.add_options()
    ("help,h", "show this help")
    ("mu-min", po::value<std::string>(), "lower end of the fit window, in [-50, 50] (default "
                                         "or auto: automatic, by b-value stability)")
    ("mu-max", po::value<std::string>(), "upper end of the fit window, in [-50, 50]; truncates "
                                         "the likelihood (default or auto: automatic, where the "
                                         "events above depart from the power law)")
    ("bin-width", po::value<std::string>()->default_value(
                      format_real(MagnitudeHistogram::kDefaultBinWidth)),
                  "magnitude bin width, in (0, 10]")
    ("blocks", po::value<std::string>(), "chain length N for the event classes, or a "
                                         "lattice's shape NXxNY (columns x rows) (default: "
                                         "scene.ini beside the catalogue)")
    ("boundary", po::value<std::string>(), "free | periodic (default: scene.ini, else free)")
    ("json", po::value<std::string>(), "also write the result as JSON to this file")
    ("scan", "also write b_scan.csv: b on every window, and the windows of its systematic "
             "error (into the folder fitted, or --out)")
    ("out", po::value<std::string>(), "folder for b_scan.csv (default: the folder fitted)")
    ("measure", po::value<std::string>()->default_value("moment"),
                "size measure: moment (the b of mu = ln moment) | blocks | topplings | area | "
                "duration (a catalogue's sizes also fitted by a power law x^-tau: Clauset et "
                "al. 2009)");
  // clang-format on
  const po::variables_map vm = parse_command_line("fit", args, opts, "catalog", 1);
  if (printed_help(vm, opts)) return 0;
  if (!vm.count("catalog"))
    throw Error("fit: missing CATALOG, histogram.csv or a folder (see bkquake fit --help)");
  // Each option is checked against the scene key it stands for (one declaration each).
  const auto real_option = [&](const char* name, const char* key) -> std::optional<double> {
    if (!vm.count(name)) return std::nullopt;
    const std::string v =
        option_value(std::string("fit: --") + name, key, vm[name].as<std::string>());
    if (v == "auto") return std::nullopt;
    return std::strtod(v.c_str(), nullptr);
  };
  const double w = *real_option("bin-width", "stats.bin_width");
  const std::optional<double> mu_min = window_option(vm, "fit", "mu-min", "stats.mu_min");
  const std::optional<double> mu_max = window_option(vm, "fit", "mu-max", "stats.mu_max");
  if (mu_min && mu_max && !(*mu_max > *mu_min))
    throw Error("fit: --mu-max must be greater than --mu-min");

  FitRequest request;
  request.catalog = vm["catalog"].as<std::string>();
  request.bin_width = w;
  request.bin_width_given = !vm["bin-width"].defaulted();
  request.mu_min = mu_min;
  request.mu_max = mu_max;
  if (vm.count("blocks")) {
    // N, or NXxNY: each part checked as the scene key it stands for.
    const std::string text = vm["blocks"].as<std::string>();
    const auto x = text.find('x');
    request.blocks = std::stoi(option_value("fit: --blocks", "model.blocks", text.substr(0, x)));
    if (x != std::string::npos)
      request.rows = std::stoi(option_value("fit: --blocks", "model.rows", text.substr(x + 1)));
  }
  if (vm.count("boundary")) request.boundary = vm["boundary"].as<std::string>();
  if (vm.count("json")) request.json = vm["json"].as<std::string>();
  request.scan = vm.count("scan") > 0;
  request.measure = vm["measure"].as<std::string>();
  if (request.measure != "moment" && request.measure != "blocks" &&
      request.measure != "topplings" && request.measure != "area" && request.measure != "duration")
    throw Error("fit: --measure: expected one of moment, blocks, topplings, area, duration, got '" +
                request.measure + "'");
  if (vm.count("out")) request.out = vm["out"].as<std::string>();
  fit_catalog(request, std::cout);
  return 0;
}

}  // namespace bkq
