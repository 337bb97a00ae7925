// The abuse test: bkquake run with randomised scenes (keys from the declared set
// with random, extreme, non-finite and mistyped values, unknown keys, in a scene file or as
// --set), fit with random options, and run --resume, fit and merge on truncated and
// byte-flipped scene, catalog, histogram, summary and checkpoint files, and (third round)
// the readers' bounds: damaged JSON, damaged HDF5, inputs that fail to read, sweeps too
// large to plan, and (fourth round) links among a run's files, the Python readers on
// devices, FIFOs and garbage, wide coupling stencils under SIGTERM. The run's length is capped by
// the harness (blocks, events, duration, steps per event); half the runs are stopped with SIGTERM
// once they have made progress (a checkpoint, rows of a time series), a state, not a time. Every
// case must end
//   - with exit 0 and a valid output (run: summary.json written, the lock released), or
//   - with exit 2 and exactly one error line (warnings before it allowed), or
//   - when stopped, with exit 143 and, for an event run, output that --resume accepts;
// never a hang (a guard of kGuard seconds fails the case), a crash, exit 1, a byte that is
// not printable text on stderr, or a changed input file. The cases are drawn from a seeded
// generator, so a failure reproduces:
//   BKQUAKE_ABUSE_SEED=S BKQUAKE_ABUSE_CASES=N build/bkquake_tests --gtest_filter='Abuse.*'
// (CI runs the default: seed 19, 160 cases, about a minute on two cores; the failure
// message names the case number and its command). scripts/abuse.sh runs many more.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "core/terminal_text.hpp"
#include "io/folder_lock.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"

namespace bkq {
namespace {
using test::tree_bytes;

namespace fs = std::filesystem;
using test::read_file;

// Only a guard against a hang: a command still running after this long fails its case. No
// case depends on how long a command takes: a run is stopped (SIGTERM) when it has reached
// a state (its first checkpoint, some rows of its time series), not at a time.
constexpr double kGuard = 300.0;

// A command run to its end (still under the guard).
const std::function<bool()> kNever = [] { return false; };

// Whether a run in `out` has made progress worth stopping it at: a checkpoint newer than
// `after` (a resumed run: one of its own), or a time series past its first rows.
std::function<bool()> progressed(const fs::path& out,
                                 fs::file_time_type after = fs::file_time_type::min()) {
  return [out, after] {
    std::error_code ec;
    const auto t = fs::last_write_time(out / "checkpoint.bin", ec);
    if (!ec && t > after) return true;
    const auto size = fs::file_size(out / "timeseries.csv", ec);
    return !ec && size > 4096 && after == fs::file_time_type::min();
  };
}

std::uint64_t env_number(const char* name, std::uint64_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtoull(v, nullptr, 10) : fallback;
}

std::string joined(const std::vector<std::string>& args) {
  std::string s = "bkquake";
  for (const auto& a : args) s += " '" + a + "'";
  return s;
}

// An event that did not end within run.max_steps_per_event: a refusal the run names (exit 2,
// its state saved), which a random scene with a tiny dt and the harness's step cap can reach.
bool runaway(const test::ProcessResult& r) {
  return r.status == 2 && r.err.find("did not end after") != std::string::npos &&
         r.err.find("run.max_steps_per_event") != std::string::npos;
}

class Abuse : public ::testing::Test {
 protected:
  std::mt19937_64 rng_{env_number("BKQUAKE_ABUSE_SEED", 19)};

  std::size_t pick(std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_);
  }
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  bool chance(double p) { return uniform(0, 1) < p; }

  // A random value for `p`: valid, at or just beyond a bound, non-finite or mistyped.
  std::string value_for(const ParamSpec& p) {
    static const std::vector<std::string> junk = {
        "abc",      "",    "1.5.2", "0x1p3", "1,5", "--1",  "1e", "1e999",
        "-1e999",   "nan", "inf",   "-inf",  "NaN", "true", "+",  "9999999999999999999999",
        "\x01\xff", "1 2", "auto"};
    const int kind = static_cast<int>(pick(4));
    if (kind == 3) return junk[pick(junk.size())];
    switch (p.type) {
      case ParamType::Choice:
        return kind == 2 ? p.choices[0] + "x" : p.choices[pick(p.choices.size())];
      case ParamType::Boolean:
        return kind == 2 ? "maybe" : (chance(0.5) ? "true" : "false");
      case ParamType::Path:  // a missing file, a folder, or none
        return kind == 2 ? "/nonexistent/table.csv" : (chance(0.5) ? "/" : "");
      case ParamType::Integer:
      case ParamType::Real: {
        std::ostringstream out;
        out.precision(17);
        if (kind == 0) {  // inside the range, log-uniform over large spans
          const double lo = p.min, hi = p.max;
          double v = lo + (hi - lo) * uniform(0, 1);
          if (hi > 1000 * std::max(1.0, std::fabs(lo)) && chance(0.7))
            v = std::max(lo, std::exp(uniform(std::log(std::max(lo, 1e-6) + 1e-12), std::log(hi))));
          if (p.type == ParamType::Integer)
            out << static_cast<long long>(std::floor(v));
          else
            out << v;
        } else if (kind == 1) {  // a bound itself
          out << (chance(0.5) ? p.min : p.max);
        } else {  // just beyond a bound
          out << (chance(0.5) ? p.min - 1e-9 * std::max(1.0, std::fabs(p.min)) - 1
                              : p.max * (1 + 1e-9) + 1);
        }
        return out.str();
      }
    }
    return "?";
  }

