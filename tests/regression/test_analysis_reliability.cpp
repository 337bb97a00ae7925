// Reliability, fourth round: the analysis commands (fit, seismicity, merge) on folders that
// are in use, were left by a killed command, or hold inconsistent catalogues. Each test
// reproduces defects found by hand abuse and asserts what replaces them: a derived output
// never writes over its input or a run's files (a live run's lock and checkpoints included),
// shares one lock for its outputs, takes over the stale lock of a killed command and clears
// what it left; a row that contradicts its run is refused naming the row and the column.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "io/folder_lock.hpp"

namespace bkq {
namespace {
using test::expect_refused;
using test::read_file;
using test::run_bkquake;
using test::tree_bytes;
namespace fs = std::filesystem;

// A finished event run of `blocks` blocks and `events` events in `dir`.
void small_run(const std::string& dir, int events = 3000,
               const std::vector<std::string>& more = {}) {
  std::vector<std::string> a = {"run",   "--quiet",
                                "--set", "model.blocks=20",
                                "--set", "run.events=" + std::to_string(events),
                                "--set", "run.transient_events=10"};
  a.insert(a.end(), more.begin(), more.end());
  a.insert(a.end(), {"--out", dir});
  const auto r = run_bkquake(a);
  ASSERT_EQ(r.status, 0) << r.err;
}

// Leaves a stale lock in `dir`, as a command killed by SIGKILL does: a child process takes
// the lock and ends without releasing it. Returns the child's pid (gone now).
pid_t leave_stale_lock(const std::string& dir, const std::string& command) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    try {
      new FolderLock(dir, command, StaleLock::Refuse);  // never released: the process ends
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_TRUE(fs::exists(fs::path(dir) / FolderLock::kFileName));
  return pid;
}

// A catalogue's text with the field `column` of data row `row` (1-based) set to `value`.
std::string with_field(const std::string& csv, int row, const std::string& column,
                       const std::string& value) {
  std::istringstream in(csv);
  std::string header, line, out;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream h(header);
  for (std::string f; std::getline(h, f, ',');) names.push_back(f);
  const auto col = std::find(names.begin(), names.end(), column) - names.begin();
  out = header + "\n";
  for (int k = 1; std::getline(in, line); ++k) {
    if (k == row) {
      std::vector<std::string> f;
      std::stringstream l(line);
      for (std::string x; std::getline(l, x, ',');) f.push_back(x);
      f[static_cast<std::size_t>(col)] = value;
      line.clear();
      for (std::size_t i = 0; i < f.size(); ++i) line += (i ? "," : "") + f[i];
    }
    out += line + "\n";
  }
  return out;
}

// seismicity --export wrote over anything, its own input included: a run's catalogue, its
// other files, another run's catalogue, a bare catalogue exported onto itself. Each is
// refused now like spectrum --out and fit --json, and nothing changes.
TEST(AnalysisReliability, ExportNeverWritesOverItsInputOrARunsFiles) {
  test::TempDir tmp;
  const std::string ex = tmp.file("ex"), other = tmp.file("other");
  small_run(ex);
  small_run(other, 500, {"--set", "run.seed=9"});
  const std::string bare = tmp.write("bare.csv", read_file(ex + "/catalog.csv"));
  const auto before = tree_bytes(tmp.path());
  for (const char* own : {"catalog.csv", "histogram.csv", "scene.ini", "summary.json",
                          "checkpoint.final.bin", "checkpoint.bin", "bkquake.lock"}) {
    SCOPED_TRACE(own);
    const auto r = run_bkquake({"seismicity", ex, "--export", ex + "/" + own});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(r.err.find("is its input") != std::string::npos ||
                r.err.find(std::string("is the file ") + own + " of the run in") !=
                    std::string::npos)
        << r.err;
  }
  expect_refused(run_bkquake({"seismicity", ex, "--export", other + "/catalog.csv"}),
                 {"seismicity --export", "is the file catalog.csv of the run in"});
  expect_refused(run_bkquake({"seismicity", bare, "--export", bare}), {"is its input"});
  // Nor into seismicity/, which the command itself replaces.
  expect_refused(run_bkquake({"seismicity", ex, "--export", ex + "/seismicity/q.csv"}),
                 {"would be replaced by seismicity's own output"});
  EXPECT_TRUE(tree_bytes(tmp.path()) == before) << "a refusal changes nothing";
  // An export beside the run's files is a derived output: written, the lock returned.
  const auto r = run_bkquake({"seismicity", ex, "--export", ex + "/quakes.csv"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(read_file(ex + "/quakes.csv").size(), 1000u);
  EXPECT_EQ(read_file(ex + "/catalog.csv"), before.at(ex + "/catalog.csv"));
  EXPECT_FALSE(fs::exists(ex + "/bkquake.lock"));
  EXPECT_EQ(run_bkquake({"fit", ex}).status, 0);
  // An export at a link is written in the link's place: the file it named is not touched.
  fs::create_symlink(ex + "/catalog.csv", tmp.file("link.csv"));
  ASSERT_EQ(run_bkquake({"seismicity", ex, "--export", tmp.file("link.csv")}).status, 0);
  EXPECT_FALSE(fs::is_symlink(tmp.file("link.csv")));
  EXPECT_EQ(read_file(ex + "/catalog.csv"), before.at(ex + "/catalog.csv"));
}

// While a run holds its folder's lock, before it has written a checkpoint or a summary, its
// lock, its checkpoints and every file it writes are its own, and a derived output into its
// folder waits for it (it took the lock only once checkpoint.bin or summary.json existed).
// fit on the folder fits the rows so far and says that a run is writing them.
TEST(AnalysisReliability, ALiveRunsLockAndFilesAreItsOwn) {
  test::TempDir tmp;
  const std::string done = tmp.file("done"), lv = tmp.file("lv");
  small_run(done);
  fs::create_directories(lv);
  // The folder as a run leaves it early on: its lock (held by this process, alive), its
  // scene and the rows of its catalogue so far; no checkpoint, no summary yet.
  const FolderLock live(lv, "run", StaleLock::Refuse);
  fs::copy_file(done + "/scene.ini", lv + "/scene.ini");
  fs::copy_file(done + "/catalog.csv", lv + "/catalog.csv");
  std::ofstream(lv + "/catalog.csv", std::ios::app) << "3001,12.5";  // a row being written
  const auto before = tree_bytes(lv);
  for (const char* own :
       {"bkquake.lock", "checkpoint.bin", "checkpoint.prev.bin", "timeseries.csv", "histogram.csv"})
    expect_refused(run_bkquake({"fit", lv + "/catalog.csv", "--json", lv + "/" + own}),
                   {std::string("is the file ") + own + " of the run in"});
  expect_refused(run_bkquake({"fit", lv, "--json", lv + "/other.json"}),
                 {"is in use by bkquake run (pid " + std::to_string(::getpid())});
  expect_refused(run_bkquake({"fit", lv, "--scan"}), {"is in use by bkquake run"});
  expect_refused(run_bkquake({"seismicity", lv}), {"is in use by bkquake run"});
  // A folder of derived outputs inside it waits for the run too, and never takes the name of
  // one of its files (a folder named checkpoint.bin would stop the run's checkpoints).
  expect_refused(run_bkquake({"seismicity", lv, "--out", lv + "/sub"}),
                 {"is in use by bkquake run"});
  expect_refused(run_bkquake({"fit", lv, "--scan", "--out", lv + "/checkpoint.bin"}),
                 {"takes the name of the file checkpoint.bin of the run in"});
  EXPECT_TRUE(tree_bytes(lv) == before) << "nothing written into a live run's folder";
  EXPECT_FALSE(fs::exists(lv + "/other.json"));
  // Reading is fine, up to the row being written, and the report says whose rows these are.
  const auto f = run_bkquake({"fit", lv});
  ASSERT_EQ(f.status, 0) << f.err;
  EXPECT_NE(f.out.find("note: bkquake run (pid " + std::to_string(::getpid())), std::string::npos)
      << f.out;
  EXPECT_NE(f.out.find("is writing this folder: these are the 3000 events written so far"),
            std::string::npos)
      << f.out;
  EXPECT_EQ(f.out.find("killed?"), std::string::npos) << f.out;
  const auto s = run_bkquake({"seismicity", lv, "--out", tmp.file("so")});
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_NE(s.out.find("is writing this folder: the events written so far are analysed"),
            std::string::npos)
      << s.out;
  EXPECT_NE(s.out.find("3000 events"), std::string::npos) << s.out;
}

// fit --scan and --json into one folder locked it twice and refused itself ("in use by
// bkquake fit --json (pid <its own>)"); they share the lock now.
TEST(AnalysisReliability, ScanAndJsonIntoOneFolderShareItsLock) {
  test::TempDir tmp;
  const std::string run = tmp.file("run");
  small_run(run);
  const auto r = run_bkquake({"fit", run, "--scan", "--json", run + "/fit.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(run + "/b_scan.csv"));
  EXPECT_NE(read_file(run + "/fit.json").find("\"b_mle\""), std::string::npos);
  EXPECT_FALSE(fs::exists(run + "/bkquake.lock"));
  // seismicity with its export beside the run's files: one lock too.
  const auto s = run_bkquake({"seismicity", run, "--export", run + "/quakes.csv"});
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_TRUE(fs::exists(run + "/seismicity/seismicity.json"));
  EXPECT_FALSE(fs::exists(run + "/bkquake.lock"));
}

// A killed seismicity or fit --scan left a stale lock that refused every rerun with advice
// (--resume, --force) that seismicity does not take, and temporaries no one removed. Derived
// outputs take over a stale lock as runs do and clear what the killed command left.
TEST(AnalysisReliability, AKilledAnalysisLeavesNothingInTheWay) {
  test::TempDir tmp;
  const std::string run = tmp.file("run");
  small_run(run);
  const pid_t gone = leave_stale_lock(run, "seismicity");
  const std::string tag = std::to_string(gone);
  fs::create_directories(run + "/.seismicity.new-" + tag);
  std::ofstream(run + "/.seismicity.new-" + tag + "/omori.csv") << "half";
  std::ofstream(run + "/b_scan.csv.bkquake-tmp-Ab12Cd") << "half";
  const auto r = run_bkquake({"seismicity", run});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("taking over the stale lock"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(run + "/seismicity/seismicity.json"));
  EXPECT_FALSE(fs::exists(run + "/.seismicity.new-" + tag));
  EXPECT_FALSE(fs::exists(run + "/bkquake.lock"));

  leave_stale_lock(run, "fit --scan");
  std::ofstream(run + "/fit.json.bkquake-tmp-Qw12Er") << "half";
  const auto f = run_bkquake({"fit", run, "--scan", "--json", run + "/fit.json"});
  ASSERT_EQ(f.status, 0) << f.err;
  EXPECT_TRUE(fs::exists(run + "/b_scan.csv"));
  EXPECT_FALSE(fs::exists(run + "/b_scan.csv.bkquake-tmp-Ab12Cd"));
  EXPECT_FALSE(fs::exists(run + "/fit.json.bkquake-tmp-Qw12Er"));
  EXPECT_FALSE(fs::exists(run + "/bkquake.lock"));

  // A kill between the two renames of a swap left the old set only as .seismicity.old-PID:
  // it is put back, even when the analysis that finds it fails.
  fs::rename(run + "/seismicity", run + "/.seismicity.old-" + tag);
  leave_stale_lock(run, "seismicity");
  const std::string json = read_file(run + "/.seismicity.old-" + tag + "/seismicity.json");
  std::ofstream(run + "/seismicity_in.csv") << "event,load,moment\n1,0.5,2\n";
  const auto bad = run_bkquake(
      {"seismicity", run + "/seismicity_in.csv", "--blocks", "20", "--mainshock-mu", "0"});
  EXPECT_EQ(bad.status, 2) << bad.err;
  EXPECT_NE(bad.err.find("need at least 2 events"), std::string::npos) << bad.err;
  EXPECT_EQ(read_file(run + "/seismicity/seismicity.json"), json);
  EXPECT_FALSE(fs::exists(run + "/.seismicity.old-" + tag));
  EXPECT_FALSE(fs::exists(run + "/bkquake.lock"));
}

// bkquake seismicity SWEEP_DIR looked for SWEEP/*/catalog.csv, but a sweep keeps its runs in
// SWEEP/points/pNNNN/rNN/: on a real sweep it always said "no point with a catalogue".
TEST(AnalysisReliability, SeismicityOfARealSweepAnalysesEveryReplica) {
  test::TempDir tmp;
  const std::string ini = tmp.write("s.ini",
                                    "[sweep]\nreplicas = 2\ncollect = catalog\n[vary]\n"
                                    "friction.alpha = 2.5, 3\n[set]\nrun.events = 1500\n"
                                    "run.transient_events = 50\nmodel.blocks = 20\n");
  const std::string sw = tmp.file("sw");
  auto r = run_bkquake({"sweep", ini, "--out", sw});
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_bkquake({"seismicity", sw});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* run : {"p0000/r00", "p0000/r01", "p0001/r00", "p0001/r01"})
    EXPECT_TRUE(fs::exists(sw + "/points/" + run + "/seismicity/seismicity.json")) << run;
  expect_refused(run_bkquake({"seismicity", sw, "--out", tmp.file("o")}),
                 {"is a sweep folder (4 replicas with a catalogue)"});
  // Without the catalogues (collect = histogram) it says what to keep.
  const std::string hist_ini =
      tmp.write("h.ini",
                "[sweep]\nreplicas = 1\ncollect = histogram\n[vary]\nfriction.alpha = 2.5\n[set]\n"
                "run.events = 300\nrun.transient_events = 10\nmodel.blocks = 10\n");
  ASSERT_EQ(run_bkquake({"sweep", hist_ini, "--out", tmp.file("sh")}).status, 0);
  expect_refused(run_bkquake({"seismicity", tmp.file("sh")}), {"collect = catalog"});
}

// Inconsistent input was analysed in silence: a NaN time, first_block above last_block,
// --blocks against the run's own shape or beyond any lattice, a scene.ini shorter than its
// catalogue's blocks. Each is refused in one line naming the row and the column.
TEST(AnalysisReliability, InconsistentCataloguesAreRefusedNamingRowAndColumn) {
  test::TempDir tmp;
  const std::string run = tmp.file("run");
  small_run(run, 1000);
  const std::string csv = read_file(run + "/catalog.csv");
  const auto bare = [&](const std::string& name, const std::string& text) {
    const std::string dir = tmp.file(name);
    fs::create_directories(dir);
    std::ofstream(dir + "/catalog.csv") << text;
    return dir + "/catalog.csv";
  };
  // A NaN time at row 700 (line 701) and in the first row.
  const std::string nan700 = bare("n700", with_field(csv, 700, "load", "nan"));
  expect_refused(run_bkquake({"seismicity", nan700}),
                 {"catalog.csv line 701", "load (the event's time) must be finite, got nan"});
  const std::string nan1 = bare("n1", with_field(csv, 1, "load", "nan"));
  expect_refused(run_bkquake({"seismicity", nan1}), {"catalog.csv line 2", "load"});
  // first_block above last_block.
  const std::string flip =
      bare("flip", with_field(with_field(csv, 5, "first_block", "15"), 5, "last_block", "3"));
  expect_refused(run_bkquake({"fit", flip, "--blocks", "20"}),
                 {"catalog.csv line 6", "first_block = 15 is above last_block = 3"});
  expect_refused(run_bkquake({"seismicity", flip}), {"catalog.csv line 6", "first_block = 15"});
  // A last_block far beyond any chain is named with what is allowed.
  const std::string huge = bare("huge", with_field(csv, 3, "last_block", "9223372036854775807"));
  expect_refused(run_bkquake({"fit", huge}),
                 {"catalog.csv line 4", "last_block", "[0, 1000000000]", "9223372036854775807"});
  // scene.ini edited to fewer blocks than the catalogue's: both commands refuse the row.
  const std::string edited = tmp.file("edited");
  fs::copy(run, edited);
  std::string scene = read_file(edited + "/scene.ini");
  scene.replace(scene.find("blocks = 20"), 11, "blocks = 5");
  std::ofstream(edited + "/scene.ini", std::ios::trunc) << scene;
  for (const char* cmd : {"fit", "seismicity"}) {
    const auto r = run_bkquake({cmd, edited});
    EXPECT_EQ(r.status, 2) << cmd << ": " << r.out << r.err;
    EXPECT_NE(r.err.find("lies beyond the 5 blocks along strike"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("catalog.csv line"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(edited + "/seismicity"));
  // --blocks against the scene.ini beside the catalogue, and beyond any lattice.
  expect_refused(run_bkquake({"fit", run, "--blocks", "16x64"}),
                 {"fit: --blocks 16x64 contradicts", "model.blocks = 20, model.rows = 1"});
  expect_refused(run_bkquake({"fit", run + "/catalog.csv", "--blocks", "40"}),
                 {"fit: --blocks 40 contradicts"});
  EXPECT_EQ(run_bkquake({"fit", run, "--blocks", "20"}).status, 0);
  expect_refused(run_bkquake({"fit", flip, "--blocks", "3000000x3000000"}),
                 {"fit: --blocks 3000000x3000000", "allowed at most 1e8"});
  // --blocks for a bare catalogue is checked against its rows.
  const std::string plain = bare("plain", csv);
  expect_refused(run_bkquake({"fit", plain, "--blocks", "10"}),
                 {"catalog.csv line", "lies beyond the 10 blocks along strike (from --blocks)"});
}

// Messages that misled: an internal error for --out at a device, "no such file" for a
// device, "has no summary.json" for a folder that does not exist, a bin width's error
// without its option, a window's without the values given.
TEST(AnalysisReliability, AnalysisMessagesNameWhatIsWrong) {
  test::TempDir tmp;
  const std::string run = tmp.file("run");
  small_run(run, 1000);
  expect_refused(run_bkquake({"fit", run, "--scan", "--out", "/dev/null"}),
                 {"fit: --out /dev/null: not a folder"});
  expect_refused(run_bkquake({"seismicity", "/dev/zero"}),
                 {"seismicity: /dev/zero: not a regular file"});
  expect_refused(run_bkquake({"seismicity", run, "--out", "/dev/null"}),
                 {"seismicity: --out /dev/null: not a folder"});
  // (A link to the device: a bkquake that renamed its export over the name replaces only
  // the link, never the device itself.)
  fs::create_symlink("/dev/null", tmp.file("null"));
  expect_refused(run_bkquake({"seismicity", run, "--export", tmp.file("null")}),
                 {"seismicity: --export " + tmp.file("null") + ": not a regular file"});
  EXPECT_TRUE(fs::is_symlink(tmp.file("null")));
  expect_refused(run_bkquake({"merge", run, tmp.file("nonexist"), "--out", tmp.file("m")}),
                 {"merge: " + tmp.file("nonexist") + ": no such folder"});
  expect_refused(run_bkquake({"fit", run, "--bin-width", "1e-9"}),
                 {"fit: --bin-width 1e-09", "too fine", "allowed"});
  expect_refused(
      run_bkquake({"fit", run, "--mu-min", "-8", "--mu-max", "-7.9"}),
      {"fit: --mu-min -8 --mu-max -7.9", "no whole bin of width 0.2", "--mu-min -8 --mu-max -7.8"});
  EXPECT_FALSE(fs::exists(tmp.file("m")));
}

}  // namespace
}  // namespace bkq
