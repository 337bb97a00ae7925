// The README and the documentation's home page (docs/index.md) list the same features and
// the same pages: the README's "Beyond a run" is the home page's, word for word with its
// links taken from the top of the repository, and its "Documentation" is the home page's
// "Where to start". The home page lists every page of the site's navigation (mkdocs.yml),
// so a page added to the site cannot be left out of either list.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kSource = BKQUAKE_SOURCE_DIR;

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The text under "## HEADING" up to the next "## " heading; empty when there is none.
std::string section(const std::string& page, const std::string& heading) {
  const std::string head = "## " + heading + "\n";
  const auto at = page.find(head);
  if (at == std::string::npos) return "";
  const auto from = at + head.size();
  const auto end = page.find("\n## ", from);
  return page.substr(from, end == std::string::npos ? std::string::npos : end - from);
}

// The section with every relative link as the README writes it: docs/ before the target.
std::string as_in_readme(const std::string& text) {
  static const std::regex link(R"(\]\((?!https?:)([^)]+)\))");
  return std::regex_replace(text, link, "](docs/$1)");
}

std::vector<std::string> link_targets(const std::string& text) {
  static const std::regex link(R"(\]\(([^)#]+)(#[^)]*)?\))");
  std::vector<std::string> targets;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), link); it != std::sregex_iterator();
       ++it)
    targets.push_back((*it)[1]);
  return targets;
}

TEST(ReadmeLists, TheSectionsExist) {
  const std::string readme = slurp(kSource + "/README.md");
  const std::string index = slurp(kSource + "/docs/index.md");
  for (const char* s : {"Beyond a run", "Documentation"})
    EXPECT_NE(section(readme, s), "") << "README.md has no section ## " << s;
  for (const char* s : {"Beyond a run", "Where to start"})
    EXPECT_NE(section(index, s), "") << "docs/index.md has no section ## " << s;
}

TEST(ReadmeLists, TheFeatureListIsTheHomePages) {
  const std::string readme = slurp(kSource + "/README.md");
  const std::string index = slurp(kSource + "/docs/index.md");
  EXPECT_EQ(section(readme, "Beyond a run"), as_in_readme(section(index, "Beyond a run")))
      << "README.md's \"Beyond a run\" differs from docs/index.md's (links aside)";
}

TEST(ReadmeLists, TheDocumentationListIsTheHomePagesWhereToStart) {
  const std::string readme = slurp(kSource + "/README.md");
  const std::string index = slurp(kSource + "/docs/index.md");
  EXPECT_EQ(section(readme, "Documentation"), as_in_readme(section(index, "Where to start")))
      << "README.md's \"Documentation\" differs from docs/index.md's \"Where to start\"";
}

TEST(ReadmeLists, TheHomePageListsEveryPageOfTheNavigation) {
  const std::string index = slurp(kSource + "/docs/index.md");
  const auto listed = link_targets(section(index, "Where to start"));
  const std::set<std::string> in_list(listed.begin(), listed.end());
  std::istringstream nav(slurp(kSource + "/mkdocs.yml"));
  int pages = 0;
  for (std::string line; std::getline(nav, line);) {
    static const std::regex md(R"(([a-z0-9_-]+/[a-z0-9_-]+\.md)\s*$)");
    std::smatch m;
    if (!std::regex_search(line, m, md)) continue;
    ++pages;
    EXPECT_TRUE(in_list.count(m[1])) << m[1] << " is in mkdocs.yml's nav but not in "
                                     << "docs/index.md's \"Where to start\"";
  }
  EXPECT_GT(pages, 30);  // the nav was read
}

}  // namespace
