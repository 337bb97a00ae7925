// `bkquake spectrum RUN_DIR`: parses the arguments and calls app/spectrum.hpp.
#include <boost/program_options.hpp>
#include <iostream>

#include "app/spectrum.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

namespace po = boost::program_options;

int cmd_spectrum(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake spectrum RUN_DIR [options]\n"
      "Amplitude spectrum (GSL FFT, mean removed, windowed) of a continuous run's signal;\n"
      "writes spectrum.csv and prints the strongest peaks and the natural frequencies");
  // clang-format off
  opts.add_options()
    ("help,h", "show this help")
    ("signal", po::value<std::string>()->default_value("pad_position"),
               "pad_position | pad_velocity | pad_friction | block:J (needs blocks.csv)")
    ("segment", po::value<std::int64_t>(), "the last half of this segment of segments.csv "
                                           "(0-based)")
    ("from", po::value<double>(), "start of the time span (default: the run's start)")
    ("to", po::value<double>(), "end of the time span (default: the run's end)")
    ("window", po::value<std::string>()->default_value("hann"), "hann | rectangular")
    ("peaks", po::value<int>()->default_value(6), "how many peaks to print")
    ("fmin", po::value<double>()->default_value(0.0), "report no peak below this frequency "
                                                      "(slow drift; Ferre 2018 disregards it)")
    ("out", po::value<std::string>(), "output file (default RUN_DIR/spectrum.csv)");
  // clang-format on
  const po::variables_map vm = parse_command_line("spectrum", args, opts, "run_dir", 1);
  if (printed_help(vm, opts)) return 0;
  if (!vm.count("run_dir")) throw Error("spectrum: missing RUN_DIR (see bkquake spectrum --help)");
  SpectrumRequest req;
  req.run_dir = vm["run_dir"].as<std::string>();
  req.signal = vm["signal"].as<std::string>();
  if (vm.count("segment")) req.segment = vm["segment"].as<std::int64_t>();
  if (vm.count("from")) req.from = vm["from"].as<double>();
  if (vm.count("to")) req.to = vm["to"].as<double>();
  if (req.segment && (req.from || req.to))
    throw Error("spectrum: --segment and --from/--to exclude each other");
  const std::string w = vm["window"].as<std::string>();
  if (w != "hann" && w != "rectangular")
    throw Error("spectrum: --window = " + w + ": expected hann or rectangular");
  req.window = w == "hann" ? Window::Hann : Window::Rectangular;
  req.peaks = vm["peaks"].as<int>();
  if (req.peaks < 0)
    throw Error("spectrum: --peaks = " + std::to_string(req.peaks) + ": expected >= 0");
  req.f_min = vm["fmin"].as<double>();
  if (vm.count("out")) req.out = vm["out"].as<std::string>();
  print_spectrum_report(spectrum_of_run(req), std::cout);
  return 0;
}

}  // namespace bkq
