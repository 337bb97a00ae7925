// Checkpoint encoding, validation and the two-file rotation (see checkpoint.hpp).
#include "io/checkpoint.hpp"

#include "bkquake_version.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/input_file.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'B', 'K', 'Q', 'C', 'K', 'P', 'T', '\n'};
// Version 2 added the observers' named states; version 1 files (without them) are read too.
constexpr std::uint32_t kFormatVersion = 2;
constexpr std::uint32_t kOldestFormatVersion = 1;
constexpr std::size_t kHeadBytes = sizeof kMagic + 4 + 8;  // magic, format version, length
constexpr std::size_t kSumBytes = 8;

// A new field in these structs must be added to the format (and kFormatVersion raised).
static_assert(sizeof(EngineCounters) == 5 * sizeof(std::int64_t),
              "EngineCounters changed: update the checkpoint");
static_assert(sizeof(ChainState) == 4 * sizeof(std::vector<double>) + 5 * sizeof(double),
              "ChainState changed: update the checkpoint");

// The checkpoint's fields in file order, written once for both directions: `io` is an
// EncodeField (writes each field) or a DecodeField (reads each field into it). A new field
// goes here, with kFormatVersion raised.
template <class Io, class Counters>
void counter_fields(Io& io, Counters& c) {
  for (auto* x : {&c.events, &c.steps, &c.block_steps, &c.sliding_block_steps, &c.releases}) io(*x);
}

// Everything but the observers' states (which came with format version 2).
template <class Io, class C>
void fixed_fields(Io& io, C& c) {
  io(c.version);
  io(c.git_revision);
  io(c.scene_hash);
  io(c.scene_ini);
  io(c.seed);

  auto& p = c.progress;
  io(p.transient_done);
  io(p.events_done);
  io(p.catalog_bytes);
  io(p.load0);
  counter_fields(io, p.counters0);
  io(p.moment_sum);
  io(p.nonpositive);
  io(p.wall_events);
  io(p.wall_total);
  io(p.resumes);

  auto& st = c.engine.state;
  for (auto* v : {&st.w, &st.wd, &st.mobile, &st.dir}) io(*v);
  for (auto* x : {&st.x, &st.xd, &st.s, &st.t, &st.sum_w}) io(*x);
  counter_fields(io, c.engine.counters);

  auto& h = c.histogram;
  io(h.bin_width);
  io(h.first_bin);
  io(h.counts);
  io(h.events);
  io(h.sum_q);
  io(h.sum_q2);
  io(h.min_mu);
  io(h.max_mu);
  io(h.exact_moments);
  io(h.total_load);
  io(h.blocks);
}

std::string read_whole(const std::string& path) {
  std::ifstream in = open_input(path, "checkpoint", std::ios::binary);
  std::string bytes;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    bytes.append(buf, static_cast<std::size_t>(in.gcount()));
    if (!in) break;
  }
  check_read(in, path, "checkpoint", 0);
  return bytes;
}

}  // namespace

void StateReader::fail() const {
  throw Error("checkpoint '" + origin_ + "' is malformed: a field runs past the end of its data");
}

std::string encode_checkpoint(const Checkpoint& c) {
  // One buffer, reserved for the chain's arrays and everything else, the payload length
  // filled in after the payload: a long chain's checkpoint is held once while it is made.
  StateWriter file;
  std::size_t others = 4096 + c.scene_ini.size() + 8 * c.histogram.counts.size();
  for (const ObserverState& o : c.observers) others += 16 + o.name.size() + o.bytes.size();
  file.bytes().reserve(4 * 8 * c.engine.state.w.size() + others);
  file.bytes().append(kMagic, sizeof kMagic);
  file.u32(kFormatVersion);
  file.u64(0);
  const std::size_t start = file.bytes().size();

  EncodeField encode{file};
  fixed_fields(encode, c);
  file.u64(c.observers.size());
  for (const ObserverState& o : c.observers) {
    file.str(o.name);
    file.str(o.bytes);
  }

  StateWriter length;
  length.u64(file.bytes().size() - start);
  file.bytes().replace(start - length.bytes().size(), length.bytes().size(), length.bytes());
  file.u64(fnv1a64(file.bytes()));
  return std::move(file.bytes());
}

