// Output folder, atomic file writes, streamed CSVs and provenance (see output.hpp).
#include "io/output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/terminal_text.hpp"
#include "io/checkpoint.hpp"
#include "io/folder_lock.hpp"
#include "io/friction_table.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"
#include "io/scene_keys.hpp"
#include "io/scene_values.hpp"

namespace bkq {

namespace fs = std::filesystem;

namespace {

std::string reason(int err) {
  return std::strerror(err);
}

// Writes all of `data` to `fd`, retrying on short writes and EINTR; returns errno or 0.
int write_all(int fd, const std::string& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    done += static_cast<std::size_t>(n);
  }
  return 0;
}

// The name of the write probe's file where the file system has no unnamed files.
constexpr const char* kProbePrefix = ".bkquake-probe-";

std::string folder_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

}  // namespace

OutputFolder::OutputFolder(const std::string& dir, bool force, bool resume,
                           const std::string& command)
    : dir_(dir), resume_(resume) {
  if (dir.empty()) throw Error("output folder: empty path");
  std::error_code ec;
  if (fs::is_symlink(dir, ec) && !fs::exists(dir, ec)) {
    // A link as the folder is followed (docs/explanation/reliability.md), but one to nothing
    // is not made into a folder at the place it names.
    const fs::path target = fs::read_symlink(dir, ec);
    throw Error("cannot use output folder '" + dir + "': it is a symbolic link to '" +
                target.string() +
                "', which does not exist; create that folder, or choose another --out");
  }
  if (resume && !fs::exists(dir, ec))
    throw Error("--resume: output folder '" + dir + "' does not exist: nothing to continue");
  fs::create_directories(dir, ec);
  if (ec) throw Error("cannot create output folder '" + dir + "': " + ec.message());
  if (!fs::is_directory(dir, ec))
    throw Error("cannot use output folder '" + dir + "': " + reason(ENOTDIR));
  // Locked before anything is looked at, so what is checked below stays true.
  lock_ = std::make_unique<FolderLock>(dir, command,
                                       force || resume ? StaleLock::TakeOver : StaleLock::Refuse);
  // What a killed process left here: the named probe of a file system without unnamed files
  // (below), always; the temporaries of writes it cut short (write_temp_beside), when a run
  // takes the folder over (--resume, --force), since the files themselves are whole, old or
  // new. A new run refuses those as files it did not write (below).
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kProbePrefix, 0) == 0 || ((force || resume) && is_write_temporary(name)))
      stale.push_back(entry.path());
  }
  for (const fs::path& f : stale) fs::remove(f, ec);
  // Probe with a real file: permissions, read-only mounts and full disks all show up here,
  // before hours of simulation rather than after. An unnamed file (O_TMPFILE) leaves nothing
  // behind whenever the process dies; where the file system has none, a named one is made
  // and removed at once.
  int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
  if (fd < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)) {
    std::string probe = path(std::string(kProbePrefix) + "XXXXXX");
    fd = ::mkstemp(probe.data());
    if (fd >= 0) ::unlink(probe.c_str());
  }
  if (fd < 0) throw Error("cannot write to output folder '" + dir + "': " + reason(errno));
  ::close(fd);
  // Checked before anything is changed: a resume continues these files in place.
  if (resume)
    for (const std::string& name : run_own_files())
      if (name != FolderLock::kFileName) refuse_link(path(name), "--resume");
  if (force || resume) return;
  const bool can_resume = command == "run";
  if (run_status(dir) == RunStatus::Finished)
    throw Error(
        "output folder '" + dir + "' already holds a finished run (summary.json); use " +
        (can_resume ? "--force to overwrite or --resume to continue" : "--force to overwrite it"));
  const CheckpointFiles checkpoints(dir);
  if (checkpoints.exist())
    throw Error(
        "output folder '" + dir + "' holds an interrupted run (" +
        (fs::exists(checkpoints.current(), ec) ? checkpoints.current() : checkpoints.previous()) +
        "); use " +
        (can_resume ? "--resume to continue it or --force to start over"
                    : "--force to write over it"));
  // Any other file would be written over by a file of the same name, or would be mistaken
  // for part of this run: a new run starts in a new or empty folder. Hidden files (the
  // lock's and the atomic writes' temporaries, a file manager's) do not count.
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.' || name == FolderLock::kFileName || entry.is_directory(ec))
      continue;
    found.push_back(name);
  }
  if (!found.empty()) {
    std::sort(found.begin(), found.end());
    std::string names;
    for (std::size_t i = 0; i < found.size() && i < 3; ++i)
      names += (i ? ", " : "") + quote_text(found[i]);
    if (found.size() > 3) names += ", ... (" + std::to_string(found.size()) + " files)";
    throw Error("output folder '" + dir + "' already holds files bkquake did not write in this " +
                command + " (" + names +
                "); choose a new or empty folder, or use --force to write over them");
  }
}

