// `bkquake sweep` as users run it: the outputs of a sweep on two and four MPI ranks and
// on one rank without mpirun are the same bytes (provenance and wall-clock timings aside);
// a bad point fails alone and the exit status says so; a sweep killed mid-way and resumed
// runs only what was missing and ends with the outputs of a sweep that never stopped; a second
// sweep on a folder in use is refused.
//
// The MPI tests run through ctest's `SweepMpi` test (CMakeLists.txt), which sets
// BKQUAKE_MPI_TEST and Open MPI's run-as-root permission in that test's environment only;
// elsewhere they skip, and they skip when mpirun is not installed.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "io/folder_lock.hpp"
#include "io/run_folder.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::run_bkquake;
using test::run_process;
using test::TempDir;

const std::string kSource = BKQUAKE_SOURCE_DIR;

// The small sweep: 2 keys x 2 values x 2 replicas, short event runs.
const char* kSmall = R"([sweep]
combine = product
replicas = 2
[vary]
friction.alpha = 1, 2.5
model.blocks = 30, 60
[set]
model.l = 5
run.events = 1500
run.transient_events = 100
)";

std::string find_mpirun() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string d; std::getline(dirs, d, ':');)
    if (!d.empty() && ::access((d + "/mpirun").c_str(), X_OK) == 0) return d + "/mpirun";
  return "";
}

// Lines of a file without the ones naming a time, a wall-clock duration or a path (and
// those holding `also`, when given).
std::string without_timings(const std::string& text, const char* also = nullptr) {
  static const char* kDrop[] = {"written",      "wall_seconds", "events_per_second",
                                "run_seconds",  "merged_from",  "steps_per_second",
                                "git_revision", "# bkquake 0.", "# sweep file "};
  std::istringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    bool drop = also && line.find(also) != std::string::npos;
    for (const char* d : kDrop) drop = drop || line.find(d) != std::string::npos;
    if (!drop) out += line + "\n";
  }
  return out;
}

// sweep.csv without its run_seconds column.
std::string without_run_seconds(const std::string& csv) {
  std::istringstream in(csv);
  std::string out, line;
  int drop = -1;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string x; std::getline(s, x, ',');) f.push_back(x);
    if (drop < 0)
      for (std::size_t i = 0; i < f.size(); ++i)
        if (f[i] == "run_seconds") drop = static_cast<int>(i);
    for (std::size_t i = 0; i < f.size(); ++i)
      if (static_cast<int>(i) != drop) out += f[i] + ",";
    out += "\n";
  }
  return out;
}

// Every file under `dir`, by relative path.
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file())
      files[fs::relative(e.path(), dir).string()] = read_file(e.path().string());
  return files;
}

// The two sweep folders hold the same files with the same bytes, timings aside (and the
// replicas' session counts, with `extended`: an extended replica counts one more).
void expect_same_outputs(const fs::path& a, const fs::path& b, bool extended = false) {
  const auto ta = tree(a), tb = tree(b);
  std::vector<std::string> na, nb;
  for (const auto& [k, v] : ta) na.push_back(k);
  for (const auto& [k, v] : tb) nb.push_back(k);
  ASSERT_EQ(na, nb);
  int compared = 0;
  for (const auto& [name, text] : ta) {
    const std::string& other = tb.at(name);
    const std::string file = fs::path(name).filename().string();
    if (file == "checkpoint.final.bin")  // a finished replica's state: it holds its clocks
      continue;
    if (file == "sweep.csv")
      EXPECT_EQ(without_run_seconds(text), without_run_seconds(other)) << name;
    else if (file == "summary.json" || file == "point.json" || file == "scene.ini" ||
             file == "sweep.ini")
      EXPECT_EQ(without_timings(text, extended ? "\"resumes\"" : nullptr),
                without_timings(other, extended ? "\"resumes\"" : nullptr))
          << name;
    else
      EXPECT_EQ(text, other) << name;  // catalog.csv, histogram.csv: every byte
    ++compared;
  }
  EXPECT_GT(compared, 10);
}

