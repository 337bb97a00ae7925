// The documentation site builds in MkDocs' strict mode, so a broken link, a missing image
// or a page missing from the navigation's files fails the suite as it fails CI
// (scripts/docs.sh). Skipped where Debian's mkdocs is not installed (scripts/docs.sh
// installs it); the site goes to a temporary folder, not build/docs/.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

const fs::path kSource = BKQUAKE_SOURCE_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(DocsSite, BuildsInStrictMode) {
  if (std::system("command -v mkdocs > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "mkdocs is not installed (scripts/docs.sh installs it)";
  const fs::path dir =
      fs::temp_directory_path() / ("bkq_test_docs_site_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string cmd = "cd '" + kSource.string() + "' && mkdocs build --strict --quiet " +
                          "--config-file mkdocs.yml --site-dir '" + (dir / "site").string() +
                          "' > '" + (dir / "log.txt").string() + "' 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "log.txt");
  // Every tutorial became a page, and the generated reference is on the site.
  for (const char* page : {"index.html", "tutorials/first-run.html", "tutorials/brake-study.html",
                           "tutorials/stability.html", "reference/commands.html",
                           "reference/scenes.html", "reference/outputs.html"})
    EXPECT_TRUE(fs::is_regular_file(dir / "site" / page)) << page;
  EXPECT_NE(slurp(dir / "site" / "reference" / "scenes.html").find("friction.alpha"),
            std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
