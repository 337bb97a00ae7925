// What the statistics need from a run folder besides the histogram and the catalogue: the
// chain length and boundary from scene.ini and a few top-level numbers from summary.json
// (events, blocks, total_load, bin_width). scene.ini is parsed by the one INI parser
// (io/ini.hpp) and its values checked against the one parameter table (io/scene.hpp); only
// the keys needed here are read, so the scene of a run finished by an older (or newer)
// bkquake, with keys since added or removed, still reads.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/scene.hpp"
#include "model/parameters.hpp"

namespace bkq {

struct SceneModelInfo {
  std::optional<int> blocks;            // [model] blocks
  std::optional<int> rows;              // [model] rows (a lattice's, when above 1)
  std::optional<std::string> boundary;  // [model] boundary ("free" | "periodic")
  std::optional<std::string> alpha;     // [friction] alpha, for labels
};

// summary.json's "status": how the run it describes ended. "finished": the run is complete
// (its checkpoints are gone); "interrupted": it was stopped by SIGINT/SIGTERM, its figures are
// those reached so far and a checkpoint beside it continues it with --resume. The one
// declaration of the field, for its writers (app/observers/summary, app/merge) and readers
// (run --resume, a new run's folder check, sweep --resume, merge, fit).
enum class RunStatus { None, Finished, Interrupted };
inline constexpr const char* kStatusKey = "status";
// "finished", "interrupted" (None: "none").
const char* status_text(RunStatus status);
// The status of the run folder `dir`: None without summary.json; a summary without "status"
// (written before the field existed, when only a finished run wrote one) is Finished.
// bkq::Error if summary.json cannot be read or its status is not one of the above.
RunStatus run_status(const std::filesystem::path& dir);

// Reads [model] blocks/boundary and [friction] alpha; bkq::Error if the file cannot be
// read or a value is outside the parameter table's range.
SceneModelInfo read_scene_model(const std::filesystem::path& scene_ini);

// The effective scene of a finished run from its scene.ini: every key this bkquake knows,
// checked against the parameter table; keys it does not know (removed since) are skipped,
// keys the file lacks (added since) keep their defaults. bkq::Error if the file cannot be
// read or a known value is outside its range.
Scene read_run_scene(const std::filesystem::path& scene_ini);

// "free" | "periodic" (the values of model.boundary); bkq::Error otherwise.
Boundary parse_boundary(const std::string& text);

// The number stored under a top-level "key" of a JSON file; nullopt when absent or null.
// bkq::Error if the file cannot be read or the value is not a number.
std::optional<double> read_json_number(const std::filesystem::path& json, const std::string& key);

// The files a run writes into its folder (its own files): no other command writes over them.
const std::vector<std::string>& run_own_files();

// Whether `dir` holds a run (scene.ini with summary.json or a checkpoint beside it).
bool is_run_folder(const std::filesystem::path& dir);

class FolderLock;

// The folder rule for a derived output: a file that a command writes from what it read
// (spectrum.csv, fit --json, a plot), possibly into an existing run folder. Refuses, with
// bkq::Error naming both, a target that is one of the command's `inputs` or one of a run's
// own files (run_own_files() in a run folder); in a run folder it takes that folder's lock
// (io/folder_lock.hpp) for `command` while alive, so it never writes beside a live run, and
// replaces only its own earlier version. (A command that writes a whole folder uses
// OutputFolder, io/output.hpp: new or empty folder, --force, the lock.)
class DerivedOutput {
 public:
  DerivedOutput(const std::filesystem::path& target,
                const std::vector<std::filesystem::path>& inputs, const std::string& command);
  ~DerivedOutput();
  DerivedOutput(const DerivedOutput&) = delete;
  DerivedOutput& operator=(const DerivedOutput&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::unique_ptr<FolderLock> lock_;
};

}  // namespace bkq
