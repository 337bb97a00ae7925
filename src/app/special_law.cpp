// The tabulated special friction law; see special_law.hpp.
#include "app/special_law.hpp"

#include <algorithm>
#include <filesystem>
#include <map>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/scene.hpp"
#include "io/segments_csv.hpp"
#include "io/settings.hpp"

namespace bkq {

std::vector<LawPoint> special_law(const std::vector<std::string>& run_dirs) {
  namespace fs = std::filesystem;
  if (run_dirs.empty()) throw Error("special-law: give at least one BK run folder");
  std::map<double, std::pair<double, int>> sums;  // speed -> (sum of friction, count)
  for (const auto& dir : run_dirs) {
    const fs::path scene_file = fs::path(dir) / "scene.ini";
    if (!fs::exists(scene_file))
      throw Error("special-law: " + dir + " is not a run folder (no scene.ini)");
    const Scene scene = Scene::from_file(scene_file.string());
    const SceneValues v = scene_values(scene);
    if (v.drive.mode != DriveMode::Continuous || v.model.kind != ModelChoice::Bk)
      throw Error("special-law: " + dir + " is a " + scene.text(key::model_kind) + " run in " +
                  scene.text(key::drive_mode) +
                  " mode; the special law needs continuous runs of model.kind = bk");
    const ModelParams p = model_from_scene(scene);
    for (const SegmentRow& r : read_segments_csv(fs::path(dir) / "segments.csv")) {
      auto& [sum, count] = sums[r.speed];
      sum += -r.stats[0].mean / (p.n * p.m_u);
      ++count;
    }
  }
  std::vector<LawPoint> law;
  for (const auto& [speed, sc] : sums) law.push_back({speed, sc.first / sc.second, sc.second});
  return law;
}

std::string special_law_csv(const std::vector<LawPoint>& law,
                            const std::vector<std::string>& comments) {
  std::string out;
  for (const auto& c : comments) out += "# " + c + "\n";
  out += header_of(special_law_schema()) + "\n";
  for (const LawPoint& p : law) out += format_real(p.speed) + "," + format_real(p.friction) + "\n";
  return out;
}

}  // namespace bkq