Checkpoint decode_checkpoint(const std::string& bytes, const std::string& origin) {
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw Error("'" + origin +
                "' is not a bkquake checkpoint (it does not start with the checkpoint magic)");
  if (bytes.size() < kHeadBytes + kSumBytes)
    throw Error("checkpoint '" + origin + "' is truncated: " + std::to_string(bytes.size()) +
                " bytes");
  StateReader head(bytes, sizeof kMagic, kHeadBytes, origin);
  const std::uint32_t format = head.u32();
  if (format < kOldestFormatVersion || format > kFormatVersion)
    throw Error("checkpoint '" + origin + "' has format version " + std::to_string(format) +
                "; this bkquake reads versions " + std::to_string(kOldestFormatVersion) + " to " +
                std::to_string(kFormatVersion));
  const std::uint64_t payload = head.u64();
  if (payload != bytes.size() - kHeadBytes - kSumBytes)
    throw Error("checkpoint '" + origin + "' is " +
                (payload > bytes.size() ? "truncated" : "damaged") + ": " +
                std::to_string(bytes.size()) + " bytes, its header announces " +
                std::to_string(payload + kHeadBytes + kSumBytes));
  const std::size_t end = kHeadBytes + static_cast<std::size_t>(payload);
  const std::uint64_t stored = StateReader(bytes, end, bytes.size(), origin).u64();
  if (stored != fnv1a64(std::string_view(bytes.data(), end)))
    throw Error("checkpoint '" + origin + "' is damaged: checksum mismatch");

  StateReader r(bytes, kHeadBytes, end, origin);
  Checkpoint c;
  DecodeField decode{r};
  fixed_fields(decode, c);

  if (format >= 2) {
    c.observers.resize(r.count(16));
    for (ObserverState& o : c.observers) {
      o.name = r.str();
      o.bytes = r.str();
    }
  }

  if (!r.done())
    throw Error("checkpoint '" + origin + "' is malformed: unexpected bytes after the last field");
  return c;
}

