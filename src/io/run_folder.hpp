// What the statistics need from a run folder besides the histogram and the catalogue:
// the chain length and boundary from scene.ini ([model] blocks, boundary) and a few
// top-level numbers from summary.json (events, blocks, total_load, bin_width). The readers
// are deliberately minimal (the writers live in src/io): INI "key = value" lines under
// "[section]" headers with ';' or '#' comments, and top-level JSON numbers found by key.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace bkq {

struct SceneModelInfo {
  std::optional<int> blocks;            // [model] blocks
  std::optional<std::string> boundary;  // [model] boundary ("free" | "periodic")
  std::optional<std::string> alpha;     // [friction] alpha, for labels
};

// Reads [model] blocks/boundary and [friction] alpha; bkq::Error if the file cannot be
// opened or blocks is not a positive integer.
SceneModelInfo read_scene_model(const std::filesystem::path& scene_ini);

// The number stored under a top-level "key" of a JSON file; nullopt when absent or null.
// bkq::Error if the file cannot be read or the value is not a number.
std::optional<double> read_json_number(const std::filesystem::path& json, const std::string& key);

}  // namespace bkq
