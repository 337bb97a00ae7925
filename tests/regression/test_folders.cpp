// Output folders as concurrent and interrupted users meet them: two runs
// on one --out (the second refuses naming the first), a run killed by SIGKILL (its stale
// lock is refused without --resume and taken over with it), a stray file in an otherwise
// empty folder (refused without --force), and merge, which writes nothing into its inputs.
#include <gtest/gtest.h>
#include <signal.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "io/scene.hpp"

namespace bkq {
namespace {
using test::expect_refused;
using test::tree_bytes;

namespace fs = std::filesystem;
using test::read_file;
using test::run_bkquake;

// Every file under `dir` with its bytes.
// A run long enough to be caught in the act (it is stopped by a signal).
const std::vector<std::string> kLong = {"run",
                                        "--set",
                                        "model.blocks=50",
                                        "--set",
                                        "run.events=100000000",
                                        "--set",
                                        "run.checkpoint_events=2000",
                                        "--quiet"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

TEST(Folders, SecondRunOnTheSameOutRefusesNamingTheFirst) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  test::ProcessResult second;
  const int first = test::run_and_signal_when(
      with(kLong, {"--out", out}),
      [&] {
        if (!fs::exists(out + "/catalog.csv")) return false;
        second = run_bkquake({"run", "--quiet", "--set", "run.events=10", "--out", out});
        return true;
      },
      SIGTERM);
  EXPECT_EQ(first, 143);
  expect_refused(second, {"'" + out + "' is in use by bkquake run (pid "});
  EXPECT_FALSE(fs::exists(out + "/bkquake.lock")) << "the first run's lock went with it";
  // The first run's outputs are its own: its scene, its checkpoint, its rows.
  EXPECT_NE(read_file(out + "/scene.ini").find("events = 100000000"), std::string::npos);
  EXPECT_TRUE(fs::exists(out + "/checkpoint.bin"));
  EXPECT_GT(read_file(out + "/catalog.csv").size(), 1000u);
}

TEST(Folders, SigkilledRunIsResumableAndItsStaleLockIsTakenOver) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const std::vector<std::string> scene = {"run",
                                          "--set",
                                          "model.blocks=50",
                                          "--set",
                                          "run.events=400000",
                                          "--set",
                                          "run.checkpoint_events=2000",
                                          "--quiet"};
  const int killed = test::run_and_signal_when(
      with(scene, {"--out", out}), [&] { return fs::exists(out + "/checkpoint.bin"); }, SIGKILL);
  ASSERT_EQ(killed, 128 + SIGKILL);
  ASSERT_TRUE(fs::exists(out + "/bkquake.lock"));
  const auto before = tree_bytes(out);
  expect_refused(run_bkquake(with(scene, {"--out", out})), {"stale lock", "--resume", "--force"});
  EXPECT_TRUE(tree_bytes(out) == before) << "a refusal changes nothing";
  const auto r = run_bkquake(with(scene, {"--out", out, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("taking over the stale lock"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(out + "/summary.json"));
  EXPECT_FALSE(fs::exists(out + "/bkquake.lock"));
}

TEST(Folders, StrayCatalogInAnEmptyFolderIsNotOverwritten) {
  test::TempDir tmp;
  const std::string stray = tmp.write("catalog.csv", "my own notes\n");
  expect_refused(run_bkquake({"run", "--quiet", "--out", tmp.path().string()}),
                 {"already holds files", "catalog.csv", "--force"});
  EXPECT_EQ(read_file(stray), "my own notes\n");
  EXPECT_FALSE(fs::exists(tmp.file("scene.ini")));
}

TEST(Folders, MergeWritesNothingIntoItsInputs) {
  test::TempDir tmp;
  const std::string a = tmp.file("a"), b = tmp.file("b"), m = tmp.file("m");
  for (const auto& [dir, seed] : {std::pair{a, "1"}, {b, "2"}}) {
    const auto r = run_bkquake({"run", "--quiet", "--set", "model.blocks=20", "--set",
                                "run.events=2000", "--set", "run.transient_events=10", "--set",
                                std::string("run.seed=") + seed, "--out", dir});
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const auto inputs = tree_bytes(tmp.path().string());
  expect_refused(run_bkquake({"merge", a, b, "--out", a}), {"is the input", a});
  expect_refused(run_bkquake({"merge", a, b, "--out", b + "/../b/"}), {"is the input"});
  expect_refused(run_bkquake({"merge", a, b, "--out", b + "/sub"}), {"lies inside the input"});
  EXPECT_TRUE(tree_bytes(tmp.path().string()) == inputs);

  ASSERT_EQ(run_bkquake({"merge", a, b, "--out", m}).status, 0);
  expect_refused(run_bkquake({"merge", a, b, "--out", m}), {"finished run", "--force"});
  EXPECT_EQ(run_bkquake({"merge", a, b, "--out", m, "--force"}).status, 0);
  EXPECT_FALSE(fs::exists(m + "/bkquake.lock"));
}

}  // namespace
}  // namespace bkq

namespace bkq {
namespace {

// Merge accepts only runs of one scene (the physics and the bins; seeds,
// lengths, checkpoints, outputs and fit windows may differ) and never the same run twice.
class MergeUnlike : public ::testing::Test {
 protected:
  // A short run into tmp_/name with the given extra --set overrides.
  std::string run(const std::string& name, const std::vector<std::string>& sets) {
    std::vector<std::string> args = {"run",   "--quiet",        "--set", "model.blocks=20",
                                     "--set", "run.events=500", "--set", "run.transient_events=10"};
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    const std::string out = tmp_.file(name);
    args.insert(args.end(), {"--out", out});
    const auto r = run_bkquake(args);
    EXPECT_EQ(r.status, 0) << r.err;
    return out;
  }
  test::ProcessResult merge(const std::vector<std::string>& runs) {
    std::vector<std::string> args = {"merge"};
    args.insert(args.end(), runs.begin(), runs.end());
    std::string name = "m";
    name += std::to_string(++merges_);
    args.insert(args.end(), {"--out", tmp_.file(name)});
    return run_bkquake(args);
  }
  test::TempDir tmp_;
  int merges_ = 0;
};

TEST_F(MergeUnlike, RefusesOtherPhysicsNamingTheKeysAndNeverChangesAnInput) {
  const std::string a = run("a", {"run.seed=1"});
  const std::string alpha = run("alpha", {"run.seed=2", "friction.alpha=2", "model.l=9"});
  const std::string bkp = run("bkp", {"run.seed=3", "model.kind=bkp"});
  const std::string bins = run("bins", {"run.seed=4", "stats.bin_width=0.1"});
  const auto inputs = tree_bytes(tmp_.path().string());
  expect_refused(merge({a, alpha}),
                 {"another scene", "model.l = 9 (not 10)", "friction.alpha = 2 (not 2.5)"});
  expect_refused(merge({a, bkp}), {"model.kind = bkp (not bk)"});
  expect_refused(merge({a, bins}), {"stats.bin_width = 0.1 (not 0.2)"});
  EXPECT_TRUE(tree_bytes(tmp_.path().string()) == inputs) << "merge wrote into an input";
}

TEST_F(MergeUnlike, RefusesTheSameRunTwice) {
  const std::string a = run("a", {"run.seed=1"});
  fs::copy(a, tmp_.file("copy"));
  expect_refused(merge({a, a}), {"the same run.seed = 1", "twice"});
  expect_refused(merge({a, tmp_.file("copy")}), {"the same run.seed = 1"});
}

// A merged folder carries the scene its runs share and the seeds merged into it (scene.ini),
// so it merges again with a further run, and the checks still hold through it.
TEST_F(MergeUnlike, AMergedFolderMergesAgainButNotWithARepeatedSeedOrOtherPhysics) {
  const std::string a = run("a", {"run.seed=1"});
  const std::string b = run("b", {"run.seed=2"});
  const std::string c = run("c", {"run.seed=3"});
  const std::string alpha = run("alpha", {"run.seed=4", "friction.alpha=2", "model.l=9"});
  ASSERT_EQ(merge({a, b}).status, 0);  // m1
  const std::string m1 = tmp_.file("m1");
  EXPECT_NE(read_file(m1 + "/scene.ini").find("\n# merged seeds 1 2\n"), std::string::npos);
  const auto r = merge({m1, c});  // m2
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(merge({a, b, c}).status, 0);  // m3
  EXPECT_EQ(read_file(tmp_.file("m2/histogram.csv")), read_file(tmp_.file("m3/histogram.csv")));
  EXPECT_NE(read_file(tmp_.file("m2/summary.json")).find("\"events\": 1500"), std::string::npos);
  EXPECT_NE(read_file(tmp_.file("m2/scene.ini")).find("\n# merged seeds 1 2 3\n"),
            std::string::npos);
  // The physics part of the merged scene is the runs' own.
  EXPECT_EQ(Scene::from_file(tmp_.file("m2/scene.ini")).text("friction.alpha"), "2.5");

  const auto inputs = tree_bytes(tmp_.path().string());
  expect_refused(merge({m1, a}), {"the same run.seed = 1", "twice"});
  expect_refused(merge({c, tmp_.file("m2")}), {"the same run.seed = 3"});
  expect_refused(merge({tmp_.file("m2"), m1}), {"the same run.seed = 1"});
  expect_refused(merge({m1, alpha}), {"another scene", "friction.alpha = 2 (not 2.5)"});
  EXPECT_TRUE(tree_bytes(tmp_.path().string()) == inputs) << "a refused merge wrote something";
}

// An interrupted run (summary.json "status": "interrupted") is no input for merge; `fit`
// on its catalogue fits the events so far and says so.
TEST_F(MergeUnlike, RefusesAnInterruptedRunWhichFitStillReads) {
  const std::string a = run("a", {"run.seed=1"});
  const std::string stopped = tmp_.file("stopped");
  ASSERT_EQ(test::run_and_signal_when(
                {"run", "--quiet", "--set", "model.blocks=20", "--set", "run.events=4000000",
                 "--set", "run.checkpoint_events=2000", "--set", "run.seed=2", "--out", stopped},
                [&] { return fs::exists(stopped + "/checkpoint.bin"); }, SIGTERM),
            143);
  const auto inputs = tree_bytes(tmp_.path().string());
  expect_refused(merge({a, stopped}), {"is an interrupted run", "--resume"});
  EXPECT_TRUE(tree_bytes(tmp_.path().string()) == inputs);
  const auto fit = run_bkquake({"fit", stopped + "/catalog.csv"});
  ASSERT_EQ(fit.status, 0) << fit.err;
  EXPECT_NE(fit.out.find("note: an interrupted run"), std::string::npos) << fit.out;
  EXPECT_NE(fit.out.find("events so far"), std::string::npos) << fit.out;
}

TEST_F(MergeUnlike, AcceptsOtherSeedsLengthsAndFitWindows) {
  const std::string a = run("a", {"run.seed=1"});
  const std::string b =
      run("b", {"run.seed=2", "run.events=700", "stats.mu_min=-5", "run.checkpoint_events=100"});
  const auto inputs = tree_bytes(tmp_.path().string());
  const auto r = merge({a, b});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(read_file(tmp_.file("m1/summary.json")).find("\"events\": 1200"), std::string::npos);
  for (const auto& [path, bytes] : inputs) EXPECT_EQ(read_file(path), bytes) << path;
}

}  // namespace
}  // namespace bkq

namespace bkq {
namespace {

// A row of catalog.csv edited after the checkpoint, keeping its length,
// passed the resume check (it counted bytes and lines); the checkpoint now keeps a checksum.
TEST(Folders, ResumeFindsAnEditedCatalogRowOfTheSameLength) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const std::vector<std::string> scene = {
      "run",   "--quiet",           "--set", "model.blocks=20",
      "--set", "run.events=400000", "--set", "run.checkpoint_events=2000"};
  ASSERT_EQ(test::run_and_signal_when(
                with(scene, {"--out", out}), [&] { return fs::exists(out + "/checkpoint.bin"); },
                SIGTERM),
            143);
  std::string catalog = read_file(out + "/catalog.csv");
  // The last digit of the third row's last field, changed in place.
  std::size_t at = 0;
  for (int line = 0; line < 4; ++line) at = catalog.find('\n', at) + 1;
  at -= 2;
  ASSERT_TRUE(std::isdigit(static_cast<unsigned char>(catalog[at]))) << catalog.substr(0, at + 2);
  catalog[at] = catalog[at] == '1' ? '2' : '1';
  std::ofstream(out + "/catalog.csv", std::ios::binary) << catalog;
  const auto before = tree_bytes(out);
  expect_refused(run_bkquake(with(scene, {"--out", out, "--resume"})),
                 {"cannot resume", "catalog.csv", "checksum differs"});
  EXPECT_TRUE(tree_bytes(out) == before) << "a refused resume changes nothing";
}

}  // namespace
}  // namespace bkq
