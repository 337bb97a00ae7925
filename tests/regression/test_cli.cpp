// The bkquake program as users and scripts see it (SPEC §5): exit statuses, one-line
// errors on stderr naming key and value, --version, --help, --dump-defaults, and the
// output-folder guards. Runs the built binary as a subprocess.
#include <gtest/gtest.h>

#include <sstream>

#include "../cli_helpers.hpp"
#include "cli/commands.hpp"
#include "io/scene.hpp"

namespace bkq {
namespace {

using test::run_bkquake;

// Exactly one line on stderr, starting "bkquake: error: " and containing every part.
void expect_one_error_line(const test::ProcessResult& r, std::initializer_list<std::string> parts) {
  EXPECT_EQ(r.status, 2) << r.err;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r.err;
  EXPECT_EQ(lines[0].rfind("bkquake: error: ", 0), 0u) << lines[0];
  for (const auto& p : parts)
    EXPECT_NE(lines[0].find(p), std::string::npos) << lines[0] << " lacks " << p;
}

TEST(Cli, Version) {
  const auto r = run_bkquake({"--version"});
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("bkquake 0.1.0", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("git "), std::string::npos);
  EXPECT_TRUE(r.err.empty());
}

// --version's second line names the optional parts and whether this build has each; its
// HDF5 answer is what a run asking for an HDF5 catalogue finds.
TEST(Cli, VersionNamesTheOptionalParts) {
  const auto r = run_bkquake({"--version"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto second = r.out.find('\n');
  ASSERT_NE(second, std::string::npos) << r.out;
  const std::string line = r.out.substr(second + 1);
  EXPECT_EQ(line.rfind("optional parts: ", 0), 0u) << line;
  for (const char* part : {"HDF5 catalogues", "MPI sweeps", "Python module"}) {
    const bool yes = line.find(std::string(part) + " yes") != std::string::npos;
    const bool no = line.find(std::string(part) + " no") != std::string::npos;
    EXPECT_NE(yes, no) << part << " in: " << line;
  }
  test::TempDir dir;
  const auto h5 =
      run_bkquake({"run", "--set", "run.events=20", "--set", "run.transient_events=0", "--set",
                   "output.catalog=hdf5", "--out", (dir.path() / "r").string()});
  EXPECT_EQ(h5.status == 0, line.find("HDF5 catalogues yes") != std::string::npos)
      << line << h5.err;
}

// --version's third line names the platform and compiler the binary was built for.
TEST(Cli, VersionNamesThePlatform) {
  const auto r = run_bkquake({"--version"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream in(r.out);
  std::string line;
  for (int k = 0; k < 3; ++k) std::getline(in, line);
  ASSERT_EQ(line.rfind("target: ", 0), 0u) << r.out;
  EXPECT_EQ(line.find("unknown"), std::string::npos) << line;
#if defined(__x86_64__)
  EXPECT_EQ(line.rfind("target: x86_64", 0), 0u) << line;
#endif
}

TEST(Cli, Help) {
  for (const char* h : {"--help", "-h", "help"}) {
    const auto r = run_bkquake({h});
    EXPECT_EQ(r.status, 0) << h;
    EXPECT_NE(r.out.find("bkquake run"), std::string::npos);
    EXPECT_NE(r.out.find("--dump-defaults"), std::string::npos);
  }
  const auto r = run_bkquake({"run", "--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--set"), std::string::npos);
}

TEST(Cli, UnknownCommandAndOption) {
  expect_one_error_line(run_bkquake({"frobnicate"}), {"unknown command 'frobnicate'"});
  expect_one_error_line(run_bkquake({"run", "--frobnicate"}), {"--frobnicate"});
  expect_one_error_line(run_bkquake({"run", "--set"}), {"--set"});
}

// The error for an unknown command lists every command there is.
TEST(Cli, UnknownCommandListsTheCommands) {
  const auto r = run_bkquake({"frobnicate"});
  EXPECT_EQ(r.status, 2) << r.err;
  ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
  const std::string line = r.err_lines()[0];
  EXPECT_NE(line.find("unknown command 'frobnicate'"), std::string::npos) << line;
  EXPECT_NE(line.find("try 'bkquake --help'"), std::string::npos) << line;
  const std::string head = "the commands are ";
  const auto from = line.find(head);
  ASSERT_NE(from, std::string::npos) << line;
  std::string names = line.substr(from + head.size());
  names = names.substr(0, names.find(';'));
  std::string expected;
  for (const Command& c : command_table())
    if (c.listed) expected += (expected.empty() ? "" : ", ") + c.name;
  EXPECT_EQ(names, expected) << line;
}

// Every command of the table is dispatched: its --help exits 0 and prints its synopsis;
// an option it does not have is refused in one line naming the option and the command.
TEST(Cli, EveryCommandOfTheTableIsDispatched) {
  for (const Command& c : command_table()) {
    const auto help = run_bkquake({c.name, "--help"});
    EXPECT_EQ(help.status, 0) << c.name << ": " << help.err;
    EXPECT_EQ(help.out, help_text(c)) << c.name;
    EXPECT_EQ(help.out.rfind("Usage: bkquake " + c.name, 0), 0u) << help.out;
    EXPECT_TRUE(help.err.empty()) << c.name << ": " << help.err;
    expect_one_error_line(run_bkquake({c.name, "--frobnicate"}),
                          {c.name + ": ", "'--frobnicate'", "bkquake " + c.name + " --help"});
  }
}

TEST(Cli, NoCommandPrintsUsageAndFails) {
  const auto r = run_bkquake({});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("Usage:"), std::string::npos);
}

TEST(Cli, ResumeAndForceExcludeEachOther) {
  test::TempDir tmp;
  expect_one_error_line(run_bkquake({"run", "--resume", "--force", "--out", tmp.file("o")}),
                        {"--resume", "--force"});
  expect_one_error_line(run_bkquake({"run", "a.ini", "b.ini"}), {"at most one scene"});
}

TEST(Cli, DumpDefaultsParsesBackToDefaults) {
  const auto r = run_bkquake({"run", "--dump-defaults"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty());
  EXPECT_EQ(Scene::from_text(r.out, "dump"), Scene());
}

TEST(Cli, BadValueInSceneFile) {
  test::TempDir tmp;
  const std::string scene = tmp.write("bad.ini", "[friction]\nsigma = 1.5\n");
  expect_one_error_line(run_bkquake({"run", scene, "--out", tmp.file("out")}),
                        {"friction.sigma", "1.5", "[0, 1)", "bad.ini"});
}

TEST(Cli, UnknownKeyAndBadOverride) {
  test::TempDir tmp;
  const std::string scene = tmp.write("typo.ini", "[friction]\nsigmaa = 0.1\n");
  expect_one_error_line(run_bkquake({"run", scene}), {"friction.sigmaa", "friction.sigma"});
  expect_one_error_line(run_bkquake({"run", "--set", "model.blocks=12abc"}),
                        {"model.blocks", "'12abc'", "(--set)"});
  expect_one_error_line(run_bkquake({"run", "--set", "model.blocks"}), {"section.key=value"});
  expect_one_error_line(run_bkquake({"run", "--set", "model.pad_mass=3"}),
                        {"model.pad_mass", "model.parameterisation"});
}

TEST(Cli, MissingSceneFile) {
  test::TempDir tmp;
  expect_one_error_line(run_bkquake({"run", tmp.file("nope.ini")}),
                        {"cannot read scene file", "nope.ini", "No such file or directory"});
}

TEST(Cli, UnwritableOutputFolder) {
  test::TempDir tmp;
  const std::string file = tmp.write("plain", "x");
  expect_one_error_line(run_bkquake({"run", "--out", file + "/sub"}),
                        {"cannot create output folder", file + "/sub"});
}

TEST(Cli, FinishedRunIsNotOverwritten) {
  test::TempDir tmp;
  const std::string content = "{\n  \"events\": 5\n}\n";
  const std::string summary = tmp.write("summary.json", content);
  expect_one_error_line(run_bkquake({"run", "--out", tmp.path().string()}),
                        {"already holds a finished run", "--force"});
  EXPECT_EQ(test::read_file(summary), content);
}

}  // namespace
}  // namespace bkq