class SweepMpi : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::getenv("BKQUAKE_MPI_TEST"))
      GTEST_SKIP() << "run by ctest's SweepMpi test (it sets the MPI environment)";
    mpirun_ = find_mpirun();
    if (mpirun_.empty()) GTEST_SKIP() << "mpirun is not installed";
  }
  test::ProcessResult mpi_sweep(int ranks, const std::vector<std::string>& args) {
    std::vector<std::string> all{"-n", std::to_string(ranks), "--oversubscribe", BKQUAKE_BINARY,
                                 "sweep"};
    all.insert(all.end(), args.begin(), args.end());
    return run_process(mpirun_, all);
  }
  std::string mpirun_;
};

TEST_F(SweepMpi, TwoAndFourRanksWriteTheBytesOfOne) {
  TempDir dir;
  const std::string sweep = dir.write("small.ini", kSmall);
  const auto one = run_bkquake({"sweep", sweep, "--out", dir.file("one")});
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_NE(one.out.find("one rank"), std::string::npos) << one.out;
  const auto two = mpi_sweep(2, {sweep, "--out", dir.file("two")});
  ASSERT_EQ(two.status, 0) << two.out << two.err;
  EXPECT_NE(two.out.find("MPI, 2 ranks"), std::string::npos) << two.out;
  expect_same_outputs(dir.path() / "one", dir.path() / "two");
  // More ranks than this machine has cores, and more than half the tasks in flight at once.
  const auto four = mpi_sweep(4, {sweep, "--out", dir.file("four")});
  ASSERT_EQ(four.status, 0) << four.out << four.err;
  expect_same_outputs(dir.path() / "one", dir.path() / "four");
  // Every point and replica ran and was merged; no lock is left behind.
  EXPECT_TRUE(fs::exists(dir.path() / "two/points/p0003/r01/catalog.csv"));
  EXPECT_TRUE(fs::exists(dir.path() / "two/points/p0003/histogram.csv"));
  EXPECT_FALSE(fs::exists(dir.path() / "two/bkquake.lock"));
}

// The Carlson-Langer table from the shipped sweep file, the
// same for 1 and 2 ranks (shortened here; the full table is one command, docs/how-to/sweeps.md).
TEST_F(SweepMpi, CarlsonLangerTableIsTheSameOnOneAndTwoRanks) {
  TempDir dir;
  const std::string sweep = kSource + "/data/sweeps/carlson-langer-table.ini";
  const std::vector<std::string> quick{"--set", "run.events=3000", "--set",
                                       "run.transient_events=200"};
  std::vector<std::string> a{sweep, "--out", dir.file("one")}, b{sweep, "--out", dir.file("two")};
  a.insert(a.end(), quick.begin(), quick.end());
  b.insert(b.end(), quick.begin(), quick.end());
  const auto one = mpi_sweep(1, a);
  ASSERT_EQ(one.status, 0) << one.err;
  const auto two = mpi_sweep(2, b);
  ASSERT_EQ(two.status, 0) << two.err;
  const std::string csv = read_file(dir.file("one/sweep.csv"));
  EXPECT_EQ(without_run_seconds(csv), without_run_seconds(read_file(dir.file("two/sweep.csv"))));
  // Eight points (4 alpha x 2 N), every one fitted on the window by eye.
  int rows = 0;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);)
    if (line.find(",ok,") != std::string::npos && line.find(",-2,") != std::string::npos) ++rows;
  EXPECT_EQ(rows, 8) << csv;
}

