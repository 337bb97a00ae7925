// Implementation of the run-folder readers (see run_folder.hpp).
#include "io/run_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <utility>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/folder_lock.hpp"
#include "io/ini.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
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

bool is_run_own_file(const std::string& name) {
  for (const std::string& own : run_own_files())
    if (name == own) return true;
  const auto ends_with = [&](const std::string& tail) {
    return name.size() >= tail.size() &&
           name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
  };
  return (name.rfind("checkpoint", 0) == 0 && ends_with(".bin")) ||
         name.rfind(FolderLock::kTemporaryPrefix, 0) == 0 || is_write_temporary(name);
}

bool is_run_folder(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  return fs::exists(dir / "scene.ini", ec) &&
         (fs::exists(dir / "summary.json", ec) || fs::exists(dir / "checkpoint.bin", ec) ||
          fs::exists(dir / "checkpoint.prev.bin", ec));
}

bool holds_run_or_lock(const std::filesystem::path& dir) {
  std::error_code ec;
  return is_run_folder(dir) || std::filesystem::exists(dir / FolderLock::kFileName, ec);
}

namespace {

// The locks this process holds through share_folder_lock, by their folder's resolved path.
std::vector<std::pair<std::filesystem::path, std::weak_ptr<FolderLock>>>& shared_locks() {
  static std::vector<std::pair<std::filesystem::path, std::weak_ptr<FolderLock>>> locks;
  return locks;
}

}  // namespace

std::shared_ptr<FolderLock> share_folder_lock(const std::filesystem::path& dir,
                                              const std::string& command, StaleLock stale) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path key = fs::weakly_canonical(fs::absolute(dir), ec);
  if (ec) key = fs::absolute(dir).lexically_normal();
  auto& locks = shared_locks();
  std::erase_if(locks, [](const auto& held) { return held.second.expired(); });
  for (const auto& [folder, lock] : locks)
    if (folder == key)
      if (auto held = lock.lock()) return held;
  auto lock = std::make_shared<FolderLock>(dir.string(), command, stale);
  locks.emplace_back(key, lock);
  return lock;
}

std::optional<LockHolder> live_lock_holder(const std::filesystem::path& dir) {
  const std::string path = (dir / FolderLock::kFileName).string();
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  // A shared flock is refused while the holder keeps its exclusive one; it is dropped at once.
  const bool held = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  if (!held) ::flock(fd, LOCK_UN);
  ::close(fd);
  if (!held) return std::nullopt;
  const auto holder = read_folder_lock(dir.string());
  if (holder && holder->pid == ::getpid()) return std::nullopt;
  return holder ? holder : LockHolder{};
}

std::shared_ptr<FolderLock> lock_derived_folder_parent(const std::filesystem::path& dir,
                                                       const std::string& command) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path abs = fs::absolute(dir).lexically_normal();
  if (!abs.has_filename()) abs = abs.parent_path();  // DIR/
  const fs::path parent = fs::weakly_canonical(abs.parent_path(), ec);
  const std::string name = abs.filename().string();
  if (!holds_run_or_lock(parent)) return nullptr;
  if (is_run_own_file(name))
    throw Error(command + ": output folder '" + dir.string() + "' takes the name of the file " +
                escape_unprintable(name) + " of the run in '" + parent.string() + "'; " + command +
                " writes nothing over a run's own files: choose another folder");
  return share_folder_lock(parent, command, StaleLock::TakeOver);
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
  if (!target.has_filename()) throw Error(command + ": output '" + path_ + "' names no file");
  // The folder through its links, the name as given: a link there is replaced, not followed.
  const auto resolve = [&](const fs::path& p) {
    const fs::path abs = fs::absolute(p);
    return fs::weakly_canonical(abs.parent_path(), ec) / abs.filename();
  };
  resolved_ = resolve(target);
  const bool target_is_link = fs::is_symlink(target, ec);
  for (const fs::path& in : inputs) {
    // The same name, or (the target being no link) the same file under another name.
    const bool same =
        resolve(in) == resolved_ || (!target_is_link && fs::exists(in, ec) &&
                                     fs::exists(target, ec) && fs::equivalent(in, target, ec));
    if (same)
      throw Error(command + ": output '" + path_ + "' is its input '" + in.string() + "'; " +
                  command + " writes nothing over its inputs: choose another output");
  }
  const fs::path dir = resolved_.parent_path();
  const std::string name = resolved_.filename().string();
  if (!holds_run_or_lock(dir)) return;
  if (is_run_own_file(name))
    throw Error(command + ": output '" + path_ + "' is the file " + escape_unprintable(name) +
                " of the run in '" + dir.string() + "'; " + command +
                " writes nothing over a run's own files: choose another name");
  // A live run's lock refuses this output; a stale lock (a run killed) is taken over, and
  // goes when this output is written. Under the lock, the temporaries of an earlier write
  // of this output cut short by a kill are stale: they go.
  lock_ = share_folder_lock(dir, command, StaleLock::TakeOver);
  remove_temporaries_of(resolved_.string());
}

DerivedOutput::~DerivedOutput() = default;

}  // namespace bkq