void validate_checkpoint(const Checkpoint& c, int blocks, double bin_width,
                         const std::string& origin) {
  auto bad = [&](const std::string& field, const std::string& value, const char* allowed) {
    throw Error("checkpoint '" + origin + "' is invalid: " + field + " = " + value + ", expected " +
                allowed + " (damaged or edited); start over with --force");
  };
  auto count = [&](const char* field, std::int64_t v) {
    if (v < 0) bad(field, std::to_string(v), "a count >= 0");
  };
  // Positions, speeds, loads and times: finite and below 1e15, far beyond any run's reach
  // (a value such as 1e300 would overflow the forces and give another catalogue).
  auto real = [&](const std::string& field, double v, bool nonnegative = false) {
    if (!std::isfinite(v) || std::fabs(v) > kCheckpointMaxMagnitude || (nonnegative && v < 0))
      bad(field, format_real(v),
          nonnegative ? "a finite value in [0, 1e15]" : "a finite value in [-1e15, 1e15]");
  };
  auto counters = [&](const std::string& where, const EngineCounters& k) {
    count((where + ".events").c_str(), k.events);
    count((where + ".steps").c_str(), k.steps);
    count((where + ".block_steps").c_str(), k.block_steps);
    count((where + ".sliding_block_steps").c_str(), k.sliding_block_steps);
    count((where + ".releases").c_str(), k.releases);
  };

  const RunProgress& p = c.progress;
  count("transient_done", p.transient_done);
  count("events_done", p.events_done);
  count("resumes", p.resumes);
  if (p.nonpositive < 0 || p.nonpositive > p.events_done)
    bad("nonpositive", std::to_string(p.nonpositive), "a count in [0, events_done]");
  real("load0", p.load0);
  real("moment_sum", p.moment_sum);
  real("wall_events", p.wall_events, true);
  real("wall_total", p.wall_total, true);
  counters("counters0", p.counters0);

  const ChainState& st = c.engine.state;
  const std::size_t n = st.w.size();
  // blocks == 0: the run's engine keeps no chain (the OFC automaton's state is a named one).
  if (blocks > 0) {
    if (n == 0) bad("blocks", "0", "at least 1");
    if (st.wd.size() != n || st.mobile.size() != n || st.dir.size() != n)
      throw Error("checkpoint '" + origin + "' is malformed: the chain arrays differ in length");
    for (std::size_t j = 0; j < n; ++j) {
      std::string at = "[";  // (built in steps: GCC 12 warns falsely on "[" + to_string(j))
      at += std::to_string(j);
      at += ']';
      real("block position" + at, st.w[j]);
      real("block velocity" + at, st.wd[j]);
      if (st.mobile[j] != 0 && st.mobile[j] != 1)
        bad("mobile" + at, format_real(st.mobile[j]), "0 or 1");
      if (st.dir[j] != -1 && st.dir[j] != 0 && st.dir[j] != 1)
        bad("direction" + at, format_real(st.dir[j]), "-1, 0 or 1");
    }
    real("pad position", st.x);
    real("pad velocity", st.xd);
    real("substrate displacement", st.s);
    real("time", st.t, true);
    real("sum of block positions", st.sum_w);
  }
  counters("engine", c.engine.counters);

  const MagnitudeHistogram::State& h = c.histogram;
  if (!(h.bin_width > 0) || !std::isfinite(h.bin_width))
    bad("histogram bin_width", format_real(h.bin_width), "a finite width > 0");
  // A moment is a finite double, so |ln M| < 710: bins beyond that hold nothing.
  if (std::fabs(static_cast<double>(h.first_bin) * h.bin_width) > kCheckpointMaxMagnitudeMu)
    bad("histogram first_bin", std::to_string(h.first_bin),
        "a bin whose magnitude lies in [-1000, 1000]");
  count("histogram events", h.events);
  if (h.events > p.events_done)
    bad("histogram events", std::to_string(h.events), "at most events_done");
  real("histogram total_load", h.total_load, true);
  if (h.blocks < 0) bad("histogram blocks", std::to_string(h.blocks), "a count >= 0");
  if (h.events > 0) {
    real("histogram min_mu", h.min_mu);
    real("histogram max_mu", h.max_mu);
  }
  try {
    (void)MagnitudeHistogram::from_state(h);
  } catch (const Error& e) {
    bad("histogram", e.what(), "a consistent histogram");
  }
  // The chain and the bins are the scene's (a checkpoint edited with its checksum redone
  // could still differ).
  if (n != static_cast<std::size_t>(blocks))
    bad("blocks", std::to_string(n), ("the model's " + std::to_string(blocks)).c_str());
  if (h.bin_width != bin_width)
    bad("histogram bin_width", format_real(h.bin_width), "the scene's stats.bin_width");
}

namespace {
constexpr const char* kOfcState = "ofc.engine";
constexpr const char* kOfcRelaxation = "ofc.relaxation";
}  // namespace

void put_ofc_state(Checkpoint& c, const OfcSnapshot& s) {
  put_state(c, kOfcState, s.g, s.offset, s.load, s.counters.events, s.counters.topplings,
            s.counters.generations);
  if (!s.pending.empty()) put_state(c, kOfcRelaxation, s.pending, s.pending_at, s.arrival);
}

OfcSnapshot find_ofc_state(const Checkpoint& c, const OfcParams& p, const std::string& origin) {
  OfcSnapshot s;
  if (!find_state(c, kOfcState, s.g, s.offset, s.load, s.counters.events, s.counters.topplings,
                  s.counters.generations))
    throw Error("checkpoint '" + origin + "': no OFC state (" + kOfcState + ") in it");
  if (p.relaxes() && !find_state(c, kOfcRelaxation, s.pending, s.pending_at, s.arrival))
    throw Error("checkpoint '" + origin + "': no OFC relaxation state (" + kOfcRelaxation +
                ") in it, and ofc.relaxation_time > 0");
  return s;
}