TEST(Sweep, ABadPointFailsAloneAndTheStatusSaysSo) {
  TempDir dir;
  // dt = 1 is above rk4's stability limit for this chain: that point is refused.
  const std::string sweep = dir.write("bad.ini", R"([vary]
integrator.dt = 0.01, 1, 0.02
[set]
run.events = 500
run.transient_events = 50
)");
  const auto r = run_bkquake({"sweep", sweep, "--out", dir.file("out")});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("point 1 (integrator.dt = 1) failed"), std::string::npos) << r.err;
  const std::string csv = read_file(dir.file("out/sweep.csv"));
  std::istringstream in(csv);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 4u) << csv;
  EXPECT_EQ(lines[1].rfind("0,0.01,ok,1,500,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("1,1,failed,1,", 0), 0u) << lines[2];
  EXPECT_NE(lines[2].find("integrator.dt"), std::string::npos) << lines[2];
  EXPECT_EQ(lines[3].rfind("2,0.02,ok,1,500,", 0), 0u) << lines[3];
}

TEST(Sweep, AWindowWithoutEventsIsNoFailureButAContradictoryPointIs) {
  TempDir dir;
  // Point 0 contradicts the base scene (mu_min above mu_max): refused alone. Point 1's fit
  // window holds no event: its b is empty, the reason in its summary.json, and it is ok.
  const std::string sweep = dir.write("w.ini", R"([vary]
stats.mu_max = -2, 4.4
[set]
run.events = 300
run.transient_events = 10
stats.mu_min = 4
)");
  const auto r = run_bkquake({"sweep", sweep, "--out", dir.file("out")});
  EXPECT_EQ(r.status, 3) << r.err;
  const std::string csv = read_file(dir.file("out/sweep.csv"));
  EXPECT_NE(csv.find("\n0,-2,failed,1,0,,,,,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("must be below stats.mu_max"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n1,4.4,ok,1,300,,,,,"), std::string::npos) << csv;
  EXPECT_NE(read_file(dir.file("out/points/p0001/summary.json")).find("\"fit_error\""),
            std::string::npos);
}

TEST(Sweep, KilledAndResumedRunsOnlyWhatWasMissing) {
  TempDir dir;
  // The kill can land while a replica probes its folder: the probe then must not stay among
  // the resumed sweep's files (it did, twice in loaded full-suite runs: io/output.cpp).
  const std::string sweep = dir.write("s.ini", R"([vary]
friction.alpha = 1, 2, 2.5, 3
[set]
model.blocks = 40
run.events = 20000
run.transient_events = 100
run.checkpoint_events = 5000
)");
  const auto full = run_bkquake({"sweep", sweep, "--out", dir.file("full")});
  ASSERT_EQ(full.status, 0) << full.err;

  // Killed (SIGKILL: no chance to clean up) once the first point is finished.
  const fs::path out = dir.path() / "cut";
  const int killed = test::run_and_signal_when(
      {"sweep", sweep, "--out", out.string()},
      [&] { return fs::exists(out / "points/p0000/point.json"); }, SIGKILL);
  ASSERT_EQ(killed, 128 + SIGKILL);
  std::map<std::string, std::string> finished;
  for (int p = 0; p < 4; ++p) {
    const fs::path f = out / ("points/p000" + std::to_string(p) + "/point.json");
    if (fs::exists(f)) finished[f.string()] = read_file(f.string());
  }
  ASSERT_GE(finished.size(), 1u);
  ASSERT_LT(finished.size(), 4u) << "the sweep finished before the kill landed";
  EXPECT_TRUE(fs::exists(out / "bkquake.lock"));  // left by the killed process

  // A new sweep into the folder is refused; --resume takes over the dead process's lock.
  const auto again = run_bkquake({"sweep", sweep, "--out", out.string()});
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.err.find("use --resume"), std::string::npos) << again.err;
  const auto resumed = run_bkquake({"sweep", sweep, "--out", out.string(), "--resume"});
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.err.find(std::to_string(4 - finished.size()) + " tasks to run"),
            std::string::npos)
      << resumed.err;
  for (const auto& [f, text] : finished) EXPECT_EQ(read_file(f), text) << f << " was redone";
  expect_same_outputs(dir.path() / "full", out);
}

