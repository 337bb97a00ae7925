// `bkquake fit`: fits the Gutenberg-Richter law (binned and unbinned maximum likelihood,
// least squares, the automatic window with b's systematic error, two power laws,
// large-event excess; stats/gutenberg_richter.hpp) to whatever holds events:
//   - a catalogue (catalog.csv or catalog.h5), or a folder holding one (a run, a sweep
//     replica): every estimate, and the event classes (N and boundary from the request,
//     else scene.ini beside the catalogue);
//   - a histogram.csv, or a folder holding one and no catalogue (a merged folder, a sweep
//     point): the binned estimates only. A histogram cannot give the unbinned (Aki) b, the
//     event classes or another bin width: it holds the counts of its own bins only;
//   - a sweep folder (sweep.ini and sweep.csv): each point's merged histogram refitted on
//     the request's window, written to sweep_fit.csv beside sweep.csv.
// With a measure other than moment, a catalogue's sizes are also fitted by a power law
// (tau, printed and in the JSON's "tau"). With `scan`, b_scan.csv (io/b_scan_csv.hpp) goes into the
// folder fitted (or `out`). Files written into a folder are written under its lock
// (io/folder_lock.hpp) and replace only their own earlier versions.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "stats/histogram.hpp"

namespace bkq {

struct FitRequest {
  std::filesystem::path catalog;  // the input: a catalogue, histogram.csv or a folder
  double bin_width = MagnitudeHistogram::kDefaultBinWidth;  // > 0
  bool bin_width_given = false;               // a histogram's own width must then agree
  std::optional<double> mu_min, mu_max;       // the fit window, else automatic
  std::optional<int> blocks;                  // N for the event classes
  std::optional<int> rows;                    // a lattice's rows (with blocks: its shape)
  std::optional<std::string> boundary;        // "free" | "periodic"
  std::optional<std::filesystem::path> json;  // also write the result here
  bool scan = false;                          // write b_scan.csv
  std::optional<std::filesystem::path> out;   // folder for b_scan.csv (default: the input's)
  // The size measure: "moment" (the Gutenberg-Richter b of mu = ln moment), or "blocks",
  // "topplings", "area", "duration" (a power law p(x) ~ x^-tau, stats/power_law.hpp; a
  // catalogue only).
  std::string measure = "moment";
  // The power law's range [x_min, x_max] for such a measure, else chosen from the data
  // (x_min by the KS distance, x_max below a gap or a rise); Python's fit() only.
  std::optional<double> x_min, x_max;
};

// Prints the fit table (and the class counts) to `out` and writes the JSON, b_scan.csv or
// sweep_fit.csv when asked. User errors throw bkq::Error.
void fit_catalog(const FitRequest& request, std::ostream& out);

}  // namespace bkq