void validate_ofc_state(const Checkpoint& c, const OfcParams& p, const std::string& origin) {
  auto bad = [&](const std::string& field, const std::string& value, const std::string& allowed) {
    throw Error("checkpoint '" + origin + "' is invalid: " + field + " = " + value + ", expected " +
                allowed + " (damaged or edited); start over with --force");
  };
  const OfcSnapshot s = find_ofc_state(c, p, origin);
  const std::size_t n = static_cast<std::size_t>(p.sites());
  const std::size_t stored = OfcEngine::stored_size(p);
  if (s.g.size() != stored)
    bad("ofc field length", std::to_string(s.g.size()),
        std::to_string(stored) + " (the lattice's " + std::to_string(n) + " sites, padded)");
  if (!std::isfinite(s.offset) || s.offset < 0 || s.offset > 5)
    bad("ofc offset", format_real(s.offset), "a value in [0, 5]");
  if (!std::isfinite(s.load) || s.load < 0 || s.load > kCheckpointMaxMagnitude)
    bad("ofc load", format_real(s.load), "a finite value in [0, 1e15]");
  for (std::size_t j = 0; j < stored; ++j) {
    std::string at = "[";  // (built in steps: GCC 12 warns falsely on "[" + to_string(j))
    at += std::to_string(j);
    at += ']';
    if (j >= n) {
      if (s.g[j] != -HUGE_VAL) bad("ofc padding" + at, format_real(s.g[j]), "-inf");
      continue;
    }
    const double f = s.g[j] + s.offset;
    if (!std::isfinite(s.g[j]) || !(f >= 0 && f < 1))
      bad("ofc stress" + at, format_real(f), "a value in [0, 1) (every site below threshold)");
  }
  const OfcCounters& k = s.counters;
  const std::int64_t events = c.progress.transient_done + c.progress.events_done;
  if (k.events != events)
    bad("ofc events", std::to_string(k.events),
        std::to_string(events) + " (the run's transient and recorded events)");
  if (k.generations < k.events)
    bad("ofc generations", std::to_string(k.generations), "at least ofc events");
  if (k.topplings < k.generations)
    bad("ofc topplings", std::to_string(k.topplings), "at least ofc generations");
  if (!p.relaxes()) return;
  if (s.pending.size() != n || s.pending_at.size() != n || s.arrival.size() != n)
    bad("ofc pending length", std::to_string(s.pending.size()),
        std::to_string(n) + " (one per site)");
  for (std::size_t j = 0; j < n; ++j) {
    std::string at = "[";
    at += std::to_string(j);
    at += ']';
    if (!std::isfinite(s.pending[j]) || s.pending[j] < 0 || s.pending[j] > kCheckpointMaxMagnitude)
      bad("ofc pending" + at, format_real(s.pending[j]), "a finite value in [0, 1e15]");
    if (!std::isfinite(s.pending_at[j]) || s.pending_at[j] < 0 || s.pending_at[j] > s.load)
      bad("ofc pending_at" + at, format_real(s.pending_at[j]), "a load in [0, ofc load]");
    // A site with pending stress has its arrival at the threshold ahead; one without, none.
    const double a = s.arrival[j];
    if (s.pending[j] > 0
            ? !(std::isfinite(a) && a >= s.pending_at[j] && a <= kCheckpointMaxMagnitude)
            : a != -1)
      bad("ofc arrival" + at, format_real(a),
          s.pending[j] > 0 ? "a load in [ofc pending_at, 1e15] (the site has pending stress)"
                           : "-1 (the site has no pending stress)");
  }
}

