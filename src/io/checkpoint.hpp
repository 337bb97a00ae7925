// Checkpoints of event-driven runs: everything a run needs to continue, after a signal, a
// crash or a power cut, with exactly the catalog.csv and histogram.csv it would have
// written without stopping (`bkquake run SCENE --out DIR --resume`).
//
// Contents: the program version (a checkpoint from another version is refused) and git
// revision, the effective scene (its hash, checked on resume, and its text, so a refusal
// can name the keys that differ), the seed, the engine snapshot (chain state and counters,
// EngineSnapshot), the histogram's complete state, and the run's own bookkeeping
// (RunProgress: events done, size of catalog.csv at the checkpoint, load at the start of
// the recorded events, moment sum, wall time). No random numbers are drawn after the
// initial state (initial_state.hpp), so there is no generator state to keep; the seed is
// recorded for provenance only.
//
// File format (version 1), all integers little-endian, doubles as their IEEE-754 bits
// (so every value round-trips exactly):
//   8 bytes   magic "BKQCKPT\n"
//   u32       format version
//   u64       payload length P
//   P bytes   payload: the fields of Checkpoint in declaration order; strings and arrays
//             are a u64 length followed by their bytes / elements
//   u64       FNV-1a 64 of everything before it (any single changed byte is detected)
// A file of any other length, magic, version or checksum is refused by decode_checkpoint.
//
// Files: DIR/checkpoint.bin, the newest, and DIR/checkpoint.prev.bin, the one before.
// A new checkpoint is written to a temporary file and fsynced, then checkpoint.bin is
// renamed to checkpoint.prev.bin and the temporary file to checkpoint.bin, then the folder
// is fsynced. Renames are atomic, so a crash at any instant leaves checkpoint.bin intact,
// or (between the two renames) checkpoint.prev.bin, which CheckpointFiles::read falls back to.
#pragma once

#include <cstdint>
#include <string>

#include "engine/event_engine.hpp"
#include "stats/histogram.hpp"

namespace bkq {

class Scene;

// Where an event run stands, besides the engine and the histogram.
struct RunProgress {
  std::int64_t transient_done = 0;  // transient (discarded) events done
  std::int64_t events_done = 0;     // recorded events done; also the rows of catalog.csv
  std::uint64_t catalog_bytes = 0;  // size of catalog.csv holding exactly those rows
  double load0 = 0;                 // substrate displacement when recording started
  EngineCounters counters0;         // engine counters when recording started
  double moment_sum = 0;            // sum of the recorded moments
  std::int64_t nonpositive = 0;     // recorded events with moment <= 0 (not in the histogram)
  double wall_events = 0;           // wall seconds spent on recorded events, all sessions
  double wall_total = 0;            // wall seconds of the whole run, all sessions
  std::int64_t resumes = 0;         // how often the run was continued from a checkpoint
};

struct Checkpoint {
  std::string version;       // kVersion of the program that wrote it
  std::string git_revision;  // kGitRevision of that program
  std::uint64_t scene_hash = 0;
  std::string scene_ini;  // Scene::to_ini() of the effective scene
  std::uint64_t seed = 0;
  RunProgress progress;
  EngineSnapshot engine;
  MagnitudeHistogram::State histogram;
};

std::string encode_checkpoint(const Checkpoint& c);
// Throws bkq::Error naming `origin` when `bytes` are not one complete, intact checkpoint
// of this format version (wrong magic, truncated, trailing bytes, checksum mismatch).
Checkpoint decode_checkpoint(const std::string& bytes, const std::string& origin);

// Throws bkq::Error when the checkpoint was written by another bkquake version or for
// another scene, naming the versions or the keys whose values differ.
void check_checkpoint_matches(const Checkpoint& c, const Scene& scene, const std::string& origin);

// Throws bkq::Error unless the first `bytes` bytes of the CSV file `path` are the line
// `header` followed by exactly `rows` complete lines; only reads the file.
void check_csv_prefix(const std::string& path, const std::string& header, std::int64_t rows,
                      std::uint64_t bytes);

// The checkpoint files of one output folder.
class CheckpointFiles {
 public:
  explicit CheckpointFiles(std::string dir);
  std::string current() const;   // DIR/checkpoint.bin
  std::string previous() const;  // DIR/checkpoint.prev.bin
  bool exist() const;            // either of them
  // Writes `c` as the new checkpoint.bin, keeping the old one as checkpoint.prev.bin.
  // Throws bkq::Error naming the file; the existing checkpoints stay intact on failure.
  void write(const Checkpoint& c) const;
  // The newest checkpoint and the file it came from: checkpoint.bin, or checkpoint.prev.bin
  // when a crash came between the renames. Throws bkq::Error when there is none or when
  // checkpoint.bin is damaged (then naming checkpoint.prev.bin, if there is one).
  Checkpoint read(std::string* from = nullptr) const;
  // Deletes both checkpoints and any temporary file left by an interrupted write.
  void remove() const;

 private:
  std::string dir_;
};

}  // namespace bkq