// A replica stopped by SIGTERM leaves a summary marked interrupted: --resume must continue
// it (a summary no longer means finished), and the result is the uninterrupted sweep's.
TEST(Sweep, AnInterruptedReplicaIsContinuedOnResume) {
  TempDir dir;
  const std::string sweep = dir.write("s.ini", R"([sweep]
replicas = 1
[vary]
friction.alpha = 2.5
[set]
model.blocks = 40
run.events = 200000
run.transient_events = 100
run.checkpoint_events = 5000
)");
  const auto full = run_bkquake({"sweep", sweep, "--out", dir.file("full")});
  ASSERT_EQ(full.status, 0) << full.err;
  const fs::path out = dir.path() / "cut";
  const fs::path replica = out / "points/p0000/r00";
  const int stopped = test::run_and_signal_when(
      {"sweep", sweep, "--out", out.string()},
      [&] { return fs::exists(replica / "checkpoint.bin"); }, SIGTERM);
  ASSERT_EQ(stopped, 143);
  ASSERT_EQ(run_status(replica), RunStatus::Interrupted);
  const auto resumed = run_bkquake({"sweep", sweep, "--out", out.string(), "--resume"});
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("1 tasks to run"), std::string::npos) << resumed.err;
  EXPECT_EQ(run_status(replica), RunStatus::Finished);
  const fs::path straight = dir.path() / "full/points/p0000";
  EXPECT_EQ(test::summary_without_timing(read_file((replica / "summary.json").string())),
            test::summary_without_timing(read_file((straight / "r00/summary.json").string())));
  for (const char* f : {"summary.json", "histogram.csv", "point.json"})
    EXPECT_EQ(without_timings(read_file((out / "points/p0000" / f).string())),
              without_timings(read_file((straight / f).string())))
        << f;
}

// A finished sweep resumed with a larger run.events extends every replica from its final
// state and merges every point again: the outputs are those of a sweep made at the larger
// run.events. A smaller one is refused in one line and changes nothing.
TEST(Sweep, ResumeWithMoreEventsExtendsEveryPoint) {
  TempDir dir;
  const std::string sweep = dir.write("s.ini", R"([sweep]
replicas = 2
[vary]
friction.alpha = 1, 2.5
[set]
model.blocks = 30
run.transient_events = 100
)");
  const auto full =
      run_bkquake({"sweep", sweep, "--out", dir.file("full"), "--set", "run.events=3000"});
  ASSERT_EQ(full.status, 0) << full.err;
  const fs::path out = dir.path() / "ext";
  const auto first =
      run_bkquake({"sweep", sweep, "--out", out.string(), "--set", "run.events=1200"});
  ASSERT_EQ(first.status, 0) << first.err;
  const auto before = tree(out);
  const auto smaller =
      run_bkquake({"sweep", sweep, "--out", out.string(), "--set", "run.events=1000", "--resume"});
  EXPECT_EQ(smaller.status, 2);
  EXPECT_NE(smaller.err.find("run.events = 1000 would not extend its replicas' 1200"),
            std::string::npos)
      << smaller.err;
  EXPECT_TRUE(tree(out) == before) << "a refused extension changed the folder";

  const auto ext =
      run_bkquake({"sweep", sweep, "--out", out.string(), "--set", "run.events=3000", "--resume"});
  ASSERT_EQ(ext.status, 0) << ext.err;
  EXPECT_NE(ext.err.find("4 tasks to run"), std::string::npos) << ext.err;
  expect_same_outputs(dir.path() / "full", out, true);
  // Continued from the final states, not run again from the start.
  for (const char* replica : {"p0000/r00", "p0000/r01", "p0001/r00", "p0001/r01"})
    EXPECT_NE(
        read_file((out / "points" / replica / "summary.json").string()).find("\"resumes\": 1"),
        std::string::npos)
        << replica;
  // Nothing left to extend: a second resume runs nothing.
  const auto again =
      run_bkquake({"sweep", sweep, "--out", out.string(), "--set", "run.events=3000", "--resume"});
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("0 tasks to run"), std::string::npos) << again.err;
}

TEST(Sweep, TwoSweepsOnOneFolderAreRefused) {
  TempDir dir;
  const std::string sweep = dir.write("s.ini", "[vary]\nfriction.alpha = 1, 2\n");
  fs::create_directories(dir.path() / "out");
  // A live process (this test) holds the folder's lock, as a running sweep does.
  const FolderLock held(dir.file("out"), "sweep", StaleLock::Refuse);
  const auto r = run_bkquake({"sweep", sweep, "--out", dir.file("out"), "--set", "run.events=100"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("is in use by bkquake sweep"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("pid " + std::to_string(::getpid())), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out/sweep.csv"));
  EXPECT_FALSE(fs::exists(dir.path() / "out/points"));
}

}  // namespace
}  // namespace bkq
