// `bkquake merge`: merges the magnitude histograms of several runs of the same scene exactly
// (counts add; loading adds) and writes histogram.csv and summary.json, with the
// Gutenberg-Richter fit of the merged histogram, and scene.ini (the first run's scene, with
// the seeds of every run merged), into an output folder, which therefore merges again. Runs
// of different scenes (the physics and the bins, compared in their scene.ini), the same run
// twice (the same seed, also inside a merged input) and interrupted runs are refused;
// nothing is written into an input folder.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace bkq {

struct MergeRequest {
  std::vector<std::string> runs;  // finished run or merged folders (summary.json, histogram.csv,
                                  // scene.ini)
  std::filesystem::path out;      // created if missing; neither an input nor inside one
  bool force = false;             // write into an output folder that already holds files
  std::optional<double> mu_min = std::nullopt;  // the fit window, else automatic
  std::optional<double> mu_max = std::nullopt;
};

// Prints a line (and the fit table) to `out`. User errors throw bkq::Error.
void merge_runs(const MergeRequest& request, std::ostream& out);

}  // namespace bkq
