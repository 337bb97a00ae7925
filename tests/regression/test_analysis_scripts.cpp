// No analysis script writes into the repository's data/ or docs/ unless told to with --out:
// tests/regression/analysis_scripts.sh runs every script of analysis/ as the documentation
// runs it (at reduced sizes) from the top of a scratch clone of the repository, and
// afterwards `git status --porcelain` of the clone must be empty (runs/ is ignored). The
// clone is of the committed tree (HEAD of the source checkout), with build/bkquake the binary
// under test. A second test checks that the driver names every script of analysis/.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_helpers.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = BKQUAKE_SOURCE_DIR;
const fs::path kDriver = kSource / "tests" / "regression" / "analysis_scripts.sh";

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(AnalysisScripts, TheDriverRunsEveryScript) {
  const std::string driver = slurp(kDriver);
  for (const auto& e : fs::directory_iterator(kSource / "analysis")) {
    const std::string ext = e.path().extension().string();
    const std::string name = e.path().filename().string();
    if ((ext != ".py" && ext != ".sh") || name == "bkquake_io.py") continue;  // a module
    EXPECT_NE(driver.find("analysis/" + name), std::string::npos)
        << "analysis_scripts.sh does not run analysis/" << name;
  }
}

TEST(AnalysisScripts, NoneChangesATrackedFile) {
  if (std::system("git --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no git";
  test::TempDir tmp;
  const fs::path clone = tmp.path() / "repo";
  const std::string quiet = " > '" + tmp.file("log") + "' 2>&1";
  ASSERT_EQ(
      std::system(("git clone --quiet '" + kSource.string() + "' '" + clone.string() + "'" + quiet)
                      .c_str()),
      0)
      << slurp(tmp.file("log"));
  fs::create_directories(clone / "build");
  fs::create_symlink(fs::absolute(BKQUAKE_BINARY), clone / "build" / "bkquake");
  const std::string run = "cd '" + clone.string() + "' && bash '" + kDriver.string() + "' > '" +
                          tmp.file("log") + "' 2>&1";
  EXPECT_EQ(std::system(run.c_str()), 0) << slurp(tmp.file("log"));
  const std::string status =
      "cd '" + clone.string() + "' && git status --porcelain > '" + tmp.file("status") + "' 2>&1";
  ASSERT_EQ(std::system(status.c_str()), 0) << slurp(tmp.file("status"));
  const std::string changed = slurp(tmp.file("status"));
  EXPECT_EQ(changed, "") << "the analysis scripts changed or left these files in the repository";
}

}  // namespace
}  // namespace bkq