  // Clamps the keys that make a run long to the harness's caps (only when the value is a
  // number above the cap: bad values stay, to be refused).
  static void cap(std::map<std::string, std::string>& keys) {
    static const std::map<std::string, double> caps = {{"model.blocks", 30},
                                                       {"run.events", 300},
                                                       {"run.transient_events", 50},
                                                       {"run.duration", 40},
                                                       {"run.max_steps_per_event", 200000}};
    for (const auto& [key, limit] : caps) {
      auto it = keys.find(key);
      if (it == keys.end()) continue;
      char* end = nullptr;
      const double v = std::strtod(it->second.c_str(), &end);
      if (end && *end == '\0' && !it->second.empty() && std::isfinite(v) && v > limit) {
        std::ostringstream out;
        out << limit;
        it->second = out.str();
      }
    }
  }

  // Checks the outcome of one command; `inputs` must be unchanged afterwards.
  void check(int n, const std::vector<std::string>& args, const test::ProcessResult& r,
             const std::map<std::string, std::string>& inputs, const fs::path& out) {
    SCOPED_TRACE("case " + std::to_string(n) + ": " + joined(args));
    // Printable text: ASCII, or UTF-8 of printable characters (a message keeps a path's
    // letters), which the terminal escaper leaves as it is.
    for (const std::string& line : r.err_lines())
      ASSERT_EQ(printable_text(line, line.size() + 1), line) << "unprintable bytes on stderr:\n"
                                                             << r.err;
    for (const auto& [path, bytes] : inputs)
      EXPECT_TRUE(read_file(path) == bytes) << "input changed: " << path;
    ASSERT_FALSE(r.hung) << "still running after " << kGuard << " s (a hang)\n" << r.err;
    // Stopped at a state it reached (a run that finished as the signal came exits 0), or
    // ended by an event its step bound cannot finish (a tiny random dt), which it names.
    if (r.timed_out && r.status != 0 && !runaway(r)) {
      EXPECT_EQ(r.status, 143) << r.err;
      // A run stopped while running says so in its summary (one stopped while setting up
      // has none yet; one whose signal came after it had written its finished summary, as
      // it was ending, keeps that).
      if (!out.empty() && args[0] == "run" && fs::exists(out / "summary.json")) {
        const RunStatus status = run_status(out);
        EXPECT_TRUE(status == RunStatus::Interrupted || status == RunStatus::Finished);
      }
      if (!out.empty()) {
        EXPECT_FALSE(fs::exists(out / "bkquake.lock")) << "lock left behind";
      }
      return;
    }
    ASSERT_TRUE(r.status == 0 || r.status == 2) << "exit " << r.status << "\n" << r.err;
    if (r.status == 2) {
      const auto lines = r.err_lines();
      ASSERT_FALSE(lines.empty());
      int errors = 0;
      for (const auto& l : lines) {
        if (l.rfind("bkquake: error: ", 0) == 0)
          ++errors;
        else
          EXPECT_EQ(l.rfind("bkquake: warning: ", 0), 0u) << "stray stderr line: " << l;
      }
      EXPECT_EQ(errors, 1) << r.err;
      EXPECT_EQ(lines.back().rfind("bkquake: error: ", 0), 0u) << r.err;
    } else if (!out.empty() && args[0] == "run") {
      EXPECT_EQ(run_status(out), RunStatus::Finished) << r.err;
    }
    if (!out.empty()) {
      EXPECT_FALSE(fs::exists(out / "bkquake.lock")) << "lock left behind";
    }
  }

