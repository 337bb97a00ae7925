// `bkquake fit`: reads an event catalogue, fits the Gutenberg-Richter law (binned and
// unbinned maximum likelihood, least squares, KS window, two power laws, large-event
// excess; stats/gutenberg_richter.hpp) and counts the event classes. The chain length and
// boundary for the classes come from the request, else from scene.ini beside the catalogue.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "stats/histogram.hpp"

namespace bkq {

struct FitRequest {
  std::filesystem::path catalog;
  double bin_width = MagnitudeHistogram::kDefaultBinWidth;  // > 0
  std::optional<double> mu_min, mu_max;                     // the fit window, else automatic
  std::optional<int> blocks;                                // N for the event classes
  std::optional<std::string> boundary;                      // "free" | "periodic"
  std::optional<std::filesystem::path> json;                // also write the result here
};

// Prints the fit table (and the class counts) to `out` and writes the JSON when asked.
// User errors throw bkq::Error.
void fit_catalog(const FitRequest& request, std::ostream& out);

}  // namespace bkq
