// Reliability, fourth round, of what a run writes and reads: a link among a run's files is
// replaced, never written through (--force) or refused (--resume); the folder itself as a
// link to nothing is refused in words; racing runs into one new folder lose with "in use"; a
// file size limit is a write error; a FIFO or device is refused as a scene or catalogue; a
// scene saved with a byte-order mark reads; messages keep non-ASCII paths readable; a wide
// stencil whose every step costs N x R is refused naming its cost.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "io/catalog_h5.hpp"

namespace bkq {
namespace {
using test::expect_refused;
using test::read_file;
using test::run_bkquake;
using test::run_bkquake_for;
using test::tree_bytes;
namespace fs = std::filesystem;

const std::string kThesis = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/thesis.ini";

bool hdf5_built() {
  test::TempDir tmp;
  const auto r = run_bkquake({"run", "--quiet", "--set", "run.events=5", "--set",
                              "output.catalog=hdf5", "--out", tmp.file("probe")});
  return r.status == 0;
}

// A folder of files another run owns, each a distinct text, to be linked to.
std::string victim_folder(test::TempDir& tmp, const std::vector<std::string>& names) {
  const std::string v = tmp.file("victim");
  fs::create_directories(v);
  for (const std::string& n : names) std::ofstream(v + "/" + n) << "victim's " << n << "\n";
  return v;
}

void expect_plain_files(const std::string& dir, const std::vector<std::string>& names) {
  for (const std::string& n : names) {
    const fs::path p = fs::path(dir) / n;
    EXPECT_FALSE(fs::is_symlink(p)) << p;
    EXPECT_TRUE(fs::is_regular_file(p)) << p;
  }
}

// run --force over a folder whose files are symbolic links into another folder: every file
// the run writes (streamed or replaced, event and continuous runs, the lock too) replaces
// the link; the other folder keeps every byte.
TEST(RunOutputs, ForceReplacesLinksAndNeverWritesThroughThem) {
  test::TempDir tmp;
  const std::vector<std::string> event_files = {"catalog.csv",  "event_slip.csv", "histogram.csv",
                                                "summary.json", "scene.ini",      "bkquake.lock"};
  const std::vector<std::string> continuous_files = {
      "catalog.csv", "timeseries.csv",     "blocks.csv",  "segments.csv",
      "energy.csv",  "energy_samples.csv", "summary.json"};
  std::vector<std::string> all = event_files;
  all.insert(all.end(), continuous_files.begin(), continuous_files.end());
  all.push_back("catalog.h5");
  const std::string victim = victim_folder(tmp, all);
  const auto before = tree_bytes(victim);
  const auto link_all = [&](const std::string& dir, const std::vector<std::string>& names) {
    fs::create_directories(dir);
    for (const std::string& n : names) fs::create_symlink(victim + "/" + n, dir + "/" + n);
  };

  const std::string ev = tmp.file("ev");
  link_all(ev, event_files);
  auto r = run_bkquake({"run", "--quiet", "--set", "model.blocks=20", "--set", "run.events=500",
                        "--set", "output.event_slip=0", "--force", "--out", ev});
  ASSERT_EQ(r.status, 0) << r.err;
  expect_plain_files(ev, {"catalog.csv", "event_slip.csv", "histogram.csv", "summary.json"});
  EXPECT_FALSE(fs::exists(ev + "/bkquake.lock"));

  const std::string co = tmp.file("co");
  link_all(co, continuous_files);
  r = run_bkquake({"run",
                   kThesis,
                   "--quiet",
                   "--set",
                   "model.blocks=20",
                   "--set",
                   "run.duration=600",
                   "--set",
                   "drive.step_interval=200",
                   "--set",
                   "output.blocks=true",
                   "--set",
                   "output.every=1",
                   "--set",
                   "output.energy=true",
                   "--set",
                   "output.energy_window=100",
                   "--force",
                   "--out",
                   co});
  ASSERT_EQ(r.status, 0) << r.err;
  expect_plain_files(co, continuous_files);

  if (hdf5_built()) {
    const std::string h5 = tmp.file("h5");
    link_all(h5, {"catalog.h5"});
    r = run_bkquake({"run", "--quiet", "--set", "model.blocks=20", "--set", "run.events=300",
                     "--set", "output.catalog=hdf5", "--force", "--out", h5});
    ASSERT_EQ(r.status, 0) << r.err;
    expect_plain_files(h5, {"catalog.h5"});
  }
  EXPECT_EQ(tree_bytes(victim), before);
}

// A hard link is a link too: --force gives the run a file of its own (the lock's as well,
// which taking over a stale lock rewrote in place).
TEST(RunOutputs, ForceReplacesAHardLink) {
  test::TempDir tmp;
  const std::string victim = victim_folder(tmp, {"catalog.csv", "notes.txt"});
  const std::string r2 = tmp.file("r2");
  fs::create_directories(r2);
  fs::create_hard_link(victim + "/catalog.csv", r2 + "/catalog.csv");
  fs::create_hard_link(victim + "/notes.txt", r2 + "/bkquake.lock");
  const auto before = tree_bytes(victim);
  const auto r = run_bkquake({"run", "--quiet", "--set", "model.blocks=10", "--set",
                              "run.events=200", "--force", "--out", r2});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(tree_bytes(victim), before);
  EXPECT_NE(read_file(r2 + "/catalog.csv"), read_file(victim + "/catalog.csv"));
}

// A FIFO in a file's place is refused, never opened (which would wait) nor removed: only a
// link is ever replaced.
TEST(RunOutputs, ForceRefusesAFifoInAFilesPlace) {
  test::TempDir tmp;
  const std::string r2 = tmp.file("r2");
  fs::create_directories(r2);
  ASSERT_EQ(::mkfifo((r2 + "/catalog.csv").c_str(), 0600), 0);
  const auto r = run_bkquake_for(20, {"run", "--quiet", "--set", "model.blocks=10", "--set",
                                      "run.events=200", "--force", "--out", r2});
  EXPECT_FALSE(r.timed_out);
  expect_refused(r, {r2 + "/catalog.csv", "is a FIFO", "plain files"});
  EXPECT_TRUE(fs::is_fifo(r2 + "/catalog.csv"));
  EXPECT_FALSE(fs::exists(r2 + "/bkquake.lock"));
}

// --resume continues files in place, so a link among them is refused before anything
// changes, naming the file: the folder and the link's target keep every byte.
TEST(RunOutputs, ResumeRefusesALinkAmongItsFiles) {
  test::TempDir tmp;
  const std::string r1 = tmp.file("r1"), elsewhere = tmp.file("elsewhere");
  auto r = run_bkquake(
      {"run", "--quiet", "--set", "model.blocks=10", "--set", "run.events=300", "--out", r1});
  ASSERT_EQ(r.status, 0) << r.err;
  fs::create_directories(elsewhere);
  fs::rename(r1 + "/catalog.csv", elsewhere + "/catalog.csv");
  fs::create_symlink(elsewhere + "/catalog.csv", r1 + "/catalog.csv");
  const auto folder = tree_bytes(r1), target = tree_bytes(elsewhere);
  expect_refused(
      run_bkquake({"run", r1 + "/scene.ini", "--quiet", "--resume", "--set", "run.events=600",
                   "--out", r1}),
      {"--resume", r1 + "/catalog.csv", "is a symbolic link to", "only inside its folder"});
  EXPECT_EQ(tree_bytes(r1), folder);
  EXPECT_EQ(tree_bytes(elsewhere), target);
  EXPECT_TRUE(fs::is_symlink(r1 + "/catalog.csv"));
  EXPECT_FALSE(fs::exists(r1 + "/bkquake.lock"));
}

// --out naming a link to a folder is followed (documented); one to nothing is refused in
// words instead of "File exists".
TEST(RunOutputs, OutAtALinkToNothingIsRefusedInWords) {
  test::TempDir tmp;
  const std::string link = tmp.file("link");
  fs::create_symlink(tmp.file("nowhere"), link);
  expect_refused(run_bkquake({"run", "--quiet", "--set", "run.events=10", "--out", link}),
                 {link, "symbolic link to", "nowhere", "does not exist"});
  EXPECT_FALSE(fs::exists(tmp.file("nowhere")));
  fs::create_directories(tmp.file("real"));
  fs::remove(link);
  fs::create_symlink(tmp.file("real"), link);
  const auto r = run_bkquake({"run", "--quiet", "--set", "run.events=10", "--out", link});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(tmp.file("real") + "/catalog.csv"));
}

// Three runs started at once into one new folder: one wins, and each loser says the folder
// is in use (or, started after the winner finished, that it holds a finished run), never
// that its lock file could not be created.
TEST(RunOutputs, RacingRunsLoseWithInUse) {
  test::TempDir tmp;
  for (int round = 0; round < 12; ++round) {
    const std::string out = tmp.file("race" + std::to_string(round));
    std::vector<std::future<test::ProcessResult>> runs;
    for (int k = 0; k < 3; ++k)
      runs.push_back(std::async(std::launch::async, [&] {
        return run_bkquake({"run", "--quiet", "--set", "model.blocks=10", "--set",
                            "run.events=2000", "--out", out});
      }));
    int winners = 0;
    for (auto& f : runs) {
      const test::ProcessResult r = f.get();
      if (r.status == 0) {
        ++winners;
        continue;
      }
      EXPECT_EQ(r.status, 2) << r.err;
      EXPECT_TRUE(r.err.find("is in use") != std::string::npos ||
                  r.err.find("already holds") != std::string::npos)
          << "round " << round << ": " << r.err;
      EXPECT_EQ(r.err.find("cannot create the lock file"), std::string::npos) << r.err;
    }
    EXPECT_EQ(winners, 1) << "round " << round;
  }
}

// A file size limit (ulimit -f) is a write error like a full disk: one line naming the file,
// exit 2, no lock left, instead of death by SIGXFSZ.
TEST(RunOutputs, FileSizeLimitIsAWriteError) {
  test::TempDir tmp;
  const std::string out = tmp.file("small");
  // 64 blocks of 512 bytes: the catalogue passes 32 KiB within the first thousand events.
  const auto r = test::run_process(
      "/bin/sh", {"-c",
                  "ulimit -f 64; exec \"$0\" run --quiet --set model.blocks=20 --set "
                  "run.events=100000 --set run.transient_events=0 --out \"$1\"",
                  BKQUAKE_BINARY, out});
  expect_refused(r, {"catalog.csv", "File too large"});
  EXPECT_FALSE(fs::exists(out + "/bkquake.lock"));
}

// A FIFO given as a scene, a catalogue or a table is refused at once (its opening would wait
// for a writer forever), by run and by fit.
TEST(RunOutputs, FifoIsRefusedNotAwaited) {
  test::TempDir tmp;
  const std::string fifo = tmp.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto r = run_bkquake_for(20, {"run", fifo, "--quiet", "--out", tmp.file("o")});
  EXPECT_FALSE(r.timed_out);
  expect_refused(r, {"scene file", fifo, "FIFO"});
  r = run_bkquake_for(20, {"fit", fifo});
  EXPECT_FALSE(r.timed_out);
  expect_refused(r, {fifo, "FIFO"});
}

// A scene saved with a UTF-8 byte-order mark reads as the same scene without it.
TEST(RunOutputs, SceneWithAByteOrderMarkReads) {
  test::TempDir tmp;
  const std::string text = "[model]\nblocks = 12\n[run]\nevents = 50\n";
  const std::string plain = tmp.write("plain.ini", text);
  const std::string bom = tmp.write("bom.ini", "\xEF\xBB\xBF" + text);
  const auto a = run_bkquake({"run", plain, "--quiet", "--out", tmp.file("a")});
  const auto b = run_bkquake({"run", bom, "--quiet", "--out", tmp.file("b")});
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_EQ(read_file(tmp.file("a") + "/catalog.csv"), read_file(tmp.file("b") + "/catalog.csv"));
}

// A path with non-ASCII letters is printed as written, not as \xc3\xbc escapes; bytes that
// are no UTF-8 are still escaped.
TEST(RunOutputs, MessagesKeepNonAsciiPathsReadable) {
  test::TempDir tmp;
  const std::string path = tmp.file("m\xC3\xBCller.ini");
  auto r = run_bkquake({"run", path, "--quiet", "--out", tmp.file("o")});
  expect_refused(r, {"m\xC3\xBCller.ini"});
  EXPECT_EQ(r.err.find("\\xc3"), std::string::npos) << r.err;
  r = run_bkquake({"run", tmp.file("bad\xFF.ini"), "--quiet", "--out", tmp.file("o")});
  expect_refused(r, {"bad\\xff.ini"});
}

// A wide stencil whose every force evaluation sums N x 2R springs far beyond any other
// scene's is refused at once, naming both keys, the cost and the bound, for a chain and a
// lattice; one below the bound runs.
TEST(RunOutputs, WideStencilIsRefusedWithItsCost) {
  test::TempDir tmp;
  auto r = run_bkquake_for(
      20, {"run", "--quiet", "--set", "model.coupling=range", "--set", "model.range=10000", "--set",
           "model.blocks=20000", "--set", "run.events=200", "--out", tmp.file("chain")});
  EXPECT_FALSE(r.timed_out);
  expect_refused(r, {"model.range = 10000", "model.blocks = 20000", "4e+08 springs",
                     "allowed: at most 1e+08"});
  EXPECT_FALSE(fs::exists(tmp.file("chain") + "/bkquake.lock"));
  r = run_bkquake_for(20, {"run", "--quiet", "--set", "model.coupling=power", "--set",
                           "model.range=40", "--set", "model.blocks=2000", "--set",
                           "model.rows=1000", "--set", "run.events=200", "--out", tmp.file("lat")});
  EXPECT_FALSE(r.timed_out);
  expect_refused(
      r, {"model.range = 40", "model.blocks x model.rows = 2000 x 1000", "allowed: at most 1e+08"});
  r = run_bkquake({"run", "--quiet", "--set", "model.coupling=range", "--set", "model.range=50",
                   "--set", "model.blocks=200", "--set", "run.events=50", "--out", tmp.file("ok")});
  EXPECT_EQ(r.status, 0) << r.err;
}

// A signal is honoured within the grace (10 s) whatever the run is doing: here the first
// event takes minutes (a tiny integrator.dt) and SIGTERM comes 3 s into it. The run
// ends by the signal about 10 s later, the lock released, not after the event.
TEST(RunOutputs, SignalIsHonouredInsideALongEvent) {
  test::TempDir tmp;
  const std::string out = tmp.file("long");
  const auto r =
      test::run_process(BKQUAKE_BINARY,
                        {"run", "--quiet", "--set", "integrator.dt=1e-9", "--set", "run.events=5",
                         "--set", "run.transient_events=0", "--out", out},
                        "", 3, 120);
  EXPECT_TRUE(r.timed_out);
  EXPECT_EQ(r.status, 143) << r.err;
  EXPECT_LT(r.exit_after_term_s, 30) << "the signal waited for the event to end";
  EXPECT_NE(r.err.find("within 10 s of the signal"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out + "/bkquake.lock"));
}

// The rows of catalog.h5 (every column, bit for bit) after a kill and a resume, and after an
// extension, are those of a run made in one go; the file's bytes are not (what
// docs/how-to/extend-run.md states).
std::vector<double> h5_rows(const std::string& path) {
  const std::vector<std::string> names = {"event",       "load",       "blocks",
                                          "first_block", "last_block", "moment",
                                          "magnitude",   "trigger",    "duration"};
  CatalogH5Reader reader(path, names);
  std::vector<double> all, block;
  while (reader.next_block(block) > 0) all.insert(all.end(), block.begin(), block.end());
  return all;
}

TEST(RunOutputs, Hdf5RowsAfterResumeAndExtensionEqualOneRun) {
  if (!hdf5_built()) GTEST_SKIP() << "built without HDF5";
  test::TempDir tmp;
  const std::vector<std::string> scene = {
      "--set",  "model.blocks=20",     "--set", "run.transient_events=0",
      "--set",  "output.catalog=hdf5", "--set", "run.checkpoint_events=500",
      "--quiet"};
  const auto run = [&](const std::string& out, std::vector<std::string> more) {
    std::vector<std::string> a = {"run"};
    a.insert(a.end(), scene.begin(), scene.end());
    a.insert(a.end(), more.begin(), more.end());
    a.insert(a.end(), {"--out", out});
    return a;
  };
  const std::string whole = tmp.file("whole"), cut = tmp.file("cut"), ext = tmp.file("ext");
  ASSERT_EQ(run_bkquake(run(whole, {"--set", "run.events=20000"})).status, 0);
  // Killed once it has a checkpoint, then resumed.
  ASSERT_EQ(test::run_and_signal_when(
                run(cut, {"--set", "run.events=20000"}),
                [&] { return fs::exists(cut + "/checkpoint.prev.bin"); }, SIGKILL),
            128 + SIGKILL);
  auto r = run_bkquake(run(cut, {"--set", "run.events=20000", "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  // Made at 8000 events, extended to 20000.
  ASSERT_EQ(run_bkquake(run(ext, {"--set", "run.events=8000"})).status, 0);
  r = run_bkquake(run(ext, {"--set", "run.events=20000", "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<double> want = h5_rows(whole + "/catalog.h5");
  ASSERT_EQ(want.size(), 20000u * 9u);
  EXPECT_TRUE(h5_rows(cut + "/catalog.h5") == want);
  EXPECT_TRUE(h5_rows(ext + "/catalog.h5") == want);
  EXPECT_EQ(read_file(cut + "/histogram.csv"), read_file(whole + "/histogram.csv"));
  EXPECT_EQ(read_file(ext + "/histogram.csv"), read_file(whole + "/histogram.csv"));
}

}  // namespace
}  // namespace bkq
