// `bkquake fit CATALOG.csv`: parses the arguments and calls app/fit.hpp, which fits the
// Gutenberg-Richter law to the catalogue, prints a short table and, with --json, writes the
// same as JSON.
#include <boost/program_options.hpp>
#include <iostream>
#include <optional>

#include "app/fit.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

namespace po = boost::program_options;

int cmd_fit(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake fit CATALOG.csv|CATALOG.h5 [options]\n"
      "Fits R(mu) = A exp(-b mu), mu = ln(moment), to an event catalogue");
  // clang-format off
  opts.add_options()
    ("help,h", "show this help")
    ("mu-min", po::value<double>(), "lower end of the fit window (default: chosen by the "
                                    "Kolmogorov-Smirnov scan of Clauset et al. 2009)")
    ("mu-max", po::value<double>(), "upper end of the fit window; truncates the likelihood "
                                    "(default: the largest populated bin, untruncated)")
    ("bin-width", po::value<double>()->default_value(MagnitudeHistogram::kDefaultBinWidth),
                  "magnitude bin width, > 0")
    ("blocks", po::value<int>(), "chain length N for the event classes (default: scene.ini "
                                 "beside the catalogue)")
    ("boundary", po::value<std::string>(), "free | periodic (default: scene.ini, else free)")
    ("json", po::value<std::string>(), "also write the result as JSON to this file");
  // clang-format on
  const po::variables_map vm = parse_command_line("fit", args, opts, "catalog", 1);
  if (vm.count("help")) {
    std::cout << opts << "\n";
    return 0;
  }
  if (!vm.count("catalog"))
    throw Error("fit: missing CATALOG.csv or CATALOG.h5 (see bkquake fit --help)");
  const double w = vm["bin-width"].as<double>();
  if (!(w > 0)) throw Error("fit: --bin-width: expected a value > 0, got " + std::to_string(w));
  std::optional<double> mu_min, mu_max;
  if (vm.count("mu-min")) mu_min = vm["mu-min"].as<double>();
  if (vm.count("mu-max")) mu_max = vm["mu-max"].as<double>();
  if (mu_min && mu_max && !(*mu_max > *mu_min))
    throw Error("fit: --mu-max must be greater than --mu-min");

  FitRequest request;
  request.catalog = vm["catalog"].as<std::string>();
  request.bin_width = w;
  request.mu_min = mu_min;
  request.mu_max = mu_max;
  if (vm.count("blocks")) {
    request.blocks = vm["blocks"].as<int>();
    if (*request.blocks < 1)
      throw Error("fit: --blocks: expected a positive integer, got " +
                  std::to_string(*request.blocks));
  }
  if (vm.count("boundary")) request.boundary = vm["boundary"].as<std::string>();
  if (vm.count("json")) request.json = vm["json"].as<std::string>();
  fit_catalog(request, std::cout);
  return 0;
}

}  // namespace bkq
