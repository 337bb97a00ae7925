// `bkquake spectrum RUN_DIR`: parses the arguments and calls app/spectrum.hpp.
#include <iostream>

#include "app/spectrum.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"

namespace bkq {

namespace {

int cmd_spectrum(const Args& args) {
  if (args.operands().empty())
    throw Error("spectrum: missing RUN_DIR (see bkquake spectrum --help)");
  SpectrumRequest req;
  req.run_dir = args.operands().front();
  req.signal = args.text("signal");
  if (args.has("segment")) req.segment = args.integer64("segment");
  if (args.has("from")) req.from = args.real("from");
  if (args.has("to")) req.to = args.real("to");
  if (req.segment && (req.from || req.to))
    throw Error("spectrum: --segment and --from/--to exclude each other");
  const std::string w = args.text("window");
  if (w != "hann" && w != "rectangular")
    throw Error("spectrum: --window = " + w + ": expected hann or rectangular");
  req.window = w == "hann" ? Window::Hann : Window::Rectangular;
  req.peaks = args.integer("peaks");
  if (req.peaks < 0)
    throw Error("spectrum: --peaks = " + std::to_string(req.peaks) + ": expected >= 0");
  req.f_min = args.real("fmin");
  if (args.has("out")) req.out = args.text("out");
  print_spectrum_report(spectrum_of_run(req), std::cout);
  return 0;
}

}  // namespace

Command spectrum_command_row() {
  return {
      "spectrum",
      "amplitude spectrum of a continuous run's signal and its peaks",
      "RUN_DIR",
      1,
      "Amplitude spectrum (GSL FFT, mean removed, windowed) of a continuous run's signal;\n"
      "writes spectrum.csv and prints the strongest peaks and the natural frequencies\n"
      "(Ferre 2018 §4.3).\n",
      {opt::text("signal", "pad_position|pad_velocity|pad_friction|block:J",
                 "the signal; block:J needs blocks.csv", "pad_position"),
       opt::integer64(
           "segment", "K",
           "the last half of this segment of segments.csv (0-based; not with --from/--to)"),
       opt::real("from", "T0", "start of the time span (default: the run's start)"),
       opt::real("to", "T1", "end of the time span (default: the run's end)"),
       opt::text("window", "hann|rectangular", "the window", "hann"),
       opt::integer("peaks", "P", "how many peaks to print", "6"),
       opt::real("fmin", "F",
                 "report no peak below this frequency (slow drift; Ferre 2018 disregards it)", "0"),
       opt::text("out", "FILE", "output file (default: RUN_DIR/spectrum.csv)")},
      cmd_spectrum};
}

}  // namespace bkq
