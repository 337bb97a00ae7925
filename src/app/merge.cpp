// Implementation of `bkquake merge` (see merge.hpp).
#include "app/merge.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <ostream>
#include <sstream>
#include <string_view>

#include "app/gr_report.hpp"
#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/histogram_csv.hpp"
#include "io/ini.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"
#include "io/scene_keys.hpp"
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
  return key == key::run_initial_disorder.name || key == key::stats_bin_width.name;
}

// A merged folder's scene.ini records the seeds of every run merged into it on this
// provenance line ("# merged seeds 11 12"), so that merging it again with another run can
// still refuse a seed that repeats.
constexpr std::string_view kMergedSeeds = "# merged seeds ";

// The inputs as merge sees them: each one's effective scene (scene.ini) and the seeds of the
// runs it holds (a run: its run.seed; a merged folder: the seeds recorded in its scene.ini).
struct Inputs {
  std::vector<Scene> scenes;
  std::vector<std::vector<std::string>> seeds;
};

// A run's scene.ini must be the scene its summary.json was written for: a key missing from
// an empty or truncated scene.ini would take its default and pass for the run's physics.
// The summary's scene_hash (Scene::hash over every key) is compared with the scene read
// back; a run of another revision (whose keys may differ) is compared too, and the message
// names both revisions. Merged folders, whose summary has no scene_hash, are compared by
// their keys alone (check_alike).
void check_scene_matches_summary(const std::string& run, const fs::path& ini, const Scene& scene) {
  const fs::path summary = fs::path(run) / "summary.json";
  const std::string text = read_text_file(summary.string(), "summary");
  const auto recorded = json_top_level_string(text, "scene_hash", summary.string());
  if (!recorded) return;
  if (*recorded == std::to_string(scene.hash())) return;
  const auto revision = json_top_level_string(text, "git_revision", summary.string());
  std::string why = "damaged, truncated or edited";
  if (revision && *revision != kGitRevision)
    why += ", or written by git revision " + quote_printable(*revision) + " whose scene keys " +
           "differ from this one's (" + kGitRevision + ")";
  throw Error("merge: " + ini.string() + " is not the scene of " + summary.string() +
              " (scene_hash " + quote_printable(*recorded) + ", the file reads as " +
              std::to_string(scene.hash()) + "): " + why);
}

// Reads every input's scene and seeds; refuses an input that is not a finished run.
Inputs read_inputs(const std::vector<std::string>& runs) {
  Inputs in;
  for (const auto& run : runs) {
    std::error_code ec;
    if (!fs::exists(run, ec))
      throw Error("merge: " + run + ": no such folder; expected a finished run's folder");
    if (!fs::is_directory(run, ec))
      throw Error("merge: " + run + " is not a folder; expected a finished run's folder");
    const RunStatus status = run_status(run);
    if (status == RunStatus::None)
      throw Error("merge: " + run + " has no summary.json: it is not a finished run");
    if (status == RunStatus::Interrupted)
      throw Error("merge: " + run +
                  " is an interrupted run (summary.json: \"status\": \"interrupted\"); finish "
                  "it first with bkquake run " +
                  (fs::path(run) / "scene.ini").string() + " --out " + run + " --resume");
    const fs::path ini = fs::path(run) / "scene.ini";
    if (!fs::exists(ini))
      throw Error("merge: " + run +
                  " has no scene.ini, so it cannot be checked to be a run of the same scene");
    in.scenes.push_back(read_run_scene(ini));
    check_scene_matches_summary(run, ini, in.scenes.back());
    std::vector<std::string> seeds;
    std::istringstream text(read_text_file(ini.string(), "scene"));
    for (std::string line; std::getline(text, line);)
      if (line.rfind(kMergedSeeds, 0) == 0) {
        std::istringstream list(line.substr(kMergedSeeds.size()));
        for (std::string seed; list >> seed;) seeds.push_back(seed);
      }
    if (seeds.empty()) seeds.push_back(in.scenes.back().text(key::run_seed));
    in.seeds.push_back(std::move(seeds));
  }
  return in;
}

// Refuses runs that are not alike (naming every differing key) and a run given twice or
// merged with a copy of itself (the same seed: the same events), also inside merged inputs.
void check_alike(const std::vector<std::string>& runs, const Inputs& in) {
  const std::vector<Scene>& scenes = in.scenes;
  for (std::size_t i = 1; i < scenes.size(); ++i) {
    std::string diff;
    for (const auto& p : parameter_table())
      if (must_match(p.key) && scenes[i].text(p.key) != scenes[0].text(p.key))
        diff += (diff.empty() ? "" : ", ") + p.key + " = " + scenes[i].text(p.key) + " (not " +
                scenes[0].text(p.key) + ")";
    if (!diff.empty())
      throw Error("merge: " + runs[i] + " is a run of another scene than " + runs[0] + ": " + diff);
  }
  for (std::size_t i = 0; i < runs.size(); ++i)
    for (std::size_t j = 0; j <= i; ++j)
      for (std::size_t a = 0; a < in.seeds[i].size(); ++a)
        for (std::size_t b = 0; b < (j == i ? a : in.seeds[j].size()); ++b)
          if (in.seeds[i][a] == in.seeds[j][b])
            throw Error("merge: " + runs[i] + (j == i ? " holds two runs" : " and " + runs[j]) +
                        " with the same run.seed = " + in.seeds[i][a] +
                        ", so the same events: merging them would count those events twice");
}

// The merged folder's scene.ini: the first input's effective scene (its physics is every
// input's), headed by the merge's provenance and the seeds of every run merged (no paths:
// those are in summary.json's merged_from, and a sweep's folders compare without them).
std::string merged_scene_ini(const std::vector<std::string>& runs, const Inputs& in) {
  std::string seeds;
  for (const auto& list : in.seeds)
    for (const auto& seed : list) seeds += (seeds.empty() ? "" : " ") + seed;
  const std::vector<std::string> header = {
      std::string("bkquake ") + kVersion + " (git " + kGitRevision + ")",
      "merge of " + std::to_string(runs.size()) + " runs (summary.json: merged_from)",
      std::string(kMergedSeeds.substr(2)) + seeds,
      "the scene of the first run: its physics, stats.bin_width and run.initial_disorder are",
      "every merged run's; run.seed and the run's length are the first run's",
      "written " + utc_now_iso()};
  return in.scenes[0].to_ini(header);
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
  const Inputs inputs = read_inputs(runs);
  check_alike(runs, inputs);
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
  write_file_atomic(folder.path("scene.ini"), merged_scene_ini(runs, inputs));
  write_file_atomic(folder.path("histogram.csv"), histogram_csv(*merged));
  Json s = Json::object();
  s.set(kStatusKey, status_text(RunStatus::Finished))
      .set("events", merged->events())
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
          .set("b_mle_sys_err", fit_number(fit.b_mle_sys_err))
          .set("b_mw", fit_number(b_moment_magnitude(fit.b_mle)))
          .set("b_mw_err", fit_number(b_moment_magnitude(fit.b_mle_err)))
          .set("mu_min", fit_number(fit.mu_min))
          .set("mu_max", fit_number(fit.mu_max))
          .set("fit", gr_fit_json(fit));
      out << where << "\n" << gr_fit_table(fit);
    } catch (const Error& e) {
      s.set("fit_error", e.what());
      out << where << "; no fit: " << e.what() << "\n";
    }
  } else {
    s.set("fit_error", kTooFewToFit);
    out << where << "; " << kTooFewToFit << ", no fit\n";
  }
  write_file_atomic(folder.path("summary.json"), s.str() + "\n");
}

}  // namespace bkq
