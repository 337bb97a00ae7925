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
// File format (version 2), all integers little-endian, doubles as their IEEE-754 bits
// (so every value round-trips exactly):
//   8 bytes   magic "BKQCKPT\n"
//   u32       format version
//   u64       payload length P
//   P bytes   payload: the fields of Checkpoint in declaration order; strings and arrays
//             are a u64 length followed by their bytes / elements. Version 2 ends the
//             payload with the observers' named states (a count, then name and bytes of
//             each); version 1 files lack them and are still read.
//   u64       FNV-1a 64 of everything before it (any single changed byte is detected)
// A file of any other length, magic, version or checksum is refused by decode_checkpoint.
//
// Files: DIR/checkpoint.bin, the newest, and DIR/checkpoint.prev.bin, the one before.
// A new checkpoint is written to a temporary file and fsynced, then checkpoint.bin is
// renamed to checkpoint.prev.bin and the temporary file to checkpoint.bin, then the folder
// is fsynced. Renames are atomic, so a crash at any instant leaves checkpoint.bin intact,
// or (between the two renames) checkpoint.prev.bin, which CheckpointFiles::read falls back to.
#pragma once

#include <bit>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/fnv1a.hpp"
#include "engine/event_engine.hpp"
#include "engine/ofc.hpp"
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

// The state of a run observer that keeps it outside the fixed fields above: its name and
// the bytes it wrote with a StateWriter. A new observer with state needs no format change.
struct ObserverState {
  std::string name;
  std::string bytes;
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
  std::vector<ObserverState> observers;

  // A run's checkpoint with its provenance filled in: this program's version and revision,
  // the scene (hash and effective text), the seed and the progress; the engine's state and
  // the observers' are the caller's to add.
  static Checkpoint of_run(std::uint64_t scene_hash, std::string scene_ini, std::uint64_t seed,
                           const RunProgress& progress);

  // Sets (or replaces) the named observer state; find returns nullptr when there is none
  // (a checkpoint from before the observer existed).
  void put(const std::string& name, std::string bytes);
  const std::string* find(const std::string& name) const;
};

// Little-endian integers and IEEE-754 bit patterns of doubles, so every value round-trips
// exactly: the checkpoint's own encoding, and the one observers use for their state.
class StateWriter {
 public:
  void u64(std::uint64_t v) { little_endian(v); }
  void u32(std::uint32_t v) { little_endian(v); }
  void i64(std::int64_t v) { u64(static_cast<std::uint64_t>(v)); }
  void i128(__int128 v) {
    u64(static_cast<std::uint64_t>(v));
    u64(static_cast<std::uint64_t>(static_cast<unsigned __int128>(v) >> 64));
  }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void str(const std::string& s) {
    u64(s.size());
    out_ += s;
  }
  void f64s(const std::vector<double>& v) {
    u64(v.size());
    for (double x : v) f64(x);
  }
  void i64s(const std::vector<std::int64_t>& v) {
    u64(v.size());
    for (std::int64_t x : v) i64(x);
  }
  std::string& bytes() { return out_; }

 private:
  template <class U>
  void little_endian(U v) {
    for (std::size_t b = 0; b < sizeof(U); ++b) out_.push_back(static_cast<char>(v >> (8 * b)));
  }
  std::string out_;
};

