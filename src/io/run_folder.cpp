// Implementation of the run-folder readers (see run_folder.hpp).
#include "io/run_folder.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
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

}  // namespace bkq