OutputFolder::~OutputFolder() = default;

std::string OutputFolder::path(const std::string& name) const {
  return (fs::path(dir_) / name).string();
}

std::string write_temp_beside(const std::string& path, const std::string& content) {
  std::string tmp =
      (fs::path(folder_of(path)) / (fs::path(path).filename().string() + kTempMarker + "XXXXXX"))
          .string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw Error("cannot write '" + path + "': " + reason(errno));
  int err = write_all(fd, content);
  if (!err && ::fsync(fd) != 0) err = errno;
  // mkstemp creates 0600; outputs are ordinary files, readable like any other.
  if (!err && ::fchmod(fd, 0644) != 0) err = errno;
  if (::close(fd) != 0 && !err) err = errno;
  if (err) {
    ::unlink(tmp.c_str());
    throw Error("cannot write '" + path + "': " + reason(err));
  }
  return tmp;
}

bool is_write_temporary(const std::string& name) {
  const std::string marker = kTempMarker;
  const auto at = name.rfind(marker);
  const auto tail = at + marker.size();
  return at != std::string::npos && at > 0 && name.size() == tail + 6 &&
         std::all_of(name.begin() + static_cast<std::ptrdiff_t>(tail), name.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; });
}

void remove_temporaries_of(const std::string& path) {
  std::error_code ec;
  const std::string name = fs::path(path).filename().string();
  const std::string stem = name + kTempMarker, old_stem = name + ".tmp-";
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(folder_of(path), ec)) {
    const std::string f = entry.path().filename().string();
    if (f.rfind(stem, 0) == 0 || f.rfind(old_stem, 0) == 0) stale.push_back(entry.path());
  }
  for (const auto& f : stale) fs::remove(f, ec);
}

namespace {

// What stands at `path` when it is not one plain file of its own: "a symbolic link to 'x'",
// "a hard link (N names)", "a FIFO", ...; empty for a plain file or nothing.
std::string link_kind(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  if (S_ISLNK(st.st_mode)) {
    std::error_code ec;
    return "a symbolic link to '" + fs::read_symlink(path, ec).string() + "'";
  }
  if (S_ISDIR(st.st_mode)) return "";  // opening it fails with its own message
  if (!S_ISREG(st.st_mode))
    return S_ISFIFO(st.st_mode) ? "a FIFO" : S_ISSOCK(st.st_mode) ? "a socket" : "a device";
  if (st.st_nlink > 1) return "a file with " + std::to_string(st.st_nlink) + " names (hard links)";
  return "";
}

}  // namespace

void replace_link(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return;
  // Only a name that leads elsewhere is removed. A FIFO or socket is refused (opening one
  // would wait, or fail), and a device is written as it stands: neither is ever deleted
  // (a run started as root must not remove /dev/full).
  if (S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode))
    throw Error("cannot write '" + path + "': it is " + link_kind(path) +
                ", not a file; a run writes plain files: remove it, or choose another --out");
  const bool elsewhere = S_ISLNK(st.st_mode) || (S_ISREG(st.st_mode) && st.st_nlink > 1);
  if (!elsewhere) return;
  if (::unlink(path.c_str()) != 0 && errno != ENOENT)
    throw Error("cannot replace '" + path + "' (" + link_kind(path) + "): " + reason(errno));
}

void refuse_link(const std::string& path, const std::string& why) {
  const std::string kind = link_kind(path);
  if (kind.empty()) return;
  throw Error(why + ": '" + path + "' is " + kind +
              "; a run writes only inside its folder, and continuing it would write through "
              "that: put the file itself in its place, or start over with --force");
}

void rename_file(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0)
    throw Error("cannot rename '" + from + "' to '" + to + "': " + reason(errno));
}

void write_file_atomic(const std::string& path, const std::string& content) {
  const std::string tmp = write_temp_beside(path, content);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw Error("cannot write '" + path + "': " + reason(err));
  }
}

void sync_folder(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) throw Error("cannot open folder '" + dir + "': " + reason(errno));
  // Some file systems cannot sync a folder (EINVAL); their renames are as durable as they get.
  const int err = ::fsync(fd) != 0 && errno != EINVAL ? errno : 0;
  ::close(fd);
  if (err) throw Error("cannot sync folder '" + dir + "': " + reason(err));
}

