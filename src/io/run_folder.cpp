// Implementation of the run-folder readers (see run_folder.hpp).
#include "io/run_folder.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/folder_lock.hpp"
#include "io/ini.hpp"
#include "io/json.hpp"
#include "io/scene.hpp"

namespace bkq {

SceneModelInfo read_scene_model(const std::filesystem::path& scene_ini) {
  const std::string where = "in " + scene_ini.string();
  // A default scene normalises and range-checks each value the table's way.
  Scene scene;
  SceneModelInfo info;
  for (const auto& [key, value] : parse_ini(read_text_file(scene_ini.string(), "scene"), where)) {
    if (key == "model.blocks") {
      scene.set(key, value, where);
      info.blocks = static_cast<int>(scene.integer(key));
    } else if (key == "model.rows") {
      scene.set(key, value, where);
      info.rows = static_cast<int>(scene.integer(key));
    } else if (key == "model.boundary") {
      scene.set(key, value, where);
      info.boundary = scene.choice(key);
    } else if (key == "friction.alpha") {
      scene.set(key, value, where);
      info.alpha = scene.text(key);
    }
  }
  return info;
}

Scene read_run_scene(const std::filesystem::path& scene_ini) {
  const std::string where = "in " + scene_ini.string();
  Scene scene;
  scene.origin = scene_ini.string();
  for (const auto& [key, value] : parse_ini(read_text_file(scene_ini.string(), "scene"), where))
    if (find_param(key)) scene.set(key, value, where);
  return scene;
}

const char* status_text(RunStatus status) {
  switch (status) {
    case RunStatus::Finished:
      return "finished";
    case RunStatus::Interrupted:
      return "interrupted";
    case RunStatus::None:
      break;
  }
  return "none";
}

RunStatus run_status(const std::filesystem::path& dir) {
  const std::filesystem::path summary = dir / "summary.json";
  std::error_code ec;
  if (!std::filesystem::exists(summary, ec)) return RunStatus::None;
  const auto s = json_top_level_string(read_text_file(summary.string(), "summary"), kStatusKey,
                                       summary.string());
  if (!s) return RunStatus::Finished;
  for (const RunStatus r : {RunStatus::Finished, RunStatus::Interrupted})
    if (*s == status_text(r)) return r;
  throw Error(summary.string() + ": \"" + kStatusKey + "\" = " + quote_printable(*s) +
              ": expected finished or interrupted");
}

Boundary parse_boundary(const std::string& text) {
  if (text == "free") return Boundary::Free;
  if (text == "periodic") return Boundary::Periodic;
  throw Error("model.boundary: expected free or periodic, got '" + text + "'");
}

std::optional<double> read_json_number(const std::filesystem::path& json, const std::string& key) {
  return json_top_level_number(read_text_file(json.string(), "JSON file"), key, json.string());
}

const std::vector<std::string>& run_own_files() {
  static const std::vector<std::string> names = {
      "scene.ini",           "catalog.csv",          "catalog.h5",         "histogram.csv",
      "summary.json",        "timeseries.csv",       "segments.csv",       "energy.csv",
      "energy_samples.csv",  "blocks.csv",           "event_slip.csv",     "checkpoint.bin",
      "checkpoint.prev.bin", "checkpoint.final.bin", FolderLock::kFileName};
  return names;
}

bool is_run_folder(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  return fs::exists(dir / "scene.ini", ec) &&
         (fs::exists(dir / "summary.json", ec) || fs::exists(dir / "checkpoint.bin", ec) ||
          fs::exists(dir / "checkpoint.prev.bin", ec));
}

DerivedOutput::DerivedOutput(const std::filesystem::path& target,
                             const std::vector<std::filesystem::path>& inputs,
                             const std::string& command)
    : path_(target.string()) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (target.empty()) throw Error(command + ": empty output path");
  if (fs::is_directory(target, ec))
    throw Error(command + ": output '" + path_ + "' is a folder, expected a file name");
  const fs::path canon = fs::weakly_canonical(fs::absolute(target), ec);
  for (const fs::path& in : inputs) {
    const bool same = fs::exists(in, ec) && fs::exists(target, ec)
                          ? fs::equivalent(in, target, ec)
                          : fs::weakly_canonical(fs::absolute(in), ec) == canon;
    if (same)
      throw Error(command + ": output '" + path_ + "' is its input '" + in.string() + "'; " +
                  command + " writes nothing over its inputs: choose another output");
  }
  const fs::path dir = canon.parent_path();
  const std::string name = canon.filename().string();
  if (!is_run_folder(dir)) return;
  for (const std::string& own : run_own_files())
    if (name == own)
      throw Error(command + ": output '" + path_ + "' is the file " + own + " of the run in '" +
                  dir.string() + "'; " + command +
                  " writes nothing over a run's own files: choose another name");
  // A stale lock (a run killed) is taken over, and goes when this output is written.
  lock_ = std::make_unique<FolderLock>(dir.string(), command, StaleLock::TakeOver);
}

DerivedOutput::~DerivedOutput() = default;

}  // namespace bkq