void check_checkpoint_matches(const Checkpoint& c, const Scene& scene, const std::string& origin) {
  if (c.version != kVersion)
    throw Error("checkpoint '" + origin + "' was written by bkquake " + c.version +
                ", this is bkquake " + kVersion +
                ": the continuation would not be exact; start over with --force");
  if (c.scene_hash == scene.hash()) return;
  std::string diff;
  try {
    const Scene saved = Scene::from_text(c.scene_ini, origin);
    int shown = 0;
    for (const ParamSpec& p : parameter_table()) {
      if (saved.text(p.key) == scene.text(p.key)) continue;
      if (shown++ < 3) {
        diff += shown > 1 ? "; " : "";
        diff +=
            p.key + " = " + saved.text(p.key) + " in the checkpoint, " + scene.text(p.key) + " now";
      }
    }
    if (shown > 3) diff += "; and " + std::to_string(shown - 3) + " more";
  } catch (const Error&) {
    // A scene text this version cannot read back: the hashes alone must tell.
  }
  if (diff.empty())
    diff = "scene hash " + std::to_string(c.scene_hash) + " in the checkpoint, " +
           std::to_string(scene.hash()) + " now";
  throw Error("checkpoint '" + origin + "' belongs to another scene (" + diff +
              "); resume with the run's own scene.ini, or start over with --force");
}

void check_csv_prefix(const std::string& path, const std::string& header, std::int64_t rows,
                      std::uint64_t bytes, std::optional<std::uint64_t> checksum) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw Error("cannot resume: '" + path + "': " + ec.message());
  if (size < bytes)
    throw Error("cannot resume: '" + path + "' has " + std::to_string(size) +
                " bytes, the checkpoint expects at least " + std::to_string(bytes) +
                " (the file was changed after the checkpoint)");
  std::ifstream in(path, std::ios::binary);
  std::string first;
  if (!in || !std::getline(in, first) || first != header)
    throw Error("cannot resume: '" + path + "' does not start with the header '" + header + "'");
  in.seekg(0);
  // Count line ends in the prefix: it must be the header and exactly `rows` whole rows.
  // line_hash of each line; a line split between two reads is hashed in two parts, the
  // bytes that do not fill a word of 8 carried over to the next read.
  std::int64_t lines = 0;
  char last = '\n';
  std::uint64_t hash = kLineHashSeed;
  char carry[8];
  std::size_t carried = 0;
  std::vector<char> buf(1 << 20);
  for (std::uint64_t left = bytes; left > 0;) {
    const auto n = static_cast<std::streamsize>(std::min<std::uint64_t>(left, buf.size()));
    if (!in.read(buf.data(), n)) throw Error("cannot resume: read error on '" + path + "'");
    const char* p = buf.data();
    const char* const end = p + n;
    while (p < end) {
      const char* nl = static_cast<const char*>(std::memchr(p, '\n', end - p));
      const char* const stop = nl ? nl + 1 : end;
      if (carried > 0) {  // the start of this line was in the previous read
        const std::size_t take = std::min<std::size_t>(8 - carried, stop - p);
        std::memcpy(carry + carried, p, take);
        carried += take;
        p += take;
        if (carried < 8 && !nl) break;  // the read ended first: carry on
        hash = line_hash(std::string_view(carry, carried), hash);
        carried = 0;
      }
      if (nl) {
        if (p < stop) hash = line_hash(std::string_view(p, stop - p), hash);
        ++lines;
      } else {  // the line goes on in the next read
        const auto whole = static_cast<std::size_t>(stop - p) / 8 * 8;
        if (whole > 0) hash = line_hash(std::string_view(p, whole), hash);
        carried = static_cast<std::size_t>(stop - p) - whole;
        std::memcpy(carry, p + whole, carried);
      }
      p = stop;
    }
    last = buf[static_cast<std::size_t>(n - 1)];
    left -= static_cast<std::uint64_t>(n);
  }
  if (lines != rows + 1 || last != '\n')
    throw Error("cannot resume: the first " + std::to_string(bytes) + " bytes of '" + path +
                "' hold " + std::to_string(lines) +
                " lines, the checkpoint expects the header and " + std::to_string(rows) +
                " rows (the file was changed after the checkpoint)");
  if (checksum && *checksum != hash)
    throw Error("cannot resume: the first " + std::to_string(bytes) + " bytes of '" + path +
                "' are not those the checkpoint saw (their checksum differs: a row was changed "
                "after the checkpoint)");
}

