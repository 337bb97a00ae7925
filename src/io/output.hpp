// The output folder of a run and the low-level writers every driver uses: the folder
// itself (created, probed for writing, protected against overwriting a finished run),
// atomic whole-file writes (scene.ini, histogram.csv, summary.json: a reader never sees
// half a file), streamed CSVs (catalog.csv, timeseries.csv: header first, flushed often
// so an unattended run loses little when killed) and the provenance lines of every output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace bkq {

class Scene;
class FolderLock;

class OutputFolder {
 public:
  // Creates `dir` (and its parents), checks it can be written and locks it for `command`
  // (io/folder_lock.hpp) until destroyed. Throws bkq::Error when it cannot, when another
  // process holds the lock (a stale one of this host is taken over with force or resume),
  // and, unless force or resume is set, when the folder already holds files: a finished run
  // (summary.json), an interrupted one (a checkpoint), or any other file, which a new run
  // would write over. With resume the folder must exist, and none of a run's own files
  // (io/run_folder.hpp) in it may be a link or other than a plain file (refuse_link): what
  // the run continues in place it would otherwise write through into another folder.
  OutputFolder(const std::string& dir, bool force, bool resume, const std::string& command = "run");
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  // dir/name.
  std::string path(const std::string& name) const;
  const std::string& dir() const { return dir_; }
  bool resume() const { return resume_; }

 private:
  std::string dir_;
  bool resume_ = false;
  std::unique_ptr<FolderLock> lock_;
};

// Writes `content` to a temporary file in the same folder, fsyncs it and renames it over
// `path`. Throws bkq::Error naming the file and the system's reason.
void write_file_atomic(const std::string& path, const std::string& content);
// The first half of write_file_atomic: writes `content` to a new temporary file beside
// `path` (same folder, so renaming it over `path` is atomic), fsynced and readable;
// returns its name. Throws bkq::Error naming `path`; nothing is left behind on failure.
std::string write_temp_beside(const std::string& path, const std::string& content);
// The temporaries of write_temp_beside are named NAME + kTempMarker + six characters: a
// marker no user's file and no other temporary (the folder lock's, an export's) carries.
inline constexpr const char* kTempMarker = ".bkquake-tmp-";
// Whether a file name is such a temporary.
bool is_write_temporary(const std::string& name);
// Removes the temporaries write_temp_beside left beside `path` when a write was cut short
// (a second signal, a crash), and those of versions that named them NAME.tmp-XXXXXX; best
// effort, errors ignored.
void remove_temporaries_of(const std::string& path);
// A run writes only inside its folder: before a file is written anew (created or truncated,
// not renamed into place), a symbolic link or a hard link to a file elsewhere at `path` is
// removed, so the new file replaces it instead of being written through it. A FIFO or
// socket there is refused (bkq::Error naming it); a device is left as it is and written
// (never removed). Throws bkq::Error naming the file when a link cannot be removed.
void replace_link(const std::string& path);
// Before a file is continued in place (appended to, cut back): bkq::Error naming it when it
// is a symbolic link, a hard link or not a plain file, which continuing would write through.
// `why` starts the message ("--resume", "cannot append to").
void refuse_link(const std::string& path, const std::string& why);
// Renames `from` over `to`; throws bkq::Error naming both.
void rename_file(const std::string& from, const std::string& to);
// fsyncs a folder, so that renames in it survive a power cut.
void sync_folder(const std::string& dir);

// "bkquake 0.1.0 (git abc123)", "seed 20261121", "scene <origin>", "scene hash <hex>",
// "written 2026-11-21T10:54:00Z": the provenance carried by every output.
std::vector<std::string> provenance_lines(const Scene& scene);

// Current UTC time as ISO 8601 ("2026-11-21T10:54:00Z").
std::string utc_now_iso();

// A CSV file written row by row. The header is the first line (no comment lines: readers
// rely on it). Rows are collected in a buffer of the stream's own and written with one
// write per buffer: every `flush_rows` rows (kWhenFull: when the buffer is full), at least
// once a second, and on close. Every write failure throws bkq::Error naming the file.
class CsvStream {
 public:
  static constexpr std::size_t kWhenFull = static_cast<std::size_t>(-1);
  static constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

  // Truncates and writes the header; with `append` keeps existing rows (resume) and writes
  // the header only when the file is new or empty, or throws if its header differs. A link
  // at `path` is replaced (replace_link), or with `append` refused (refuse_link).
  CsvStream(const std::string& path, const std::string& header, bool append = false,
            std::size_t flush_rows = 1000);
  ~CsvStream();  // closes; errors here are lost, so call close() to see them
  CsvStream(const CsvStream&) = delete;
  CsvStream& operator=(const CsvStream&) = delete;

  // Appends one line (no newline in `line`).
  void row(const std::string& line);
  // A row formatted in place: begin_row returns room for `max_bytes` characters in the
  // buffer, end_row takes the end of what was written there (no newline).
  char* begin_row(std::size_t max_bytes);
  void end_row(char* end);
  void flush();
  // Flushes and syncs to disk; returns the file's size, so a checkpoint can record how much
  // of the file belongs to it. Throws on failure.
  std::uint64_t sync();
  // Flushes, syncs to disk and closes; throws on failure. Idempotent.
  void close();

  const std::string& path() const { return path_; }
  std::size_t rows() const { return rows_; }

 private:
  void check(bool ok, const char* what);

  std::string path_;
  std::FILE* file_ = nullptr;
  std::size_t flush_rows_;
  std::size_t rows_ = 0;
  std::size_t unflushed_ = 0;
  std::vector<char> buf_;
  std::size_t used_ = 0;
  std::int64_t last_flush_ns_ = 0;
};

}  // namespace bkq