std::string utc_now_iso() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::vector<std::string> provenance_lines(const Scene& scene) {
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(scene.hash()));
  std::vector<std::string> lines = {
      std::string("bkquake ") + kVersion + " (git " + kGitRevision + ")",
      "seed " + scene.text(key::run_seed),
      "scene " + scene.provenance(),
      std::string("scene hash ") + hash,
  };
  // The table law's file by its contents too (the scene holds only its path).
  const LawChoice given = scene_values(scene).friction.law;
  if (!given.rsf && given.law == law_id<law::Table>)
    lines.push_back("friction table " + scene.text(key::friction_table) + " fnv1a64 " +
                    file_checksum(scene.text(key::friction_table)));
  lines.push_back("written " + utc_now_iso());
  return lines;
}

namespace {

// A coarse monotonic clock (a few ms of resolution, a few ns to read): enough for the
// once-a-second flush, read once per row.
std::int64_t coarse_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC_COARSE, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

CsvStream::CsvStream(const std::string& path, const std::string& header, bool append,
                     std::size_t flush_rows)
    : path_(path), flush_rows_(flush_rows == 0 ? 1 : flush_rows), buf_(kBufferBytes) {
  bool need_header = true;
  if (append)
    refuse_link(path, "cannot append");
  else
    replace_link(path);
  if (append) {
    std::ifstream in(path);
    std::string first;
    if (in && std::getline(in, first)) {
      if (first != header)
        throw Error("cannot append to '" + path + "': its header '" + first +
                    "' differs from the expected '" + header + "'");
      need_header = false;
    }
  }
  // O_NOFOLLOW: a link put here since the check above is refused, never written through.
  const int fd =
      ::open(path.c_str(),
             O_WRONLY | O_CREAT | O_CLOEXEC | O_NOFOLLOW | (append ? O_APPEND : O_TRUNC), 0644);
  if (fd < 0) throw Error("cannot open '" + path + "' for writing: " + reason(errno));
  file_ = ::fdopen(fd, append ? "ab" : "wb");
  if (!file_) {
    const int err = errno;
    ::close(fd);
    throw Error("cannot open '" + path + "' for writing: " + reason(err));
  }
  // The stream's own buffer is the only one: each flush is one write.
  std::setvbuf(file_, nullptr, _IONBF, 0);
  if (need_header) {
    const std::string line = header + "\n";
    check(std::fwrite(line.data(), 1, line.size(), file_) == line.size(), "write");
  }
  last_flush_ns_ = coarse_ns();
}

CsvStream::~CsvStream() {
  if (!file_) return;
  if (used_ > 0) std::fwrite(buf_.data(), 1, used_, file_);
  std::fclose(file_);
}

void CsvStream::check(bool ok, const char* what) {
  if (ok && file_ && !std::ferror(file_)) return;
  const int err = errno;
  if (file_) {
    std::fclose(file_);
    file_ = nullptr;
  }
  throw Error(std::string("cannot ") + what + " '" + path_ + "': " + reason(err));
}

char* CsvStream::begin_row(std::size_t max_bytes) {
  if (!file_) throw Error("cannot write '" + path_ + "': the file is closed");
  if (buf_.size() - used_ < max_bytes + 1) {
    flush();
    if (buf_.size() < max_bytes + 1) buf_.resize(max_bytes + 1);
  }
  return buf_.data() + used_;
}

void CsvStream::end_row(char* end) {
  *end++ = '\n';
  used_ = static_cast<std::size_t>(end - buf_.data());
  ++rows_;
  ++unflushed_;
  // Bounds what a kill loses to about a second of rows.
  if (unflushed_ >= flush_rows_ || coarse_ns() - last_flush_ns_ >= 1'000'000'000) flush();
}

void CsvStream::row(const std::string& line) {
  char* out = begin_row(line.size());
  end_row(std::char_traits<char>::copy(out, line.data(), line.size()) + line.size());
}

void CsvStream::flush() {
  if (!file_) return;
  if (used_ > 0) check(std::fwrite(buf_.data(), 1, used_, file_) == used_, "write");
  used_ = 0;
  check(std::fflush(file_) == 0, "write");
  unflushed_ = 0;
  last_flush_ns_ = coarse_ns();
}

std::uint64_t CsvStream::sync() {
  if (!file_) throw Error("cannot sync '" + path_ + "': the file is closed");
  flush();
  check(::fsync(::fileno(file_)) == 0 || errno == EINVAL, "sync");
  struct stat st {};
  check(::fstat(::fileno(file_), &st) == 0, "stat");
  return static_cast<std::uint64_t>(st.st_size);
}

void CsvStream::close() {
  if (!file_) return;
  flush();
  check(::fsync(::fileno(file_)) == 0 || errno == EINVAL, "sync");
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) throw Error("cannot close '" + path_ + "': " + reason(errno));
}

}  // namespace bkq
