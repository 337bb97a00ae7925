// Implementation of `bkquake merge` (see merge.hpp).
#include "app/merge.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <ostream>

#include "app/gr_report.hpp"
#include "core/error.hpp"
#include "io/histogram_csv.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {

namespace fs = std::filesystem;

namespace {

// The keys two runs must share to be merged: the physics and the histogram's bins. Not the
// seed, the run's length, checkpoints, outputs or the fit window.
bool must_match(const std::string& key) {
  for (const char* section : {"model.", "friction.", "drive.", "integrator."})
    if (key.rfind(section, 0) == 0) return true;
  return key == "run.initial_disorder" || key == "stats.bin_width";
}

// Refuses runs that are not alike (naming every differing key) and a run given twice or
// merged with a copy of itself (the same seed: the same events).
void check_alike(const std::vector<std::string>& runs) {
  std::vector<Scene> scenes;
  for (const auto& run : runs) {
    const fs::path ini = fs::path(run) / "scene.ini";
    if (!fs::exists(ini))
      throw Error("merge: " + run +
                  " has no scene.ini, so it cannot be checked to be a run of the same scene");
    scenes.push_back(read_run_scene(ini));
  }
  for (std::size_t i = 1; i < scenes.size(); ++i) {
    std::string diff;
    for (const auto& p : parameter_table())
      if (must_match(p.key) && scenes[i].text(p.key) != scenes[0].text(p.key))
        diff += (diff.empty() ? "" : ", ") + p.key + " = " + scenes[i].text(p.key) + " (not " +
                scenes[0].text(p.key) + ")";
    if (!diff.empty())
      throw Error("merge: " + runs[i] + " is a run of another scene than " + runs[0] + ": " + diff);
    for (std::size_t j = 0; j < i; ++j)
      if (scenes[i].text("run.seed") == scenes[j].text("run.seed"))
        throw Error("merge: " + runs[i] + " and " + runs[j] +
                    " have the same run.seed = " + scenes[i].text("run.seed") +
                    ", so the same events: merging them would count those events twice");
  }
}

double required(const fs::path& summary, const std::string& key) {
  const auto v = read_json_number(summary, key);
  if (!v) throw Error(summary.string() + ": missing \"" + key + "\"");
  return *v;
}
}  // namespace

void merge_runs(const MergeRequest& request, std::ostream& out) {
  const auto& runs = request.runs;
  // Merge writes nothing into its inputs: the output may be neither one of them nor inside one.
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(fs::absolute(request.out), ec);
  for (const auto& run : runs) {
    const fs::path input = fs::weakly_canonical(fs::absolute(run), ec);
    const auto [in_end, t_end] =
        std::mismatch(input.begin(), input.end(), target.begin(), target.end());
    if (in_end == input.end())
      throw Error("merge: --out " + request.out.string() +
                  (t_end == target.end() ? " is the input " : " lies inside the input ") + run +
                  "; merge writes nothing into its inputs: choose another --out");
  }
  check_alike(runs);
  std::optional<MagnitudeHistogram> merged;
  for (const auto& run : runs) {
    const fs::path dir = run;
    const fs::path summary = dir / "summary.json";
    const double w = required(summary, "bin_width");
    const double blocks = required(summary, "blocks");
    const double load = required(summary, "total_load");
    if (!(blocks >= 1) || blocks != static_cast<double>(static_cast<int>(blocks)))
      throw Error(summary.string() + ": \"blocks\": expected a positive integer");
    MagnitudeHistogram h =
        read_histogram_csv(dir / "histogram.csv", load, static_cast<int>(blocks), w);
    if (const auto ev = read_json_number(summary, "events");
        ev && *ev != static_cast<double>(h.events()))
      throw Error(dir.string() + ": histogram.csv holds " + std::to_string(h.events()) +
                  " events, summary.json says " + std::to_string(static_cast<std::int64_t>(*ev)));
    if (!merged) {
      merged = std::move(h);
      continue;
    }
    if (merged->bin_width() != h.bin_width())
      throw Error("merge: " + run + " has bin width " + std::to_string(h.bin_width()) +
                  ", the first run " + std::to_string(merged->bin_width()));
    if (merged->blocks() != h.blocks())
      throw Error("merge: " + run + " has N = " + std::to_string(h.blocks()) +
                  ", the first run N = " + std::to_string(merged->blocks()));
    merged->merge(h);
  }
  if (!merged) throw Error("merge: no RUN_DIR given");

  const OutputFolder folder(request.out.string(), request.force, false, "merge");
  write_file_atomic(folder.path("histogram.csv"), histogram_csv(*merged));
  Json s = Json::object();
  s.set("events", merged->events())
      .set("blocks", static_cast<std::int64_t>(merged->blocks()))
      .set("total_load", fit_number(merged->total_load()))
      .set("bin_width", fit_number(merged->bin_width()))
      .set("merged_from", Json::strings(runs));
  const std::string where =
      "merged " + std::to_string(runs.size()) + " runs into " + request.out.string();
  if (merged->events() >= 2) {
    // A window that holds no fit is a result, not a failure: it is named in fit_error.
    try {
      const GrFit fit = fit_histogram(*merged, request.mu_min, request.mu_max);
      s.set("b_mle", fit_number(fit.b_mle))
          .set("b_mle_err", fit_number(fit.b_mle_err))
          .set("mu_min", fit_number(fit.mu_min))
          .set("mu_max", fit_number(fit.mu_max))
          .set("fit", gr_fit_json(fit));
      out << where << "\n" << gr_fit_table(fit);
    } catch (const Error& e) {
      s.set("fit_error", e.what());
      out << where << "; no fit: " << e.what() << "\n";
    }
  } else {
    out << where << "; fewer than 2 events, no fit\n";
  }
  write_file_atomic(folder.path("summary.json"), s.str() + "\n");
}

}  // namespace bkq
