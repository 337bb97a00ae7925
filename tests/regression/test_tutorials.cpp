// The tutorials (docs/tutorials/*.md) and the README's tour run as written, so the documentation
// cannot drift from the program: every fenced ```bash block of a page is run, in page order, by
// bash (-e, with pipefail) in a fresh folder that holds `data/` and `analysis/` of the source tree
// and `build/bkquake`, the binary under test. Reduced sizes follow one documented convention: a
// comment right above a block,
//   <!-- test SUBCOMMAND: OPTIONS -->
// appends OPTIONS to every `build/bkquake SUBCOMMAND ...` command of that block (before a
// redirection, pipe or comment on its line), e.g. `<!-- test run: --set run.events=5000 -->`;
// later options win, so the page's own sizes are overridden. Every `--out FILE.png` a block
// names must exist afterwards. Blocks fenced as ```text (sample output) are not run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kSource = BKQUAKE_SOURCE_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct BashBlock {
  int line = 0;                                // line of the opening fence, 1-based
  std::string text;                            // the commands as the page shows them
  std::map<std::string, std::string> options;  // subcommand -> options the test appends
};

// Every ```bash block of a markdown page, with the test options of the comments above it.
std::vector<BashBlock> bash_blocks(const std::string& page) {
  static const std::regex test_comment(R"(^<!-- test ([a-z-]+): (.*) -->\s*$)");
  std::vector<BashBlock> blocks;
  std::map<std::string, std::string> pending;
  std::istringstream in(page);
  std::string line;
  int n = 0;
  bool in_bash = false, in_other = false;
  while (std::getline(in, line)) {
    ++n;
    if (in_bash || in_other) {
      if (line.rfind("```", 0) == 0) {
        in_bash = in_other = false;
      } else if (in_bash) {
        blocks.back().text += line + "\n";
      }
      continue;
    }
    std::smatch m;
    if (std::regex_match(line, m, test_comment)) {
      std::string& options = pending[m[1]];
      if (!options.empty()) options += ' ';
      options += m[2].str();
    } else if (line == "```bash") {
      in_bash = true;
      blocks.push_back({n, "", pending});
      pending.clear();
    } else if (line.rfind("```", 0) == 0) {
      in_other = true;
      pending.clear();
    } else if (!line.empty()) {
      pending.clear();
    }
  }
  return blocks;
}

// The block with each `build/bkquake SUB` command given its test options: continued lines
// are joined, and the options go before the first redirection, pipe, `&&` or comment.
std::string with_test_options(const BashBlock& block) {
  std::string out;
  std::istringstream in(block.text);
  std::string line, command;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\\') {
      command += line.substr(0, line.size() - 1) + " ";
      continue;
    }
    command += line;
    static const std::regex bkquake(R"(^\s*build/bkquake\s+([a-z-]+)\b)");
    std::smatch m;
    if (std::regex_search(command, m, bkquake) && block.options.count(m[1])) {
      std::size_t at = command.size();
      for (const char* stop : {" #", " >", " |", " &&", " 2>"})
        at = std::min(at, command.find(stop, m.length(0)));
      std::string options(1, ' ');
      options += block.options.at(m[1]);
      command.insert(at, options);
    }
    out += command + "\n";
    command.clear();
  }
  return out;
}

// Every FILE.png that a command of the block writes with --out.
std::vector<std::string> png_outputs(const std::string& text) {
  static const std::regex out_png(R"(--out\s+(\S+\.png))");
  std::vector<std::string> files;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), out_png);
       it != std::sregex_iterator(); ++it)
    files.push_back((*it)[1]);
  return files;
}

std::vector<std::string> tutorial_pages() {
  std::vector<std::string> pages;
  const fs::path dir = kSource / "docs" / "tutorials";
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".md") pages.push_back(e.path().stem().string());
  std::sort(pages.begin(), pages.end());
  pages.push_back("README");  // the README's five-minute tour, under the same rules
  return pages;
}

// The markdown file of a page name: docs/tutorials/NAME.md, or the top README.md.
fs::path page_path(const std::string& name) {
  return name == "README" ? kSource / "README.md" : kSource / "docs" / "tutorials" / (name + ".md");
}

TEST(Tutorials, TheTestOptionsGoAfterThePagesOwnOptionsAndBeforeRedirections) {
  const auto blocks = bash_blocks(
      "text\n<!-- test run: --set run.events=10 -->\n<!-- test fit: --json f.json -->\n"
      "```bash\nbuild/bkquake run S.ini --set run.events=1000 \\\n    --out r # note\n"
      "build/bkquake fit r/catalog.csv > fit.txt\nbuild/bkquake stability S.ini\n"
      "/usr/bin/python3 analysis/plot_gr.py r --out r/gr.png\n```\n\n```text\nnot run\n```\n"
      "```bash\nbuild/bkquake run\n```\n");
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].line, 4);
  EXPECT_EQ(
      with_test_options(blocks[0]),
      "build/bkquake run S.ini --set run.events=1000      --out r --set run.events=10 # note\n"
      "build/bkquake fit r/catalog.csv --json f.json > fit.txt\n"
      "build/bkquake stability S.ini\n"
      "/usr/bin/python3 analysis/plot_gr.py r --out r/gr.png\n");
  EXPECT_EQ(png_outputs(blocks[0].text), std::vector<std::string>{"r/gr.png"});
  EXPECT_TRUE(blocks[1].options.empty());  // the comments apply to the next block only
  EXPECT_EQ(with_test_options(blocks[1]), "build/bkquake run\n");
}

TEST(Tutorials, ThereAreTheFourTutorials) {
  const auto pages = tutorial_pages();
  for (const char* page : {"first-run", "brake-study", "stability", "rate-and-state"})
    EXPECT_NE(std::find(pages.begin(), pages.end(), page), pages.end()) << page;
}

class Tutorial : public testing::TestWithParam<std::string> {};

TEST_P(Tutorial, EveryCommandRunsAtReducedSize) {
  const fs::path page = page_path(GetParam());
  const auto blocks = bash_blocks(slurp(page));
  ASSERT_FALSE(blocks.empty()) << page << " has no ```bash block";
  // One folder per page and process: suites of several checkouts may run at once.
  const fs::path dir = fs::temp_directory_path() /
                       ("bkq_test_tutorial_" + GetParam() + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "build");
  fs::create_directory_symlink(kSource / "data", dir / "data");
  fs::create_directory_symlink(kSource / "analysis", dir / "analysis");
  fs::create_symlink(fs::absolute(BKQUAKE_BINARY), dir / "build" / "bkquake");
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const std::string script = with_test_options(blocks[i]);
    const fs::path file = dir / ("block" + std::to_string(i) + ".sh");
    std::ofstream(file) << "set -eo pipefail\n" << script;
    const fs::path log = dir / ("block" + std::to_string(i) + ".log");
    const std::string cmd = "cd '" + dir.string() + "' && MPLBACKEND=Agg bash '" + file.string() +
                            "' > '" + log.string() + "' 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << page.filename().string() << ", the block at line "
                                           << blocks[i].line << " failed; run as\n"
                                           << script << "output:\n"
                                           << slurp(log);
    for (const auto& png : png_outputs(blocks[i].text)) {
      EXPECT_TRUE(fs::is_regular_file(dir / png) && fs::file_size(dir / png) > 0)
          << png << " (block at line " << blocks[i].line << ")";
    }
  }
  if (!HasFailure()) fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Docs, Tutorial, testing::ValuesIn(tutorial_pages()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
