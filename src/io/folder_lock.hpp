// The lock of an output folder: while a bkquake command writes a folder it holds the file
// DIR/bkquake.lock (host, pid, command, start time) and an flock() on it, so a second
// command on the same folder refuses with exit 2 naming the holder instead of silently
// writing over the first one's files. The kernel drops the flock when its process dies, even
// by SIGKILL, so a lock left behind is recognisably stale: on the same host it is reported
// and taken over when the caller allows it (--resume continues a killed run, --force starts
// over); a lock written by another host is never taken over (its flock may not reach us).
// While a lock is held, SIGINT, SIGTERM and SIGHUP whose action is the default (outside a
// run's own handlers, app/stop_signals.hpp: opening files, checking a resume) remove the lock
// file before the process ends by that signal, so a signal never leaves a lock behind.
#pragma once

#include <optional>
#include <string>

namespace bkq {

// What the lock file says about its holder.
struct LockHolder {
  std::string host;
  long pid = 0;
  std::string command;  // "run", "merge", ...
  std::string since;    // UTC, ISO 8601
  // "bkquake run (pid 123 on host h, since 2026-11-25T09:00:00Z)"; "an unknown process" when
  // the file could not be parsed.
  std::string describe() const;
};

// What to do with a lock whose holder is gone (same host only).
enum class StaleLock { Refuse, TakeOver };

class FolderLock {
 public:
  static constexpr const char* kFileName = "bkquake.lock";
  // The lock is written to a temporary of this prefix, then linked to kFileName.
  static constexpr const char* kTemporaryPrefix = ".bkquake.lock.tmp-";

  // Takes the lock of the existing folder `dir` for `command`. Throws bkq::Error when another
  // live process holds it, when a stale lock is found and `stale` is Refuse (naming --resume
  // and --force, the options that take one over), when the lock was written on another host,
  // and when the folder cannot be written. A stale lock taken over is reported on stderr.
  FolderLock(const std::string& dir, const std::string& command, StaleLock stale);
  // Removes the lock file (if it is still ours) and drops the flock.
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  const std::string& path() const { return path_; }

 private:
  void held();  // registers the lock for release on a signal, removes stale temporaries
  // Removes the temporaries of lock attempts whose process died (no flock held on them).
  static void remove_stale_temporaries(const std::string& dir);

  std::string path_;
  int fd_ = -1;
};

// Removes every lock this process holds (each only if it is still ours). Async-signal-safe:
// for signal handlers that end the process (app/stop_signals.hpp's second signal).
void release_folder_locks_from_signal() noexcept;

// The holder named by DIR/bkquake.lock, or nullopt when there is no lock file. Never throws
// for a garbled file (its fields stay empty).
std::optional<LockHolder> read_folder_lock(const std::string& dir);

}  // namespace bkq
