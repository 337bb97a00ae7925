// Keys that do not apply to the scene are never used without a word.
// The rule (docs/reference/scenes.md): a key given by --set where it does not apply is an error
// naming the key and why; one from a scene file, which may be shared between scenes, is ignored
// with a one-line warning per key. The effective scene.ini comments such keys out, so a run's
// own scene.ini runs again (and resumes) without a word; --dump-defaults honours --set.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "io/scene.hpp"

namespace bkq {
namespace {
using test::expect_refused;

using test::read_file;
using test::run_bkquake;

const std::vector<std::string> kShort = {
    "--quiet",        "--set", "model.blocks=10",        "--set",
    "run.events=200", "--set", "run.transient_events=10"};

std::vector<std::string> args(std::vector<std::string> a, const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

TEST(InapplicableKeys, SetWhereTheyDoNotApplyIsAnError) {
  test::TempDir tmp;
  expect_refused(run_bkquake(args({"run", "--set", "model.s_m=2"}, kShort)),
                 {"--set model.s_m=2 does not apply",
                  "needs model.parameterisation = thesis or model.kind = bkp"});
  expect_refused(run_bkquake(args({"run", "--set", "model.damping_ratio=0.5"}, kShort)),
                 {"model.damping_ratio", "model.kind = bkp|1dof", "model.kind = bk"});
  expect_refused(run_bkquake({"run", "--set", "drive.mode=continuous", "--set", "run.events=5",
                              "--out", tmp.file("o")}),
                 {"run.events", "drive.mode = events", "drive.mode = continuous"});
  EXPECT_FALSE(std::filesystem::exists(tmp.file("o")));
}

TEST(InapplicableKeys, FromASceneFileTheyAreIgnoredWithAWarningAndCommentedOut) {
  test::TempDir tmp;
  const std::string scene =
      tmp.write("shared.ini", "[model]\ndamping_ratio = 0.3\ns_p = 2\n[run]\nduration = 50\n");
  const auto r = run_bkquake(args({"run", scene, "--out", tmp.file("out")}, kShort));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 3u) << r.err;
  EXPECT_NE(lines[0].find("bkquake: warning: model.damping_ratio = 0.3 (in " + scene +
                          ") does not apply"),
            std::string::npos)
      << lines[0];
  EXPECT_NE(lines[2].find("run.duration = 50"), std::string::npos) << lines[2];
  const std::string ini = read_file(tmp.file("out/scene.ini"));
  EXPECT_NE(ini.find("# damping_ratio = 0.0833333333333333  (unused: needs model.kind"),
            std::string::npos)
      << ini;
  // The run's own scene.ini reads back without a warning and runs the same events.
  const auto again =
      run_bkquake({"run", tmp.file("out/scene.ini"), "--quiet", "--out", tmp.file("again")});
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_TRUE(again.err.empty()) << again.err;
  EXPECT_EQ(read_file(tmp.file("again/catalog.csv")), read_file(tmp.file("out/catalog.csv")));
}

TEST(InapplicableKeys, AContinuousRunsOwnSceneIniRunsAgain) {
  test::TempDir tmp;
  const auto r =
      run_bkquake({"run", "--quiet", "--set", "drive.mode=continuous", "--set", "model.blocks=10",
                   "--set", "run.duration=50", "--out", tmp.file("c")});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string ini = read_file(tmp.file("c/scene.ini"));
  EXPECT_NE(ini.find("# events = 100000  (unused: needs drive.mode = events"), std::string::npos)
      << ini;
  const auto again =
      run_bkquake({"run", tmp.file("c/scene.ini"), "--quiet", "--out", tmp.file("d")});
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_TRUE(again.err.empty()) << again.err;
  EXPECT_EQ(read_file(tmp.file("d/timeseries.csv")), read_file(tmp.file("c/timeseries.csv")));
}

TEST(InapplicableKeys, DumpDefaultsHonoursSceneAndSet) {
  const auto r = run_bkquake(
      {"run", "--dump-defaults", "--set", "friction.alpha=1", "--set", "model.kind=bkp"});
  ASSERT_EQ(r.status, 0) << r.err;
  Scene expected;
  expected.set("friction.alpha", "1");
  expected.set("model.kind", "bkp");
  EXPECT_EQ(Scene::from_text(r.out, "dump"), expected);
  EXPECT_NE(r.out.find("\ndamping_ratio = "), std::string::npos) << "applies to bkp";
  const auto plain = run_bkquake({"run", "--dump-defaults"});
  EXPECT_EQ(Scene::from_text(plain.out, "dump"), Scene());
  expect_refused(run_bkquake({"run", "--dump-defaults", "--set", "run.duration=5"}),
                 {"run.duration"});
}

}  // namespace
}  // namespace bkq