// Reads what a StateWriter wrote, from bytes [begin, end) of `bytes`; a field running past
// the end throws bkq::Error naming `origin`. `bytes` must outlive the reader.
class StateReader {
 public:
  StateReader(const std::string& bytes, std::size_t begin, std::size_t end, std::string origin)
      : b_(bytes), pos_(begin), end_(end), origin_(std::move(origin)) {}
  StateReader(const std::string& bytes, std::string origin)
      : StateReader(bytes, 0, bytes.size(), std::move(origin)) {}
  std::uint64_t u64() { return little_endian<std::uint64_t>(); }
  std::uint32_t u32() { return little_endian<std::uint32_t>(); }
  std::int64_t i64() { return static_cast<std::int64_t>(u64()); }
  __int128 i128() {
    const std::uint64_t lo = u64();
    const std::uint64_t hi = u64();
    return static_cast<__int128>((static_cast<unsigned __int128>(hi) << 64) | lo);
  }
  double f64() { return std::bit_cast<double>(u64()); }
  std::string str() {
    const std::size_t n = count(1);
    std::string s = b_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::vector<double> f64s() {
    std::vector<double> v(count(8));
    for (double& x : v) x = f64();
    return v;
  }
  std::vector<std::int64_t> i64s() {
    std::vector<std::int64_t> v(count(8));
    for (std::int64_t& x : v) x = i64();
    return v;
  }
  // A length prefix, checked against what is left so a bad one cannot allocate wildly.
  std::size_t count(std::size_t element_bytes) {
    const std::uint64_t n = u64();
    if (n > (end_ - pos_) / element_bytes) fail();
    return static_cast<std::size_t>(n);
  }
  bool done() const { return pos_ == end_; }

 private:
  template <class U>
  U little_endian() {
    if (end_ - pos_ < sizeof(U)) fail();
    U v = 0;
    for (std::size_t b = 0; b < sizeof(U); ++b)
      v |= static_cast<U>(static_cast<unsigned char>(b_[pos_ + b])) << (8 * b);
    pos_ += sizeof(U);
    return v;
  }
  [[noreturn]] void fail() const;

  const std::string& b_;
  std::size_t pos_, end_;
  std::string origin_;
};

// One field in the encoding of its type: EncodeField writes it, DecodeField reads it back.
// The checkpoint's own fields and the observers' states both go through these.
struct EncodeField {
  StateWriter& w;
  void operator()(const std::string& x) { w.str(x); }
  void operator()(std::uint64_t x) { w.u64(x); }
  void operator()(std::int64_t x) { w.i64(x); }
  void operator()(int x) { w.i64(x); }
  void operator()(double x) { w.f64(x); }
  void operator()(bool x) { w.u32(x ? 1 : 0); }
  void operator()(__int128 x) { w.i128(x); }
  void operator()(const std::vector<double>& x) { w.f64s(x); }
  void operator()(const std::vector<std::int64_t>& x) { w.i64s(x); }
};

struct DecodeField {
  StateReader& r;
  void operator()(std::string& x) { x = r.str(); }
  void operator()(std::uint64_t& x) { x = r.u64(); }
  void operator()(std::int64_t& x) { x = r.i64(); }
  void operator()(int& x) { x = static_cast<int>(r.i64()); }
  void operator()(double& x) { x = r.f64(); }
  void operator()(bool& x) { x = r.u32() != 0; }
  void operator()(__int128& x) { x = r.i128(); }
  void operator()(std::vector<double>& x) { x = r.f64s(); }
  void operator()(std::vector<std::int64_t>& x) { x = r.i64s(); }
};

// An observer state made of a few fields, in order: put_state writes them under `name`;
// find_state reads them back and is false (nothing read) when the checkpoint has no state
// of that name.
template <class... T>
void put_state(Checkpoint& c, const std::string& name, const T&... fields) {
  StateWriter w;
  EncodeField encode{w};
  (encode(fields), ...);
  c.put(name, std::move(w.bytes()));
}

template <class... T>
bool find_state(const Checkpoint& c, const std::string& name, T&... fields) {
  const std::string* bytes = c.find(name);
  if (!bytes) return false;
  StateReader r(*bytes, name);
  DecodeField decode{r};
  (decode(fields), ...);
  return true;
}

// The largest magnitude of a position, speed, load or time a checkpoint may hold, and of a
// histogram bin's magnitude (a moment is a finite double: |ln M| < 710).
inline constexpr double kCheckpointMaxMagnitude = 1e15;
inline constexpr double kCheckpointMaxMagnitudeMu = 1000;

// Checks every field of a checkpoint as a scene key is checked (counts >= 0, reals finite
// and in range, flags 0/1, directions -1/0/1, a consistent histogram, the model's `blocks`
// and the scene's `bin_width`): bkq::Error naming the field, its value and what is
// allowed. A resume calls it after check_checkpoint_matches and before it changes anything,
// so an edited checkpoint (with a valid checksum) is refused with the folder as it was.
// `blocks` 0: the run's engine keeps no chain (OFC), whose state is then not checked here.
void validate_checkpoint(const Checkpoint& c, int blocks, double bin_width,
                         const std::string& origin);

// The OFC automaton's state travels as named states of the checkpoint: "ofc.engine" (the
// field as stored, the offset, the load, the counters) and, with relaxation, also
// "ofc.relaxation" (each site's pending stress, the load it was brought up to and its
// arrival at the threshold). The
// chain snapshot stays empty. find_ofc_state throws bkq::Error naming `origin` when a state
// the lattice `p` needs is missing.
void put_ofc_state(Checkpoint& c, const OfcSnapshot& s);
OfcSnapshot find_ofc_state(const Checkpoint& c, const OfcParams& p, const std::string& origin);

// Checks every field of the OFC state as a scene key is checked, against the lattice `p`
// and the run's progress: the field's length (the lattice's sites, padded as the engine
// stores them); each stress g + offset in [0, 1) (every site below threshold between
// events) and the padding at -inf; offset in [0, 5] (the engine folds it back past 4);
// load finite in [0, 1e15]; counters with 0 <= events <= generations <= topplings and
// events = the run's transient and recorded events; with relaxation, each pending stress
// finite in [0, 1e15] and brought up at a load in [0, load], and an arrival time exactly
// for the sites with pending stress. bkq::Error naming the field,
// its value and what is allowed; nothing is changed. A resume calls it with
// validate_checkpoint, before it changes anything.
void validate_ofc_state(const Checkpoint& c, const OfcParams& p, const std::string& origin);

std::string encode_checkpoint(const Checkpoint& c);
// Throws bkq::Error naming `origin` when `bytes` are not one complete, intact checkpoint
// of this format version (wrong magic, truncated, trailing bytes, checksum mismatch).
Checkpoint decode_checkpoint(const std::string& bytes, const std::string& origin);

// Throws bkq::Error when the checkpoint was written by another bkquake version or for
// another scene, naming the versions or the keys whose values differ.
void check_checkpoint_matches(const Checkpoint& c, const Scene& scene, const std::string& origin);

// Throws bkq::Error unless the first `bytes` bytes of the CSV file `path` are the line
// `header` followed by exactly `rows` complete lines, whose line_hash is `checksum` when one is
// given; only reads the file.
void check_csv_prefix(const std::string& path, const std::string& header, std::int64_t rows,
                      std::uint64_t bytes, std::optional<std::uint64_t> checksum = std::nullopt);

// The checkpoint files of one output folder.
class CheckpointFiles {
 public:
  explicit CheckpointFiles(std::string dir);
  std::string current() const;   // DIR/checkpoint.bin
  std::string previous() const;  // DIR/checkpoint.prev.bin
  bool exist() const;            // either of them
  // The final state of a finished event run (DIR/checkpoint.final.bin), kept so that
  // `run --resume --set run.events=N2` can extend it; it never counts as an interruption.
  std::string final_state() const;
  bool final_exists() const;
  void write_final(const Checkpoint& c) const;
  Checkpoint read_final() const;
  // Writes `c` as the new checkpoint.bin, keeping the old one as checkpoint.prev.bin.
  // Throws bkq::Error naming the file; the existing checkpoints stay intact on failure.
  void write(const Checkpoint& c) const;
  // The final state when `final` (write_final), a checkpoint otherwise (write).
  void save(const Checkpoint& c, bool final) const {
    if (final)
      write_final(c);
    else
      write(c);
  }
  // The newest checkpoint and the file it came from: checkpoint.bin, or checkpoint.prev.bin
  // when a crash came between the renames. Throws bkq::Error when there is none or when
  // checkpoint.bin is damaged (then naming checkpoint.prev.bin, if there is one).
  Checkpoint read(std::string* from = nullptr) const;
  // Deletes both checkpoints (and the final state) and any temporary file left by an
  // interrupted write.
  void remove() const;
  // Deletes both checkpoints and their temporaries, keeping the final state.
  void remove_interim() const;

 private:
  std::string dir_;
};

}  // namespace bkq
