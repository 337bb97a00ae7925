// Reliability, third round: each test reproduces one defect found by hand abuse (a crash on
// deeply nested JSON, read errors taken for empty files, a hang on a damaged HDF5
// catalogue, ...) and asserts the refusal that replaces it: exit 2, one line naming the file
// and what failed, no lock left behind, no input changed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "io/checkpoint.hpp"

namespace bkq {
namespace {
using test::expect_refused;
using test::read_file;
using test::run_bkquake;
using test::run_bkquake_for;
using test::tree_bytes;
namespace fs = std::filesystem;

const std::string kThesis = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/thesis.ini";

// A small finished event run in `dir`.
void small_run(const std::string& dir, const std::vector<std::string>& more = {}) {
  std::vector<std::string> a = {"run",   "--quiet",        "--set", "model.blocks=10",
                                "--set", "run.events=300", "--set", "run.transient_events=10"};
  a.insert(a.end(), more.begin(), more.end());
  a.insert(a.end(), {"--out", dir});
  const auto r = run_bkquake(a);
  ASSERT_EQ(r.status, 0) << r.err;
}

// A JSON object nested `depth` levels deep: {"a":{"a":...1...}}.
std::string deep_json(int depth) {
  std::string s;
  s.reserve(static_cast<std::size_t>(depth) * 6 + 1);
  for (int k = 0; k < depth; ++k) s += "{\"a\":";
  s += "1";
  s += std::string(static_cast<std::size_t>(depth), '}');
  return s;
}

// Every reader of summary.json bounds its nesting: fit, run --resume and merge refuse a
// summary nested 100 000 levels deep (which overflowed the stack) and leave no lock.
TEST(Reliability, DeeplyNestedSummaryIsRefused) {
  test::TempDir tmp;
  const std::string r = tmp.file("r"), b = tmp.file("b");
  small_run(r);
  small_run(b, {"--set", "run.seed=2"});
  std::ofstream(r + "/summary.json", std::ios::binary | std::ios::trunc) << deep_json(100000);
  const auto before = tree_bytes(r);
  // fit does without a summary that does not read, and says so.
  const auto fit = run_bkquake({"fit", r + "/catalog.csv"});
  EXPECT_EQ(fit.status, 0) << fit.err;
  EXPECT_NE(fit.err.find("warning: " + r + "/summary.json: not a JSON object: nested deeper"),
            std::string::npos)
      << fit.err;
  expect_refused(run_bkquake({"run", r + "/scene.ini", "--quiet", "--resume", "--out", r}),
                 {"summary.json", "nested deeper"});
  expect_refused(run_bkquake({"merge", r, b, "--out", tmp.file("m")}),
                 {"summary.json", "nested deeper"});
  EXPECT_EQ(tree_bytes(r), before);
  EXPECT_FALSE(fs::exists(r + "/bkquake.lock"));
  EXPECT_FALSE(fs::exists(tmp.file("m") + "/bkquake.lock"));
}

// A read error is not an empty file: a scene, catalogue or friction table that fails to read
// (EIO from /proc/self/mem) and a folder given as a file are refused, naming what failed.
TEST(Reliability, ReadErrorsAreNotEmptyFiles) {
  test::TempDir tmp;
  const std::string out = tmp.file("x");
  expect_refused(run_bkquake({"run", "/proc/self/mem", "--quiet", "--out", out}),
                 {"cannot read scene file '/proc/self/mem'"});
  EXPECT_FALSE(fs::exists(out + "/catalog.csv"));
  expect_refused(run_bkquake({"fit", "/proc/self/mem"}),
                 {"cannot read catalogue '/proc/self/mem'"});
  // A folder is a run folder to fit: one without anything to fit says so; a folder where
  // the catalogue should be is a read error, not an empty file.
  expect_refused(run_bkquake({"fit", tmp.path().string()}), {"holds no catalog.csv"});
  fs::create_directory(tmp.file("d"));
  fs::create_directory(tmp.file("d") + "/catalog.csv");
  expect_refused(run_bkquake({"fit", tmp.file("d")}), {"catalog.csv", "Is a directory"});
  expect_refused(run_bkquake({"run", "--quiet", "--set", "friction.law=table", "--set",
                              "friction.table=/proc/self/mem", "--out", tmp.file("t")}),
                 {"/proc/self/mem"});
  expect_refused(run_bkquake({"run", "--quiet", "--set", "friction.law=table", "--set",
                              "friction.table=" + tmp.path().string(), "--out", tmp.file("t2")}),
                 {"Is a directory"});
}

// An interrupted event run in `dir`, stopped by SIGTERM once its second checkpoint is in
// (no transient, so the catalogue holds at least 200 rows by then).
void interrupted_run(const std::string& dir, const std::vector<std::string>& more = {}) {
  std::vector<std::string> a = {"run",   "--quiet",
                                "--set", "model.blocks=20",
                                "--set", "run.events=100000000",
                                "--set", "run.transient_events=0",
                                "--set", "run.checkpoint_events=200"};
  a.insert(a.end(), more.begin(), more.end());
  a.insert(a.end(), {"--out", dir});
  ASSERT_EQ(test::run_and_signal_when(
                a, [&] { return fs::exists(dir + "/checkpoint.prev.bin"); }, SIGTERM),
            143);
}

bool hdf5_built() {
  test::TempDir tmp;
  const auto r = run_bkquake({"run", "--quiet", "--set", "run.events=5", "--set",
                              "output.catalog=hdf5", "--out", tmp.file("probe")});
  return r.status == 0;
}

// A damaged HDF5 catalogue (one byte of its superblock changed) is refused with one line,
// by fit and by --resume, instead of waiting in HDF5's metadata retries; the resume leaves
// the folder as it was and no lock. (The limit only turns a hang into a failure.)
TEST(Reliability, DamagedHdf5CatalogIsRefusedNotAwaited) {
  if (!hdf5_built()) GTEST_SKIP() << "built without HDF5";
  test::TempDir tmp;
  const std::string r = tmp.file("r");
  small_run(r, {"--set", "output.catalog=hdf5"});
  const std::string good = read_file(r + "/catalog.h5");
  for (const std::size_t at : {12u, 20u, 33u, 47u}) {
    SCOPED_TRACE("byte " + std::to_string(at));
    std::string bad = good;
    bad[at] = bad[at] == '\x5a' ? '\x5b' : '\x5a';
    const std::string x = tmp.write("x.h5", bad);
    const auto fit = run_bkquake_for(120, {"fit", x});
    ASSERT_FALSE(fit.timed_out) << "fit hangs on a damaged HDF5 file";
    expect_refused(fit, {x});
  }
  const std::string s = tmp.file("s");
  interrupted_run(s, {"--set", "output.catalog=hdf5"});
  std::string bad = read_file(s + "/catalog.h5");
  bad[20] = bad[20] == '\x5a' ? '\x5b' : '\x5a';
  std::ofstream(s + "/catalog.h5", std::ios::binary | std::ios::trunc) << bad;
  const auto before = tree_bytes(s);
  const auto resume =
      run_bkquake_for(120, {"run", s + "/scene.ini", "--quiet", "--resume", "--out", s});
  ASSERT_FALSE(resume.timed_out) << "--resume hangs on a damaged HDF5 file";
  expect_refused(resume, {"catalog.h5"});
  EXPECT_EQ(tree_bytes(s), before);
}

// A signal that arrives while a command holds a folder's lock outside a run's own handlers
// (here: setting up a chain of 2e6 blocks) ends the command by that signal and removes the
// lock; the next --resume is not told the folder is in use. (A FIFO in the checkpoint's
// place, which once blocked the resume there, is now refused at once: a run's files must be
// plain files, io/output.hpp refuse_link.)
TEST(Reliability, SignalOutsideTheRunReleasesTheLock) {
  test::TempDir tmp;
  const std::string s = tmp.file("s");
  interrupted_run(s);
  fs::remove(s + "/checkpoint.bin");
  ASSERT_EQ(::mkfifo((s + "/checkpoint.bin").c_str(), 0644), 0);
  expect_refused(run_bkquake_for(20, {"run", s + "/scene.ini", "--quiet", "--resume", "--out", s}),
                 {s + "/checkpoint.bin", "is a FIFO"});
  EXPECT_FALSE(fs::exists(s + "/bkquake.lock"));
  const std::string big = tmp.file("big");
  const int status = test::run_and_signal_when(
      {"run", "--quiet", "--set", "model.blocks=2000000", "--set", "run.events=10", "--out", big},
      [&] { return fs::exists(big + "/bkquake.lock"); }, SIGTERM);
  EXPECT_EQ(status, 143);
  EXPECT_FALSE(fs::exists(big + "/bkquake.lock")) << "the lock outlived its holder";
}

// A sweep whose product of lists is huge is refused before anything is planned, naming the
// number of points; it does not run out of memory.
TEST(Reliability, HugeSweepIsRefusedWithItsSize) {
  test::TempDir tmp;
  const std::string sweep = tmp.write("huge.ini",
                                      "[vary]\nfriction.alpha = 1:3:1000\n"
                                      "friction.sigma = 0.001:0.1:1000\n"
                                      "model.l = 1:20:1000\n[set]\nrun.events = 10\n");
  const auto r = run_bkquake({"sweep", sweep, "--out", tmp.file("out")});
  expect_refused(r, {"the sweep has at least 1e+06 points", "at most 100000"});
  EXPECT_FALSE(fs::exists(tmp.file("out") + "/sweep.ini"));
  // Points x replicas is bounded too.
  const std::string many = tmp.write("many.ini",
                                     "[sweep]\nreplicas = 100\n[vary]\n"
                                     "friction.alpha = 1:3:20000\n[set]\nrun.events = 10\n");
  expect_refused(run_bkquake({"sweep", many, "--out", tmp.file("out2")}),
                 {"2000000 runs", "at most 1000000"});
}

// Running out of memory (here under a 400 MB address-space limit, a chain of 10^7 blocks)
// is one error line and exit 2, not an internal error; the lock goes with the process.
TEST(Reliability, OutOfMemoryIsARefusal) {
  test::TempDir tmp;
  const std::string out = tmp.file("big");
  const auto r = test::run_process(
      "/usr/bin/prlimit", {"--as=400000000", BKQUAKE_BINARY, "run", "--quiet", "--set",
                           "model.blocks=10000000", "--set", "run.events=10", "--out", out});
  expect_refused(r, {"out of memory"});
  EXPECT_FALSE(fs::exists(out + "/bkquake.lock"));
}

// A catalogue cut inside its last field still parses (the field reads as another number):
// fit refuses a last row without its line end, and a run's catalogue whose row count differs
// from its summary's events, naming both counts.
TEST(Reliability, TruncatedCatalogIsRefused) {
  test::TempDir tmp;
  const std::string r = tmp.file("r");
  small_run(r);
  const std::string whole = read_file(r + "/catalog.csv");
  ASSERT_EQ(whole.back(), '\n');
  const std::string cut = whole.substr(0, whole.size() - 3);  // inside the last field
  std::ofstream(r + "/catalog.csv", std::ios::binary | std::ios::trunc) << cut;
  expect_refused(run_bkquake({"fit", r + "/catalog.csv"}), {"has no line end", "cut short"});
  // Whole rows, but fewer than the run wrote.
  const std::string fewer = whole.substr(0, whole.rfind('\n', whole.size() - 2) + 1);
  std::ofstream(r + "/catalog.csv", std::ios::binary | std::ios::trunc) << fewer;
  expect_refused(run_bkquake({"fit", r + "/catalog.csv"}), {"holds 299 rows", "counts 300 events"});
  // The same file outside its run folder is fitted as it is.
  const std::string alone = tmp.write("alone.csv", fewer);
  EXPECT_EQ(run_bkquake({"fit", alone}).status, 0);
}

// merge compares each run's scene.ini with the scene its summary.json was written for: an
// emptied or truncated scene.ini (whose missing keys would take their defaults and let runs
// of other physics merge) is refused.
TEST(Reliability, MergeRefusesAScenethatIsNotItsRuns) {
  test::TempDir tmp;
  const std::string a = tmp.file("a"), b = tmp.file("b");
  small_run(a, {"--set", "friction.alpha=1"});
  small_run(b, {"--set", "friction.alpha=1", "--set", "run.seed=2"});
  const std::string ini = read_file(b + "/scene.ini");
  for (const std::string& damaged : {std::string(), ini.substr(0, ini.find("alpha"))}) {
    std::ofstream(b + "/scene.ini", std::ios::binary | std::ios::trunc) << damaged;
    expect_refused(run_bkquake({"merge", a, b, "--out", tmp.file("m")}),
                   {b + "/scene.ini", "is not the scene of", "scene_hash"});
    EXPECT_FALSE(fs::exists(tmp.file("m")));
  }
  std::ofstream(b + "/scene.ini", std::ios::binary | std::ios::trunc) << ini;
  EXPECT_EQ(run_bkquake({"merge", a, b, "--out", tmp.file("m")}).status, 0);
}

// A checkpoint edited with its checksum redone is checked field by field before a resume
// changes anything: a negative transient count, a block at 1e300, a histogram bin far out
// of range are refused naming the field, and the folder stays as it was. A checkpoint that
// is a folder is refused as well (it was an internal error).
TEST(Reliability, EditedCheckpointIsRefusedAndChangesNothing) {
  test::TempDir tmp;
  const std::string s = tmp.file("s");
  interrupted_run(s);
  const std::string ckpt = s + "/checkpoint.bin";
  const std::string good = read_file(ckpt);
  const auto resume =
      std::vector<std::string>{"run", s + "/scene.ini", "--quiet", "--resume", "--out", s};
  struct Edit {
    const char* name;
    void (*apply)(Checkpoint&);
    const char* field;
  };
  const Edit edits[] = {
      {"negative transient", [](Checkpoint& c) { c.progress.transient_done = -1; },
       "transient_done = -1"},
      {"block at 1e300", [](Checkpoint& c) { c.engine.state.w[3] = 1e300; },
       "block position[3] = 1e+300"},
      {"huge first bin", [](Checkpoint& c) { c.histogram.first_bin = 1LL << 60; },
       "histogram first_bin"},
  };
  for (const Edit& e : edits) {
    SCOPED_TRACE(e.name);
    Checkpoint c = decode_checkpoint(good, ckpt);
    e.apply(c);
    std::ofstream(ckpt, std::ios::binary | std::ios::trunc) << encode_checkpoint(c);
    const auto before = tree_bytes(s);
    expect_refused(run_bkquake(resume), {"checkpoint.bin' is invalid", e.field});
    EXPECT_EQ(tree_bytes(s), before) << "a refused resume changed the folder";
  }
  fs::remove(ckpt);
  fs::create_directory(ckpt);
  expect_refused(run_bkquake(resume), {"checkpoint.bin", "Is a directory"});
  EXPECT_NO_THROW(decode_checkpoint(good, ckpt)) << "the checkpoint as written passes";
}

// Offset in an uncompressed catalog.h5 of row `row` (1-based event number), found by its
// event numbers: rows are 12 cells of 8 bytes, the event number first.
std::size_t h5_row_offset(const std::string& bytes, std::int64_t row) {
  auto cell = [](std::int64_t v) { return std::string(reinterpret_cast<const char*>(&v), 8); };
  const std::string first = cell(row);
  for (std::size_t at = bytes.find(first); at != std::string::npos; at = bytes.find(first, at + 1))
    if (at + 96 + 8 <= bytes.size() && bytes.compare(at + 96, 8, cell(row + 1)) == 0) return at;
  return std::string::npos;
}

// HDF5 resume checks the rows before its checkpoint as the CSV resume does: eight bytes of a
// row before the checkpoint overwritten (a load) are refused, and the folder stays as it was.
TEST(Reliability, Hdf5ResumeChecksTheRowsBeforeTheCheckpoint) {
  if (!hdf5_built()) GTEST_SKIP() << "built without HDF5";
  test::TempDir tmp;
  const std::string s = tmp.file("s");
  interrupted_run(s, {"--set", "output.catalog=hdf5"});
  std::string bytes = read_file(s + "/catalog.h5");
  const std::size_t row = h5_row_offset(bytes, 5);
  ASSERT_NE(row, std::string::npos) << "row 5 not found in catalog.h5";
  const double other = 12345.678;
  bytes.replace(row + 8, 8, std::string(reinterpret_cast<const char*>(&other), 8));
  std::ofstream(s + "/catalog.h5", std::ios::binary | std::ios::trunc) << bytes;
  const auto before = tree_bytes(s);
  expect_refused(run_bkquake({"run", s + "/scene.ini", "--quiet", "--resume", "--out", s}),
                 {"catalog.h5", "are not those the checkpoint saw"});
  EXPECT_EQ(tree_bytes(s), before);
}

// One folder rule: no command writes over one of its inputs or a run's own files; a command
// that writes a folder wants a new or empty one, or --force.
TEST(Reliability, NoCommandWritesOverItsInputsOrARunsFiles) {
  test::TempDir tmp;
  const std::string r = tmp.file("r");
  small_run(r);
  const std::string catalog = tmp.write("C.csv", read_file(r + "/catalog.csv"));
  const auto before = tree_bytes(tmp.path());
  expect_refused(run_bkquake({"fit", catalog, "--json", catalog}), {"is its input"});
  expect_refused(run_bkquake({"fit", catalog, "--json", r + "/summary.json"}),
                 {"is the file summary.json of the run in"});
  EXPECT_EQ(tree_bytes(tmp.path()), before);
  // Every file a run writes is its own: the slips of output.event_slip, the energy samples
  // of output.energy and the final state were missing from the list and could be replaced.
  const std::string e = tmp.file("e");
  small_run(e, {"--set", "output.event_slip=-2"});
  ASSERT_TRUE(fs::exists(e + "/event_slip.csv"));
  const auto e_files = tree_bytes(e);
  for (const char* own : {"event_slip.csv", "checkpoint.final.bin", "energy_samples.csv"})
    expect_refused(run_bkquake({"fit", e + "/catalog.csv", "--json", e + "/" + own}),
                   {std::string("is the file ") + own + " of the run in"});
  EXPECT_EQ(tree_bytes(e), e_files);
  // A derived output into the run folder is fine, and takes (and returns) its lock.
  EXPECT_EQ(run_bkquake({"fit", r + "/catalog.csv", "--json", r + "/fit.json"}).status, 0);
  EXPECT_TRUE(fs::exists(r + "/fit.json"));
  EXPECT_FALSE(fs::exists(r + "/bkquake.lock"));

  const std::string c = tmp.file("c");
  ASSERT_EQ(run_bkquake({"run", "--quiet", "--set", "drive.mode=continuous", "--set",
                         "model.blocks=5", "--set", "run.duration=20", "--out", c})
                .status,
            0);
  const auto series = read_file(c + "/timeseries.csv");
  expect_refused(run_bkquake({"spectrum", c, "--out", c + "/timeseries.csv"}), {"is its input"});
  EXPECT_EQ(read_file(c + "/timeseries.csv"), series);

  // stability writes a folder: not over a run's, and not over its own earlier one without
  // --force.
  const auto run_files = tree_bytes(r);
  expect_refused(run_bkquake({"stability", kThesis, "--set", "model.blocks=5", "--out", r}),
                 {"already holds a finished run"});
  EXPECT_EQ(tree_bytes(r), run_files);
  const std::string st = tmp.file("st");
  ASSERT_EQ(run_bkquake({"stability", kThesis, "--set", "model.blocks=5", "--out", st}).status, 0);
  expect_refused(run_bkquake({"stability", kThesis, "--set", "model.blocks=5", "--out", st}),
                 {"already holds files", "--force"});
  EXPECT_EQ(
      run_bkquake({"stability", kThesis, "--set", "model.blocks=5", "--out", st, "--force"}).status,
      0);

  // sweep: not into a folder holding other files without --force.
  const std::string sweep = tmp.write("s.ini",
                                      "[vary]\nrun.seed = 1, 2\n[set]\nrun.events = 20\n"
                                      "model.blocks = 5\nrun.transient_events = 5\n");
  expect_refused(run_bkquake({"sweep", sweep, "--out", r}), {"already holds files", "--force"});
  EXPECT_EQ(tree_bytes(r), run_files);
  const std::string sw = tmp.file("sw");
  ASSERT_EQ(run_bkquake({"sweep", sweep, "--out", sw}).status, 0);
  expect_refused(run_bkquake({"sweep", sweep, "--out", sw}), {"holds a sweep", "--force"});
  EXPECT_EQ(run_bkquake({"sweep", sweep, "--out", sw, "--force"}).status, 0);

  // friction-study writes a folder too: not over a run's (refused before any run starts),
  // and not over its own earlier study without --force.
  const std::vector<std::string> study = {"friction-study",
                                          "--configs",
                                          "1dof",
                                          "--segment",
                                          "1",
                                          "--quiet",
                                          "--scenes",
                                          std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/brake"};
  auto with_out = [&](const std::string& out, bool force) {
    std::vector<std::string> a = study;
    a.insert(a.end(), {"--out", out});
    if (force) a.push_back("--force");
    return a;
  };
  expect_refused(run_bkquake(with_out(r, false)), {"already holds a finished run"});
  EXPECT_EQ(tree_bytes(r), run_files);
  const std::string fs_out = tmp.file("study");
  ASSERT_EQ(run_bkquake(with_out(fs_out, false)).status, 0);
  ASSERT_TRUE(fs::exists(fs_out + "/friction_study.csv"));
  EXPECT_FALSE(fs::exists(fs_out + "/bkquake.lock"));
  expect_refused(run_bkquake(with_out(fs_out, false)), {"already holds files", "--force"});
  EXPECT_EQ(run_bkquake(with_out(fs_out, true)).status, 0);
}

// Samples on the stated grid: with output.every = 0.5 and dt = 0.005 every time in
// timeseries.csv is k * 0.5 exactly (they drifted by the rounding of the summed steps,
// to spacings such as 0.495 and 0.505 in long runs).
TEST(Reliability, SampleTimesLieOnTheStatedGrid) {
  test::TempDir tmp;
  const std::string c = tmp.file("c");
  ASSERT_EQ(run_bkquake({"run", "--quiet", "--set", "drive.mode=continuous", "--set",
                         "model.blocks=5", "--set", "integrator.dt=0.005", "--set",
                         "output.every=0.5", "--set", "run.duration=400", "--out", c})
                .status,
            0);
  std::istringstream in(read_file(c + "/timeseries.csv"));
  std::string line;
  std::getline(in, line);
  std::int64_t k = 0;
  for (; std::getline(in, line); ++k)
    ASSERT_EQ(std::stod(line.substr(0, line.find(','))), 0.5 * static_cast<double>(k))
        << "sample " << k << ": " << line;
  EXPECT_EQ(k, 801);
}

// A binary says which instruction set it was built for, so that a result can name the build
// it came from: the portable default x86-64-v3, native (-DBKQUAKE_NATIVE=ON) or default
// (the compiler's own baseline).
TEST(Reliability, VersionNamesTheBuildTarget) {
  const auto r = run_bkquake({"--version"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto at = r.out.find(", built for ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string target = r.out.substr(at + 12, r.out.find(')', at) - at - 12);
  EXPECT_TRUE(target == "x86-64-v3" || target == "native" || target == "default" ||
              target.rfind("x86-64", 0) == 0)
      << target;
}

// The revision a binary names is the source tree's at build time, not at the last configure:
// the header is rewritten at every build (src/core/version.cmake), so a build after a
// commit names that commit (./test.sh builds first; testing a build older than HEAD fails
// here, as it should). Skipped where the sources are not a git checkout.
TEST(Reliability, VersionNamesTheCommitItWasBuiltFrom) {
  const std::string command =
      std::string("git -C '") + BKQUAKE_SOURCE_DIR + "' rev-parse --short=12 HEAD 2>/dev/null";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[64] = {};
  const bool read = std::fgets(buffer, sizeof buffer, pipe) != nullptr;
  const int status = ::pclose(pipe);
  if (!read || status != 0) GTEST_SKIP() << "the sources are not a git checkout";
  std::string head(buffer);
  head.erase(head.find_last_not_of(" \n") + 1);
  ASSERT_EQ(head.size(), 12u) << head;
  const auto r = run_bkquake({"--version"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("git " + head), std::string::npos)
      << r.out << " does not name HEAD " << head
      << " (a build before the last commit names the commit before: rebuild, then test)";
}

// Messages that said something untrue or cut themselves short.
TEST(Reliability, MessagesSayWhatIsTrue) {
  test::TempDir tmp;
  // --resume without a checkpoint in a folder that holds a run: --force, not "without
  // --resume" (which would be refused too).
  const std::string r = tmp.file("r");
  small_run(r);
  fs::remove(r + "/summary.json");
  expect_refused(run_bkquake({"run", r + "/scene.ini", "--quiet", "--resume", "--out", r}),
                 {"no checkpoint", "use --force instead of --resume"});
  // A NUL byte in a scene value is named, and the message goes on to the file.
  const std::string nul = tmp.write("nul.ini", std::string("[friction]\nalpha = 2\0x\n", 23));
  expect_refused(run_bkquake({"run", nul, "--quiet", "--out", tmp.file("n")}),
                 {"friction.alpha", "NUL byte", "nul.ini"});
  // Sweep files: a mistyped [vary] key gets a suggestion, a missing scene the folder it was
  // looked for in.
  const std::string typo = tmp.write("typo.ini", "[vary]\nfriction.alpah = 1, 2\n");
  expect_refused(run_bkquake({"sweep", typo, "--out", tmp.file("s1")}),
                 {"did you mean 'friction.alpha'"});
  const std::string lost =
      tmp.write("lost.ini", "[sweep]\nscene = nowhere.ini\n[vary]\nfriction.alpha = 1, 2\n");
  expect_refused(run_bkquake({"sweep", lost, "--out", tmp.file("s2")}),
                 {"nowhere.ini", "read from the sweep file's folder '" + tmp.path().string()});
  // Help names scripts that exist; --dump-defaults says which laws event runs refuse.
  const auto help = run_bkquake({"friction-study", "--help"});
  EXPECT_EQ(help.out.find("plot_friction_study.py"), std::string::npos) << help.out;
  EXPECT_TRUE(fs::exists(std::string(BKQUAKE_SOURCE_DIR) + "/analysis/plot_brake.py"));
  EXPECT_NE(help.out.find("analysis/plot_brake.py"), std::string::npos) << help.out;
  EXPECT_NE(run_bkquake({"run", "--dump-defaults"}).out.find("event runs refuse it"),
            std::string::npos);
  // An error about a built-in default scene that --set made continuous does not call it
  // event-driven.
  const auto cont =
      run_bkquake({"run", "--quiet", "--set", "drive.mode=continuous", "--set",
                   "integrator.dt=0.01", "--set", "run.duration=1e14", "--out", tmp.file("c")});
  expect_refused(cont, {"run.duration = 1e+14", "(built-in default scene with --set overrides)"});
  EXPECT_EQ(cont.err.find("event-driven"), std::string::npos) << cont.err;
  // stability analyses an event-driven scene continuously driven: --set drive.speed is
  // accepted and used (it was refused, and the default speed used in silence).
  const std::string st = tmp.file("st");
  const auto stab = run_bkquake(
      {"stability", "--set", "model.blocks=5", "--set", "drive.speed=0.25", "--out", st});
  ASSERT_EQ(stab.status, 0) << stab.err;
  EXPECT_EQ(stab.out.find("\n0.01 "), std::string::npos) << stab.out;
  EXPECT_NE(stab.out.find("\n0.25 "), std::string::npos) << stab.out;
  EXPECT_NE(read_file(st + "/scene.ini").find("speed = 0.25"), std::string::npos);
  // ... and refuses what it cannot analyse instead of analysing another model: the OFC
  // automaton (it analysed a chain), an explicit event drive (the default speed again).
  expect_refused(run_bkquake({"stability", "--set", "model.kind=ofc", "--out", tmp.file("so")}),
                 {"stability: model.kind = ofc", "no steady sliding"});
  expect_refused(run_bkquake({"stability", "--set", "drive.mode=events", "--set",
                              "drive.speed=0.25", "--out", tmp.file("se")}),
                 {"drive.speed"});
  expect_refused(run_bkquake({"stability", "--set", "drive.mode=events", "--out", tmp.file("se2")}),
                 {"stability: drive.mode = events", "remove --set drive.mode=events"});
  EXPECT_FALSE(fs::exists(tmp.file("so")));
  // A brake run (a pad, continuously driven) says where its figures are, not a b line.
  const std::string brake = tmp.file("brake");
  const auto br =
      run_bkquake({"run", std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/brake/bkp.ini", "--set",
                   "model.blocks=5", "--set", "run.duration=20", "--set", "drive.step_interval=10",
                   "--out", brake});
  ASSERT_EQ(br.status, 0) << br.err;
  EXPECT_EQ(br.out.find("  b"), std::string::npos) << br.out;
  EXPECT_NE(br.out.find("2 speed segments: the pad's mean and amplitude in segments.csv"),
            std::string::npos)
      << br.out;
  // Its summary's reason for no b names the test that failed, not a KS tolerance.
  EXPECT_EQ(read_file(brake + "/summary.json").find("KS tolerance"), std::string::npos);
  // A catalogue whose run was killed (checkpoints, no summary) is fitted with a note.
  const std::string k = tmp.file("k");
  interrupted_run(k);
  fs::remove(k + "/summary.json");
  const auto fit = run_bkquake({"fit", k + "/catalog.csv"});
  EXPECT_EQ(fit.status, 0) << fit.err;
  EXPECT_NE(fit.out.find("note: an interrupted run (checkpoints beside it, no summary.json"),
            std::string::npos)
      << fit.out;
}

}  // namespace
}  // namespace bkq
