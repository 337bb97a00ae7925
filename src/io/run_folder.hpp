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

#include "io/folder_lock.hpp"
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

// Whether `name` is a file a run owns in its folder: one of run_own_files(), any
// checkpoint*.bin, or a temporary of the lock or of an atomic write.
bool is_run_own_file(const std::string& name);

// Whether `dir` holds a run (scene.ini with summary.json or a checkpoint beside it).
bool is_run_folder(const std::filesystem::path& dir);

// Whether `dir` holds a run or is being written by one: a run folder, or a folder holding
// the lock file (a run locks its folder before it writes anything else in it).
bool holds_run_or_lock(const std::filesystem::path& dir);

// The lock of `dir` for this process: the one it already holds on that folder (a command
// writing two outputs into one folder, fit --scan --json) or a new one (FolderLock's
// rules). The lock goes when its last holder does.
std::shared_ptr<FolderLock> share_folder_lock(const std::filesystem::path& dir,
                                              const std::string& command, StaleLock stale);

// The holder of DIR/bkquake.lock when another live process holds it (its flock is taken),
// else nullopt: no lock file, a stale one, or this process's own. Takes nothing.
std::optional<LockHolder> live_lock_holder(const std::filesystem::path& dir);

// The folder rule for a folder of derived outputs (fit --scan --out DIR, seismicity --out
// DIR) that lies in a folder holding a run or a run's lock: DIR may not take the name of one
// of the run's files (a folder named checkpoint.bin or bkquake.lock would break the run),
// and the run's folder is locked as for a derived output. Returns that lock, or null where
// DIR lies in no such folder; bkq::Error as DerivedOutput.
std::shared_ptr<FolderLock> lock_derived_folder_parent(const std::filesystem::path& dir,
                                                       const std::string& command);

// The folder rule for a derived output: a file that a command writes from what it read
// (spectrum.csv, fit --json, a plot), possibly into an existing run folder. The output's
// folder is resolved through links; a link at its own name is replaced by the output, never
// written through. Refuses, with bkq::Error naming both, a target that is one of the
// command's `inputs` (or a link to one) or, in a folder that holds a run or a run's lock
// (holds_run_or_lock), one of the run's own files (is_run_own_file); in such a folder it
// takes the folder's lock (io/folder_lock.hpp, a stale one taken over) for `command` while
// alive, so it never writes beside a live run, and replaces only its own earlier version
// (whose temporaries, left by a kill, it removes).
// (A command that writes a whole folder uses OutputFolder, io/output.hpp: new or empty
// folder, --force, the lock.)
class DerivedOutput {
 public:
  DerivedOutput(const std::filesystem::path& target,
                const std::vector<std::filesystem::path>& inputs, const std::string& command);
  ~DerivedOutput();
  DerivedOutput(const DerivedOutput&) = delete;
  DerivedOutput& operator=(const DerivedOutput&) = delete;
  const std::string& path() const { return path_; }
  // The path written: the target's folder resolved through links, then its name.
  const std::filesystem::path& resolved() const { return resolved_; }

 private:
  std::string path_;
  std::filesystem::path resolved_;
  std::shared_ptr<FolderLock> lock_;
};

}  // namespace bkq