  test::TempDir tmp_;
};

// Random scenes: a capped base scene with random keys in a file or as --set.
TEST_F(Abuse, RandomScenesAndOptions) {
  const int cases = static_cast<int>(env_number("BKQUAKE_ABUSE_CASES", 160));
  const auto& table = parameter_table();
  for (int n = 0; n < cases; ++n) {
    const fs::path dir = tmp_.path() / ("c" + std::to_string(n));
    fs::create_directories(dir);
    std::map<std::string, std::string> file_keys = {{"model.blocks", "10"}};
    const bool continuous = chance(0.35);
    if (continuous) {
      file_keys["drive.mode"] = "continuous";
      file_keys["run.duration"] = "20";
    } else {
      file_keys["run.events"] = "150";
      file_keys["run.transient_events"] = "10";
      file_keys["run.max_steps_per_event"] = "200000";
    }
    std::vector<std::string> sets;
    const int extra = 1 + static_cast<int>(pick(4));
    for (int k = 0; k < extra; ++k) {
      std::string key = table[pick(table.size())].key;
      if (chance(0.06)) key = chance(0.5) ? key + "x" : "nosuch.key";
      const ParamSpec* p = find_param(key);
      const std::string v = p ? value_for(*p) : "1";
      if (chance(0.3) && v.find_first_of("\x01\xff") == std::string::npos)
        sets.push_back(key + "=" + v);
      else
        file_keys[key] = v;
    }
    cap(file_keys);
    for (std::string& s : sets) {  // a --set of a long run's key is capped as in the file
      std::map<std::string, std::string> one = {
          {s.substr(0, s.find('=')), s.substr(s.find('=') + 1)}};
      cap(one);
      s = one.begin()->first + "=" + one.begin()->second;
    }
    std::string ini;
    for (const auto& [key, value] : file_keys) {
      const auto dot = key.find('.');
      // (In steps: GCC 12 warns falsely on "[" + key.substr(...) here.)
      ini += '[';
      ini += key.substr(0, dot);
      ini += "]\n" + key.substr(dot + 1) + " = " + value + "\n";
    }
    const std::string scene = (dir / "scene-in.ini").string();
    std::ofstream(scene, std::ios::binary) << ini;
    std::vector<std::string> args = {"run", scene, "--quiet", "--out", (dir / "out").string()};
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    const auto inputs = tree_bytes(scene);
    // Half the runs are stopped once they have made progress, the others run to their end.
    const bool stop = chance(0.5);
    const auto r = stop ? test::run_bkquake_until(progressed(dir / "out"), args, kGuard)
                        : test::run_bkquake_until(kNever, args);
    check(n, args, r, inputs, dir / "out");
    if (HasFailure()) return;
    // A stopped run resumes (or is refused only for a reason it names: a continuous run
    // with output.energy, whose windows are not checkpointed), stopped again at its first
    // checkpoint of its own.
    if (r.status == 143 && fs::exists(dir / "out" / "checkpoint.bin")) {
      auto again = args;
      again.push_back("--resume");
      const auto r2 = test::run_bkquake_until(
          progressed(dir / "out", fs::last_write_time(dir / "out" / "checkpoint.bin")), again,
          kGuard);
      check(n, again, r2, inputs, dir / "out");
      EXPECT_TRUE(
          r2.status == 0 || r2.status == 143 || runaway(r2) ||
          (continuous && r2.status == 2 && r2.err.find("output.energy") != std::string::npos))
          << r2.err;
    }
    // Every few cases, the fit with random options on a random run's catalogue.
    if (r.status == 0 && !continuous && chance(0.5)) {
      std::vector<std::string> fit = {"fit", (dir / "out" / "catalog.csv").string()};
      for (const char* opt : {"--mu-min", "--mu-max", "--bin-width"})
        if (chance(0.5))
          fit.insert(
              fit.end(),
              {opt, value_for(*find_param(opt[2] == 'b' ? "stats.bin_width" : "stats.mu_min"))});
      const auto inputs_fit = tree_bytes(dir / "out");
      check(n, fit, test::run_bkquake_until(kNever, fit), inputs_fit, {});
    }
    fs::remove_all(dir);
    if (HasFailure()) return;
  }
}

// Damaged files: truncated, byte-flipped or with inserted garbage, fed to the command that
// reads them.
TEST_F(Abuse, DamagedFiles) {
  const int cases = static_cast<int>(env_number("BKQUAKE_ABUSE_CASES", 160)) / 2;
  const std::vector<std::string> base = {"--quiet", "--set", "model.blocks=20", "--set",
                                         "run.transient_events=10"};
  auto run_into = [&](const std::string& name, const std::vector<std::string>& more) {
    std::vector<std::string> a = {"run"};
    a.insert(a.end(), base.begin(), base.end());
    a.insert(a.end(), more.begin(), more.end());
    a.insert(a.end(), {"--out", tmp_.file(name)});
    return a;
  };
  // Two finished runs to merge, and one stopped mid-run with checkpoints to resume.
  ASSERT_EQ(
      test::run_bkquake(run_into("a", {"--set", "run.events=400", "--set", "run.seed=1"})).status,
      0);
  ASSERT_EQ(
      test::run_bkquake(run_into("b", {"--set", "run.events=400", "--set", "run.seed=2"})).status,
      0);
  const auto stopped_args =
      run_into("stopped", {"--set", "run.events=20000", "--set", "run.checkpoint_events=200"});
  ASSERT_EQ(test::run_and_signal_when(
                stopped_args, [&] { return fs::exists(tmp_.file("stopped/checkpoint.prev.bin")); },
                SIGTERM),
            143);
  struct Target {
    std::string folder, file;
  };
  const std::vector<Target> targets = {
      {"b", "scene.ini"},      {"b", "histogram.csv"},        {"b", "summary.json"},
      {"b", "catalog.csv"},    {"stopped", "checkpoint.bin"}, {"stopped", "catalog.csv"},
      {"stopped", "scene.ini"}};
  for (int n = 0; n < cases; ++n) {
    const Target t = targets[pick(targets.size())];
    const fs::path work = tmp_.path() / ("d" + std::to_string(n));
    fs::create_directories(work);
    fs::copy(tmp_.file(t.folder), work / t.folder, fs::copy_options::recursive);
    const fs::path victim = work / t.folder / t.file;
    std::string bytes = read_file(victim.string());
    if (bytes.empty()) bytes = "x";
    switch (pick(3)) {
      case 0:
        bytes.resize(pick(bytes.size()));
        break;
      case 1:
        for (int k = 0, m = 1 + static_cast<int>(pick(4)); k < m; ++k)
          bytes[pick(bytes.size())] ^= static_cast<char>(1 + pick(255));
        break;
      default:
        bytes.insert(pick(bytes.size()), std::string("\x00\x1b[2J\xff\n,,nan,", 13));
    }
    std::ofstream(victim, std::ios::binary | std::ios::trunc) << bytes;

    std::vector<std::string> args;
    std::map<std::string, std::string> inputs;
    fs::path out;
    if (t.folder == "stopped") {  // resume the damaged interrupted run with its own scene
      args = {"run",     (work / "stopped" / "scene.ini").string(),
              "--quiet", "--resume",
              "--out",   (work / "stopped").string()};
      if (t.file == "scene.ini") inputs = tree_bytes(victim);
      out = work / "stopped";
    } else if (t.file == "catalog.csv") {
      args = {"fit", victim.string()};
      inputs = tree_bytes(work);
    } else if (t.file == "scene.ini" && chance(0.5)) {
      args = {"run", victim.string(), "--quiet", "--out", (work / "rerun").string()};
      inputs = tree_bytes(work / t.folder);
      out = work / "rerun";
    } else {
      fs::copy(tmp_.file("a"), work / "a", fs::copy_options::recursive);
      args = {"merge", (work / "a").string(), (work / "b").string(), "--out",
              (work / "m").string()};
      inputs = tree_bytes(work);
      out = work / "m";
    }
    // Run to its end (a resume of a damaged folder is refused or finishes: stopping it at
    // once would race its checks).
    const auto r = test::run_bkquake_until(kNever, args, kGuard);
    // A resume refused after a damaged checkpoint or catalogue must leave the folder as it
    // was (the resume checks everything before it changes anything).
    check(n, args, r, inputs, out);
    fs::remove_all(work);
    if (HasFailure()) return;
  }
}

// The analysis commands on hostile folders (fourth round): fit --json/--scan and
// seismicity --export/--out aimed at a run's own files, at links (to another run's
// catalogue, to a device, dangling, to the input), at devices and folders, in a run folder
// whose lock is live or stale or that holds what a killed analysis left. Beyond check():
// no file of either run changes, a live run's folder gets nothing, and an analysis that
// succeeded into the folder leaves no lock and none of the temporaries it found.
TEST_F(Abuse, AnalysisOnHostileFoldersAndLinks) {
  const int cases = static_cast<int>(env_number("BKQUAKE_ABUSE_CASES", 160)) / 2;
  for (const char* name : {"a", "b"}) {
    const auto r = test::run_bkquake({"run", "--quiet", "--set", "model.blocks=20", "--set",
                                      "run.events=600", "--set", "run.transient_events=10", "--set",
                                      std::string("run.seed=") + (name[0] == 'a' ? "1" : "2"),
                                      "--out", tmp_.file(name)});
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const std::vector<std::string> own = {"catalog.csv",         "scene.ini",      "summary.json",
                                        "histogram.csv",       "checkpoint.bin", "bkquake.lock",
                                        "checkpoint.final.bin"};
  for (int n = 0; n < cases; ++n) {
    const fs::path work = tmp_.path() / ("h" + std::to_string(n));
    fs::create_directories(work);
    fs::copy(tmp_.file("a"), work / "a", fs::copy_options::recursive);
    fs::copy(tmp_.file("b"), work / "b", fs::copy_options::recursive);
    const fs::path a = work / "a", b = work / "b";
    // The folder's state: as finished, a live lock, a stale lock, what a killed analysis left.
    const std::size_t state = pick(4);
    std::unique_ptr<FolderLock> live;
    pid_t gone = 0;
    if (state == 1) live = std::make_unique<FolderLock>(a.string(), "run", StaleLock::Refuse);
    if (state == 2 || state == 3) {
      gone = ::fork();
      if (gone == 0) {
        new FolderLock(a.string(), "seismicity", StaleLock::Refuse);  // killed: never released
        ::_exit(0);
      }
      int status = 0;
      ::waitpid(gone, &status, 0);
    }
    if (state == 3) {
      const std::string tag = std::to_string(gone);
      fs::create_directories(a / (".seismicity.new-" + tag));
      std::ofstream(a / "b_scan.csv.bkquake-tmp-Xy12Zw") << "half";
    }
    // Where the output goes: a run's own file (its own or the other's), a link, a device, a
    // folder, or a plain new file inside or outside the folder.
    const auto target = [&]() -> fs::path {
      switch (pick(6)) {
        case 0:
          return a / own[pick(own.size())];
        case 1:
          return b / own[pick(own.size())];
        case 2: {
          const fs::path link = a / "out.csv";
          static const char* const to[] = {"../b/catalog.csv", "/dev/null", "missing/nothing",
                                           "catalog.csv"};
          fs::create_symlink(to[pick(4)], link);
          return link;
        }
        case 3:  // (a device only through a link: a regression must not replace the device)
          if (chance(0.5)) return b;
          fs::create_symlink("/dev/null", work / "null");
          return work / "null";
        case 4:
          return a / "derived.csv";
        default:
          return work / "elsewhere.csv";
      }
    }();
    std::vector<std::string> args;
    switch (pick(5)) {
      case 0:
        args = {"fit", a.string(), "--json", target.string()};
        break;
      case 1:
        args = {"fit", (a / "catalog.csv").string(), "--scan", "--out",
                chance(0.5) ? a.string() : target.string()};
        break;
      case 2:
        args = {"fit", a.string(), "--scan", "--json", target.string()};
        break;
      case 3:
        args = {"seismicity", a.string(), "--export", target.string()};
        break;
      default:
        args = {"seismicity", a.string(), "--out", chance(0.5) ? target.string() : a.string()};
    }
    std::map<std::string, std::string> inputs = tree_bytes(b);
    for (const auto& f : own)
      if (fs::is_regular_file(a / f) && f != "bkquake.lock")
        inputs[(a / f).string()] = read_file((a / f).string());
    const auto before = tree_bytes(a);
    const auto r = test::run_bkquake_until(kNever, args, kGuard);
    // A lock is checked for only where none was left before the command.
    check(n, args, r, inputs, state == 0 ? a : fs::path());
    SCOPED_TRACE("case " + std::to_string(n) + " (state " + std::to_string(state) +
                 "): " + joined(args));
    if (state == 1) {  // nothing new in a live run's folder
      live.reset();
      for (const auto& [file, bytes] : tree_bytes(a))
        EXPECT_TRUE(before.count(file)) << file << " written beside a live run";
    }
    if (state == 3 && r.status == 0 && args[0] == "seismicity" && args[2] != "--out") {
      EXPECT_FALSE(fs::exists(a / (".seismicity.new-" + std::to_string(gone))));
      EXPECT_FALSE(fs::exists(a / "bkquake.lock"));
    }
    fs::remove_all(work);
    if (HasFailure()) return;
  }
}

// The readers' bounds: summary.json replaced by deeply nested, unbalanced or huge JSON (fit,
// merge, run --resume), catalog.h5 with bytes changed anywhere (fit, run --resume), inputs
// that fail to read (/proc/self/mem, a folder, a device, for scene, catalogue, histogram,
// friction table and sweep file) and sweeps too large to plan (long lists, products that
// overflow, many replicas). Each case ends as check() demands, within its limit.
TEST_F(Abuse, ReadersAndSweeps) {
  const int cases = static_cast<int>(env_number("BKQUAKE_ABUSE_CASES", 160)) / 2;
  auto run_into = [&](const std::string& name, const std::vector<std::string>& more) {
    std::vector<std::string> a = {"run", "--quiet", "--set", "model.blocks=20"};
    a.insert(a.end(), more.begin(), more.end());
    a.insert(a.end(), {"--out", tmp_.file(name)});
    return a;
  };
  ASSERT_EQ(
      test::run_bkquake(run_into("a", {"--set", "run.events=400", "--set", "run.seed=1"})).status,
      0);
  ASSERT_EQ(
      test::run_bkquake(run_into("b", {"--set", "run.events=400", "--set", "run.seed=2"})).status,
      0);
  ASSERT_EQ(
      test::run_and_signal_when(
          run_into("stopped", {"--set", "run.events=20000", "--set", "run.checkpoint_events=200"}),
          [&] { return fs::exists(tmp_.file("stopped/checkpoint.prev.bin")); }, SIGTERM),
      143);
  const bool h5 =
      test::run_bkquake(run_into("h5", {"--set", "run.events=400", "--set", "output.catalog=hdf5"}))
          .status == 0;
  if (h5) {
    ASSERT_EQ(
        test::run_and_signal_when(
            run_into("h5stopped", {"--set", "run.events=20000", "--set",
                                   "run.checkpoint_events=200", "--set", "output.catalog=hdf5"}),
            [&] { return fs::exists(tmp_.file("h5stopped/checkpoint.prev.bin")); }, SIGTERM),
        143);
  }

  auto damaged_json = [&]() -> std::string {
    const std::size_t depth = 1 + pick(200000);
    switch (pick(5)) {
      case 0:  // nested objects, closed
        return [&] {
          std::string t;
          for (std::size_t k = 0; k < depth; ++k) t += "{\"a\":";
          return t + "1" + std::string(depth, '}');
        }();
      case 1:  // nested arrays, never closed
        return "{\"events\": " + std::string(depth, '[');
      case 2:  // a long string
        return "{\"status\": \"" + std::string(depth * 10, 'x') + "\"}";
      case 3: {  // bracket soup
        std::string t = "{";
        for (std::size_t k = 0; k < depth % 5000; ++k) t += "[{\"\":,]}"[pick(8)];
        return t;
      }
      default:  // a valid summary nested inside a deep value
        return "{\"x\": " + std::string(depth, '[') + std::string(depth, ']') +
               ", \"events\": 400, \"status\": \"finished\"}";
    }
  };
  for (int n = 0; n < cases; ++n) {
    const fs::path work = tmp_.path() / ("r" + std::to_string(n));
    fs::create_directories(work);
    std::vector<std::string> args;
    std::map<std::string, std::string> inputs;
    fs::path out;
    const std::size_t kind = pick(h5 ? 4 : 3);
    if (kind == 0) {  // damaged JSON
      const std::string folder = chance(0.5) ? "b" : "stopped";
      fs::copy(tmp_.file(folder), work / folder, fs::copy_options::recursive);
      std::ofstream(work / folder / "summary.json", std::ios::binary | std::ios::trunc)
          << damaged_json();
      if (folder == "stopped") {
        args = {"run",     (work / "stopped" / "scene.ini").string(),
                "--quiet", "--resume",
                "--out",   (work / "stopped").string()};
        out = work / "stopped";
      } else if (chance(0.5)) {
        args = {"fit", (work / "b" / "catalog.csv").string()};
        inputs = tree_bytes(work);
      } else {
        fs::copy(tmp_.file("a"), work / "a", fs::copy_options::recursive);
        args = {"merge", (work / "a").string(), (work / "b").string(), "--out",
                (work / "m").string()};
        inputs = tree_bytes(work);
        out = work / "m";
      }
    } else if (kind == 1) {  // an input that fails to read
      static const std::vector<std::string> bad = {"/proc/self/mem", "/", "/dev/zero", "/dev/null",
                                                   "/nonexistent/x"};
      const std::string path = bad[pick(bad.size())];
      switch (pick(5)) {
        case 0:
          args = {"run", path, "--quiet", "--out", (work / "o").string()};
          out = work / "o";
          break;
        case 1:
          args = {"fit", path};
          break;
        case 2:
          args = {"run",   "--quiet",
                  "--set", "friction.law=table",
                  "--set", "friction.table=" + path,
                  "--out", (work / "o").string()};
          out = work / "o";
          break;
        case 3:
          args = {"sweep", path, "--out", (work / "o").string()};
          break;
        default:  // histogram.csv of a run to merge
          fs::copy(tmp_.file("a"), work / "a", fs::copy_options::recursive);
          fs::copy(tmp_.file("b"), work / "b", fs::copy_options::recursive);
          fs::remove(work / "b" / "histogram.csv");
          if (path == "/")
            fs::create_directory(work / "b" / "histogram.csv");
          else
            fs::create_symlink(path, work / "b" / "histogram.csv");
          args = {"merge", (work / "a").string(), (work / "b").string(), "--out",
                  (work / "m").string()};
          out = work / "m";
      }
    } else if (kind == 2) {  // a sweep too large to plan
      std::string ini =
          "[sweep]\nreplicas = " + std::to_string(1 + pick(chance(0.3) ? 100000 : 3)) +
          "\n[vary]\n";
      const char* keys[] = {"friction.alpha", "friction.sigma", "model.l", "drive.speed"};
      // One list longer than a sweep may be, or a product of 2-4 lists of 20 000 and more
      // (at least 4e8 points): always beyond the bound, never run.
      const bool one = chance(0.2);
      const int nkeys = one ? 1 : 2 + static_cast<int>(pick(3));
      for (int k = 0; k < nkeys; ++k)
        ini += std::string(keys[k]) + " = " + (k == 1 ? "0.001" : "1") + ":" +
               (k == 1 ? "0.5" : "3") + ":" +
               std::to_string(one ? 100001 + pick(900000) : 20000 + pick(1000000)) + "\n";
      ini += "[set]\nrun.events = 10\nmodel.blocks = 5\n";
      const std::string file = (work / "huge.ini").string();
      std::ofstream(file, std::ios::binary) << ini;
      args = {"sweep", file, "--out", (work / "o").string()};
      inputs = tree_bytes(file);
    } else {  // catalog.h5 with bytes changed
      const std::string folder = chance(0.5) ? "h5" : "h5stopped";
      fs::copy(tmp_.file(folder), work / folder, fs::copy_options::recursive);
      const fs::path victim = work / folder / "catalog.h5";
      std::string bytes = read_file(victim.string());
      for (int k = 0, m = 1 + static_cast<int>(pick(8)); k < m; ++k) {
        const std::size_t at =
            chance(0.6) ? pick(std::min<std::size_t>(bytes.size(), 4096)) : pick(bytes.size());
        bytes[at] = static_cast<char>(pick(256));
      }
      std::ofstream(victim, std::ios::binary | std::ios::trunc) << bytes;
      if (folder == "h5stopped") {
        args = {"run",     (work / folder / "scene.ini").string(),
                "--quiet", "--resume",
                "--out",   (work / folder).string()};
        out = work / folder;
      } else {
        args = {"fit", victim.string()};
        inputs = tree_bytes(work);
      }
    }
    // Run to its end (a resume of a damaged folder is refused or finishes: stopping it at
    // once would race its checks).
    const auto r = test::run_bkquake_until(kNever, args, kGuard);
    check(n, args, r, inputs, out);
    if (kind == 1 || kind == 2) {
      SCOPED_TRACE("case " + std::to_string(n) + ": " + joined(args));
      EXPECT_EQ(r.status, 2) << r.err;  // every one of these is refused
    }
    fs::remove_all(work);
    if (HasFailure()) return;
  }
}

// Links, devices and wide stencils (fourth round): run --force and --resume into folders
// whose files are links into another run (which must keep every byte: a link is replaced or
// refused, never written through); the Python readers on devices, FIFOs and garbage, direct
// or through a link in a run folder (a ValueError with a printable message, never a hang);
// wide coupling stencils, beyond the cost bound (refused at once) or below it (stopped by
// SIGTERM, which must end them within the guard, the lock released).
TEST_F(Abuse, LinksDevicesAndWideStencils) {
  const int cases = static_cast<int>(env_number("BKQUAKE_ABUSE_CASES", 160)) / 8;
  auto run_into = [&](const std::string& name, const std::vector<std::string>& more) {
    std::vector<std::string> a = {"run", "--quiet", "--set", "model.blocks=20"};
    a.insert(a.end(), more.begin(), more.end());
    a.insert(a.end(), {"--out", tmp_.file(name)});
    return a;
  };
  ASSERT_EQ(test::run_bkquake(
                run_into("victim", {"--set", "run.events=400", "--set", "output.event_slip=0"}))
                .status,
            0);
  ASSERT_EQ(
      test::run_and_signal_when(
          run_into("stopped", {"--set", "run.events=20000", "--set", "run.checkpoint_events=200"}),
          [&] { return fs::exists(tmp_.file("stopped/checkpoint.prev.bin")); }, SIGTERM),
      143);
  const fs::path python_dir = fs::path(BKQUAKE_BINARY).parent_path() / "python";
  const bool python =
      fs::exists(python_dir / "bkquake" / "__init__.py") && fs::exists("/usr/bin/python3");
  const fs::path victim = tmp_.path() / "victim";
  const std::vector<std::string> linkable = {
      "catalog.csv",    "histogram.csv",      "summary.json",  "scene.ini",    "event_slip.csv",
      "timeseries.csv", "energy.csv",         "blocks.csv",    "segments.csv", "catalog.h5",
      "bkquake.lock",   "energy_samples.csv", "checkpoint.bin"};
  for (int n = 0; n < cases; ++n) {
    const fs::path work = tmp_.path() / ("l" + std::to_string(n));
    fs::create_directories(work);
    std::vector<std::string> args;
    std::map<std::string, std::string> inputs;
    fs::path out;
    double stop_after = 0;  // > 0: SIGTERM after this many seconds (a state is not at hand)
    const std::size_t kind = pick(python ? 3 : 2);
    if (kind == 0) {  // links among a run's files
      const bool resume = chance(0.3);
      out = work / "o";
      if (resume)
        fs::copy(tmp_.file("stopped"), out, fs::copy_options::recursive);
      else
        fs::create_directories(out);
      for (int k = 0, m = 1 + static_cast<int>(pick(4)); k < m; ++k) {
        const std::string name = linkable[pick(linkable.size())];
        fs::remove(out / name);
        const fs::path target = victim / (fs::exists(victim / name) ? name : "catalog.csv");
        if (chance(0.7))
          fs::create_symlink(target, out / name);
        else
          fs::create_hard_link(target, out / name);
      }
      if (resume) {
        args = {"run",     (tmp_.path() / "stopped" / "scene.ini").string(),
                "--quiet", "--resume",
                "--out",   out.string()};
      } else {
        static const std::vector<std::vector<std::string>> scenes = {
            {"--set", "run.events=300", "--set", "output.event_slip=0"},
            {"--set", "run.events=300", "--set", "output.catalog=hdf5"},
            {"--set", "drive.mode=continuous", "--set", "run.duration=300", "--set",
             "output.blocks=true", "--set", "output.energy=true", "--set",
             "output.energy_window=50"}};
        args = {"run", "--quiet", "--set", "model.blocks=20"};
        const auto& more = scenes[pick(scenes.size())];
        args.insert(args.end(), more.begin(), more.end());
        args.insert(args.end(), {"--force", "--out", out.string()});
      }
      inputs = tree_bytes(victim);
    } else if (kind == 1) {  // wide stencils
      const bool lattice = chance(0.3);
      // Costs log-uniform from 1e6 to 1e10 terms: about half beyond the bound.
      const double terms = std::exp(uniform(std::log(1e6), std::log(1e10)));
      std::int64_t range = 0, blocks = 0, rows = 1;
      if (lattice) {
        range = 2 + static_cast<std::int64_t>(pick(60));
        const double sites = terms / (3.14 * static_cast<double>(range * range));
        rows = std::max<std::int64_t>(range + 1, static_cast<std::int64_t>(std::sqrt(sites)));
        blocks = std::max<std::int64_t>(range + 1, static_cast<std::int64_t>(sites) / rows);
      } else {
        range = 1 + static_cast<std::int64_t>(std::exp(uniform(0, std::log(50000.0))));
        blocks =
            std::max<std::int64_t>(2 * range + 1, static_cast<std::int64_t>(terms / (2.0 * range)));
      }
      blocks = std::min<std::int64_t>(blocks, 10'000'000);
      rows = std::min<std::int64_t>(rows, 10'000'000 / std::max<std::int64_t>(blocks, 1));
      out = work / "o";
      args = {"run",   "--quiet",
              "--set", std::string("model.coupling=") + (chance(0.5) ? "range" : "power"),
              "--set", "model.range=" + std::to_string(range),
              "--set", "model.blocks=" + std::to_string(blocks),
              "--set", "model.rows=" + std::to_string(std::max<std::int64_t>(rows, 1)),
              "--set", "run.events=200",
              "--out", out.string()};
      stop_after = uniform(0.2, 1.5);
    } else {  // the Python readers on devices, FIFOs and garbage
      static const std::vector<std::string> devices = {"/dev/zero", "/dev/urandom", "/dev/null"};
      std::string path;
      switch (pick(3)) {
        case 0:
          path = devices[pick(devices.size())];
          break;
        case 1:
          path = (work / "fifo").string();
          ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
          break;
        default: {
          path = (work / "garbage").string();
          std::string bytes(1 + pick(5000), '\0');
          for (char& c : bytes) c = static_cast<char>(pick(256));
          std::ofstream(path, std::ios::binary) << bytes;
        }
      }
      // Read directly, or as a file of a run folder (a link to it there).
      static const std::vector<std::pair<std::string, std::string>> readers = {
          {"", "bkquake.read_catalog(p)"},
          {"catalog.csv", "bkquake.load(d).columns"},
          {"histogram.csv", "bkquake.load(d).histogram"},
          {"timeseries.csv", "bkquake.load(d).table('timeseries.csv')"},
          {"summary.json", "bkquake.load(d).summary"},
          {"scene.ini", "bkquake.load(d).scene"}};
      const auto& [file, call] = readers[pick(readers.size())];
      const fs::path d = work / "run";
      fs::create_directories(d);
      if (!file.empty()) fs::create_symlink(path, d / file);
      const std::string script =
          "import sys, warnings\n"
          "warnings.simplefilter('ignore')\n"
          "import bkquake\n"
          "p, d = sys.argv[1], sys.argv[2]\n"
          "try:\n"
          "    " +
          call +
          "\n"
          "except ValueError as e:\n"
          "    m = str(e)\n"
          "    ok = m and not any(ord(c) < 32 or 127 <= ord(c) < 160 for c in m)\n"
          "    sys.exit(0 if ok else 5)\n"
          "except (OSError, UnicodeDecodeError) as e:\n"
          "    sys.exit(0 if str(e) else 6)\n";
      args = {"python3", "-c", script, path, d.string()};
      const auto r = test::run_process(
          "/usr/bin/env",
          {"PYTHONPATH=" + python_dir.string(), "/usr/bin/python3", "-c", script, path, d.string()},
          "", 60, 5);
      SCOPED_TRACE("case " + std::to_string(n) + ": " + call + " on " + path);
      EXPECT_FALSE(r.timed_out) << "a Python reader hung";
      EXPECT_EQ(r.status, 0) << r.err;
      fs::remove_all(work);
      if (HasFailure()) return;
      continue;
    }
    const auto r = stop_after > 0 ? test::run_process(BKQUAKE_BINARY, args, "", stop_after, kGuard)
                                  : test::run_bkquake_until(kNever, args, kGuard);
    check(n, args, r, inputs, out);
    if (kind == 0) {
      SCOPED_TRACE("case " + std::to_string(n) + ": " + joined(args));
      // The link's target kept every byte (check() above); the files every run writes are
      // the run's own (a link of a name the scene does not write stays, untouched).
      if (r.status == 0)
        for (const char* name : {"scene.ini", "summary.json"}) {
          EXPECT_FALSE(fs::is_symlink(out / name)) << name;
        }
    }
    fs::remove_all(work);
    if (HasFailure()) return;
  }
}

}  // namespace
}  // namespace bkq
