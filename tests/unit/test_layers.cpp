// The layers link downward only: core <- model <- integrate <- engine <- stats <- io <- app
// <- cli, and python (the Python module's bindings) beside cli: the two top layers see app
// and below, not each other. The build already refuses an upward include (each layer compiles
// against an include root holding only itself and the layers below); this test names every
// offending line at once, and also catches an include that happens to resolve relative to the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace bkq {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kLayers = {"core",  "model", "integrate", "engine",
                                          "stats", "io",    "app",       "cli"};
// Layers of the same rank as another: python sits beside cli.
const std::vector<std::pair<std::string, std::string>> kBeside = {{"python", "cli"}};

int rank_of(const std::string& layer) {
  for (const auto& [name, like] : kBeside)
    if (layer == name) return rank_of(like);
  const auto it = std::find(kLayers.begin(), kLayers.end(), layer);
  return it == kLayers.end() ? -1 : static_cast<int>(it - kLayers.begin());
}

TEST(Layers, EveryFolderUnderSrcIsALayer) {
  for (const auto& e : fs::directory_iterator(fs::path(BKQUAKE_SOURCE_DIR) / "src")) {
    if (e.is_directory()) {
      EXPECT_GE(rank_of(e.path().filename().string()), 0) << e.path() << " is not a layer";
    }
  }
}

TEST(Layers, NoFileIncludesAHigherLayer) {
  const std::regex include(R"re(^\s*#\s*include\s*"([a-z_]+)/)re");
  std::vector<std::string> offences;
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(BKQUAKE_SOURCE_DIR) / "src")) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), fs::path(BKQUAKE_SOURCE_DIR) / "src");
    const int own = rank_of(rel.begin()->string());
    ++files;
    std::ifstream in(e.path());
    int lineno = 0;
    for (std::string line; std::getline(in, line);) {
      ++lineno;
      std::smatch m;
      if (!std::regex_search(line, m, include)) continue;
      const int target = rank_of(m[1].str());
      // Higher, or a sibling of the same rank (cli and python do not see each other).
      if (target > own || (target == own && m[1].str() != rel.begin()->string()))
        offences.push_back(rel.string() + ":" + std::to_string(lineno) + ": " + line);
    }
  }
  EXPECT_GT(files, 50);
  for (const auto& o : offences) ADD_FAILURE() << o;
}

}  // namespace
}  // namespace bkq