CheckpointFiles::CheckpointFiles(std::string dir) : dir_(std::move(dir)) {}

std::string CheckpointFiles::current() const {
  return (fs::path(dir_) / "checkpoint.bin").string();
}
std::string CheckpointFiles::previous() const {
  return (fs::path(dir_) / "checkpoint.prev.bin").string();
}

std::string CheckpointFiles::final_state() const {
  return (fs::path(dir_) / "checkpoint.final.bin").string();
}

bool CheckpointFiles::final_exists() const {
  std::error_code ec;
  return fs::exists(final_state(), ec);
}

void CheckpointFiles::write_final(const Checkpoint& c) const {
  const std::string tmp = write_temp_beside(final_state(), encode_checkpoint(c));
  try {
    rename_file(tmp, final_state());
  } catch (const Error&) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  sync_folder(dir_);
}

Checkpoint CheckpointFiles::read_final() const {
  return decode_checkpoint(read_whole(final_state()), final_state());
}

bool CheckpointFiles::exist() const {
  std::error_code ec;
  return fs::exists(current(), ec) || fs::exists(previous(), ec);
}

Checkpoint Checkpoint::of_run(std::uint64_t scene_hash, std::string scene_ini, std::uint64_t seed,
                              const RunProgress& progress) {
  Checkpoint c;
  c.version = kVersion;
  c.git_revision = kGitRevision;
  c.scene_hash = scene_hash;
  c.scene_ini = std::move(scene_ini);
  c.seed = seed;
  c.progress = progress;
  return c;
}

void Checkpoint::put(const std::string& name, std::string bytes) {
  for (ObserverState& o : observers)
    if (o.name == name) {
      o.bytes = std::move(bytes);
      return;
    }
  observers.push_back({name, std::move(bytes)});
}

const std::string* Checkpoint::find(const std::string& name) const {
  for (const ObserverState& o : observers)
    if (o.name == name) return &o.bytes;
  return nullptr;
}

void CheckpointFiles::write(const Checkpoint& c) const {
  const std::string tmp = write_temp_beside(current(), encode_checkpoint(c));
  std::error_code ec;
  try {
    if (fs::exists(current(), ec)) rename_file(current(), previous());
    rename_file(tmp, current());
  } catch (const Error&) {
    fs::remove(tmp, ec);
    throw;
  }
  sync_folder(dir_);
}

Checkpoint CheckpointFiles::read(std::string* from) const {
  std::error_code ec;
  std::string path = current();
  if (!fs::exists(path, ec)) {
    path = previous();
    if (!fs::exists(path, ec)) {
      // A folder that holds a run's files is refused without --force: say so.
      const bool has_run = fs::exists(fs::path(dir_) / "scene.ini", ec) ||
                           fs::exists(fs::path(dir_) / "catalog.csv", ec) ||
                           fs::exists(fs::path(dir_) / "catalog.h5", ec);
      throw Error("--resume: no checkpoint in '" + dir_ + "' (checkpoint.bin): nothing to " +
                  (has_run ? "continue; to run it again from the start, use --force instead of "
                             "--resume"
                           : "continue; start the run without --resume"));
    }
  }
  if (from) *from = path;
  try {
    return decode_checkpoint(read_whole(path), path);
  } catch (const Error& e) {
    if (path == current() && fs::exists(previous(), ec))
      throw Error(std::string(e.what()) + "; the checkpoint before it is '" + previous() +
                  "': rename it to checkpoint.bin to resume from there");
    throw;
  }
}

void CheckpointFiles::remove_interim() const {
  std::error_code ec;
  fs::remove(current(), ec);
  fs::remove(previous(), ec);
  remove_temporaries_of(current());
}

void CheckpointFiles::remove() const {
  std::error_code ec;
  fs::remove(current(), ec);
  fs::remove(previous(), ec);
  fs::remove(final_state(), ec);
  remove_temporaries_of(current());  // of a write cut short by a second signal or a crash
  remove_temporaries_of(final_state());
}

}  // namespace bkq
