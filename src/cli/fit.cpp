// `bkquake fit CATALOG.csv`: parses the arguments and calls app/fit.hpp, which fits the
// Gutenberg-Richter law to the catalogue, prints a short table and, with --json, writes the
// same as JSON.
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
      "bkquake fit CATALOG.csv|CATALOG.h5 [options]\n"
      "Fits R(mu) = A exp(-b mu), mu = ln(moment), to an event catalogue");
  // clang-format off
  opts.add_options()
    ("help,h", "show this help")
    ("mu-min", po::value<std::string>(), "lower end of the fit window, in [-50, 50] (default "
                                         "or auto: automatic, docs/explanation/b-fit.md)")
    ("mu-max", po::value<std::string>(), "upper end of the fit window, in [-50, 50]; truncates "
                                         "the likelihood (default or auto: automatic, below the "
                                         "bump of large events)")
    ("bin-width", po::value<std::string>()->default_value(
                      format_real(MagnitudeHistogram::kDefaultBinWidth)),
                  "magnitude bin width, in (0, 10]")
    ("blocks", po::value<std::string>(), "chain length N for the event classes (default: "
                                         "scene.ini beside the catalogue)")
    ("boundary", po::value<std::string>(), "free | periodic (default: scene.ini, else free)")
    ("json", po::value<std::string>(), "also write the result as JSON to this file");
  // clang-format on
  const po::variables_map vm = parse_command_line("fit", args, opts, "catalog", 1);
  if (printed_help(vm, opts)) return 0;
  if (!vm.count("catalog"))
    throw Error("fit: missing CATALOG.csv or CATALOG.h5 (see bkquake fit --help)");
  // Each option is checked against the scene key it stands for (one declaration each).
  const auto real_option = [&](const char* name, const char* key) -> std::optional<double> {
    if (!vm.count(name)) return std::nullopt;
    const std::string v =
        option_value(std::string("fit: --") + name, key, vm[name].as<std::string>());
    if (v == "auto") return std::nullopt;
    return std::strtod(v.c_str(), nullptr);
  };
  const double w = *real_option("bin-width", "stats.bin_width");
  const std::optional<double> mu_min = real_option("mu-min", "stats.mu_min");
  const std::optional<double> mu_max = real_option("mu-max", "stats.mu_max");
  if (mu_min && mu_max && !(*mu_max > *mu_min))
    throw Error("fit: --mu-max must be greater than --mu-min");

  FitRequest request;
  request.catalog = vm["catalog"].as<std::string>();
  request.bin_width = w;
  request.mu_min = mu_min;
  request.mu_max = mu_max;
  if (vm.count("blocks"))
    request.blocks =
        std::stoi(option_value("fit: --blocks", "model.blocks", vm["blocks"].as<std::string>()));
  if (vm.count("boundary")) request.boundary = vm["boundary"].as<std::string>();
  if (vm.count("json")) request.json = vm["json"].as<std::string>();
  fit_catalog(request, std::cout);
  return 0;
}

}  // namespace bkq
