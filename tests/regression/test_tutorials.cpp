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
//
// A printout a page shows is a ```text block right below `<!-- output of: COMMAND -->`, COMMAND
// being a command of an earlier ```bash block of the page as written there. Its standard output
// is kept when the block runs and compared with the shown text: each shown line (the shown
// text may be an excerpt) matches a later line of the output word for word, with numbers
// compared as numbers: a value shown with an error (`0.9257 ± 0.0079`, `+/-`) within that
// error, an error within a factor of two, a time (a number before `s`, `µs` or `events/s`)
// not at all, any other number within 2 %. Where the test reduces the size of the command or
// of a block before it, only the wording is compared (the numbers are of another run).
// scripts/remake_doc_examples.py remakes the shown printouts and figures at the pages' own sizes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
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

// A ```text block marked as the printout of a command of the page.
struct ShownOutput {
  int line = 0;           // line of the opening fence, 1-based
  std::string command;    // as the marker names it
  std::string text;       // the printout as the page shows it
  std::size_t after = 0;  // how many ```bash blocks precede it
};

struct Page {
  std::vector<BashBlock> blocks;
  std::vector<ShownOutput> shown;
  std::vector<int> unmarked_text;    // lines of ```text blocks without an output marker
  std::vector<std::string> figures;  // files a `<!-- figure: FILE -->` says the blocks write
  std::vector<int> unmarked_images;  // lines of images without a figure marker
};

// Every ```bash block of a markdown page, with the test options of the comments above it,
// and every ```text block with the command whose printout it shows.
Page parse_page(const std::string& text) {
  static const std::regex test_comment(R"(^<!-- test ([a-z-]+): (.*) -->\s*$)");
  static const std::regex output_comment(R"(^<!-- output of: (.*\S)\s*-->\s*$)");
  static const std::regex figure_comment(R"(^<!-- figure: (\S+)\s*-->\s*$)");
  bool figure_pending = false;
  Page page;
  std::map<std::string, std::string> pending;
  std::string pending_output;
  std::istringstream in(text);
  std::string line;
  int n = 0;
  enum { kNone, kBash, kText, kOther } in_block = kNone;
  while (std::getline(in, line)) {
    ++n;
    if (in_block != kNone) {
      if (line.rfind("```", 0) == 0) {
        if (in_block == kText && !page.shown.empty() && page.shown.back().line < 0)
          page.shown.back().line = -page.shown.back().line;
        in_block = kNone;
      } else if (in_block == kBash) {
        page.blocks.back().text += line + "\n";
      } else if (in_block == kText && !page.shown.empty() && page.shown.back().line < 0) {
        page.shown.back().text += line + "\n";
      }
      continue;
    }
    std::smatch m;
    if (std::regex_match(line, m, test_comment)) {
      std::string& options = pending[m[1]];
      if (!options.empty()) options += ' ';
      options += m[2].str();
    } else if (std::regex_match(line, m, output_comment)) {
      pending_output = m[1];
    } else if (std::regex_match(line, m, figure_comment)) {
      page.figures.push_back(m[1]);
      figure_pending = true;
    } else if (line.rfind("![", 0) == 0) {
      if (!figure_pending) page.unmarked_images.push_back(n);
      figure_pending = false;
    } else if (line == "```bash") {
      in_block = kBash;
      page.blocks.push_back({n, "", pending});
      pending.clear();
      pending_output.clear();
    } else if (line == "```text") {
      in_block = kText;
      if (pending_output.empty()) {
        page.unmarked_text.push_back(n);
      } else {
        // line < 0 while the block is read, so that its lines go to it.
        page.shown.push_back({-n, pending_output, "", page.blocks.size()});
      }
      pending.clear();
      pending_output.clear();
    } else if (line.rfind("```", 0) == 0) {
      in_block = kOther;
      pending.clear();
      pending_output.clear();
    } else if (line.rfind("<!--", 0) == 0) {
      // another comment (remake options, see scripts/remake_doc_examples.py) keeps them
    } else if (!line.empty()) {
      pending.clear();
      pending_output.clear();
    }
  }
  return page;
}

std::vector<BashBlock> bash_blocks(const std::string& page) {
  return parse_page(page).blocks;
}

// Whitespace runs as one space, none at either end.
std::string squeezed(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  if (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// A command whose standard output the test keeps (a shown printout's command).
struct Capture {
  std::string command;   // as the page writes it, squeezed
  std::string file;      // where its output goes
  bool found = false;    // a block ran it
  bool reduced = false;  // with test options, so the numbers are of another size
};

// The block with each `build/bkquake SUB` command given its test options: continued lines
// are joined, and the options go before the first redirection, pipe, `&&` or comment. A
// command named by a capture has its standard output written to the capture's file too.
std::string with_test_options(const BashBlock& block, std::vector<Capture>* captures = nullptr) {
  std::string out;
  std::istringstream in(block.text);
  std::string line, command;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\\') {
      command += line.substr(0, line.size() - 1) + " ";
      continue;
    }
    command += line;
    Capture* capture = nullptr;
    if (captures)
      for (Capture& c : *captures)
        if (!c.found && squeezed(command) == c.command) capture = &c;
    static const std::regex bkquake(R"(^\s*build/bkquake\s+([a-z-]+)\b)");
    std::smatch m;
    if (std::regex_search(command, m, bkquake) && block.options.count(m[1])) {
      std::size_t at = command.size();
      for (const char* stop : {" #", " >", " |", " &&", " 2>"})
        at = std::min(at, command.find(stop, m.length(0)));
      std::string options(1, ' ');
      options += block.options.at(m[1]);
      command.insert(at, options);
      if (capture) capture->reduced = true;
    }
    if (capture) {
      capture->found = true;
      command = "{ " + command + " ; } | tee '" + capture->file + "'";
    }
    out += command + "\n";
    command.clear();
  }
  return out;
}

// The numbers of a line of program output and its words with each number as `#`.
struct Tokens {
  std::string words;
  std::vector<double> numbers;
  std::vector<char> kind;  // 'v' a value, 'e' an error (after ± or +/-), 't' a time
};

Tokens tokens(const std::string& line) {
  static const std::regex number(R"([-+]?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?)");
  static const std::regex time_unit(R"(^\s*(s\b|µs|ms\b|events/s))");
  static const std::regex error_sign(R"((±|\+/-)\s*$)");
  Tokens t;
  std::size_t from = 0;
  for (auto it = std::sregex_iterator(line.begin(), line.end(), number);
       it != std::sregex_iterator(); ++it) {
    const std::size_t at = static_cast<std::size_t>(it->position());
    const std::string before = line.substr(from, at - from);
    t.words += before + "#";
    t.numbers.push_back(std::stod(it->str()));
    const std::string after = line.substr(at + it->length());
    t.kind.push_back(std::regex_search(after, time_unit)                 ? 't'
                     : std::regex_search(line.substr(0, at), error_sign) ? 'e'
                                                                         : 'v');
    from = at + static_cast<std::size_t>(it->length());
  }
  t.words = squeezed(t.words + line.substr(from));
  return t;
}

// Where the shown printout `shown` departs from the program's output `actual` (empty when it
// does not): its lines in order among the output's, word for word, and with `numbers` the
// numbers as the file's opening comment says.
std::string printout_mismatch(const std::string& shown, const std::string& actual, bool numbers) {
  std::vector<std::string> lines;
  {
    std::istringstream in(actual);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  std::istringstream in(shown);
  std::size_t next = 0;
  for (std::string l; std::getline(in, l);) {
    if (squeezed(l).empty()) continue;
    const Tokens want = tokens(l);
    std::size_t k = next;
    while (k < lines.size() && tokens(lines[k]).words != want.words) ++k;
    if (k == lines.size()) return "the shown line \"" + l + "\" is not in the output (words)";
    next = k + 1;
    if (!numbers) continue;
    const Tokens got = tokens(lines[k]);
    for (std::size_t i = 0; i < want.numbers.size(); ++i) {
      const double a = want.numbers[i], b = got.numbers[i];
      bool ok = true;
      if (want.kind[i] == 'e') {
        ok = (a == 0 && b == 0) || (a > 0 && b > 0 && b <= 2 * a && a <= 2 * b);
      } else if (want.kind[i] == 'v') {
        double tolerance = 0.02 * std::max(std::abs(a), std::abs(b)) + 1e-12;
        if (i + 1 < want.numbers.size() && want.kind[i + 1] == 'e')
          tolerance = std::max(want.numbers[i + 1], got.numbers[i + 1]) + 1e-12;
        ok = std::abs(a - b) <= tolerance;
      }
      if (!ok)
        return "the shown line \"" + l + "\" differs from the program's \"" + lines[k] +
               "\" in its number " + std::to_string(i + 1);
    }
  }
  return "";
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

TEST(Tutorials, AShownPrintoutMatchesInWordsAndInNumbersWithinTheirErrors) {
  const std::string out =
      "bkquake 0.1.0: 100 events in 1.92 s, 5.2e+04 events/s\n"
      "  b = 0.9257 ± 0.0079 (binned MLE) on mu in [-7.60, 1.20], 13317 events\n"
      "  outputs in r/\n";
  // An excerpt, another time, b within its error: the same.
  EXPECT_EQ(printout_mismatch("bkquake 0.1.0: 100 events in 9.1 s, 1.1e+04 events/s\n"
                              "  outputs in r/\n",
                              out, true),
            "");
  EXPECT_EQ(printout_mismatch("  b = 0.9300 ± 0.0079 (binned MLE) on mu in [-7.60, 1.21], "
                              "13300 events\n",
                              out, true),
            "");
  // b off by more than its error, a window edge off by more than 2 %, other words.
  EXPECT_NE(printout_mismatch("  b = 0.9400 ± 0.0079 (binned MLE) on mu in [-7.60, 1.20], "
                              "13317 events\n",
                              out, true),
            "");
  EXPECT_NE(printout_mismatch("  b = 0.9257 ± 0.0079 (binned MLE) on mu in [-7.60, 2.60], "
                              "13317 events\n",
                              out, true),
            "");
  EXPECT_NE(
      printout_mismatch("  b = 0.9257 ± 0.0079 (binned MLE) on mu in [-7.60, 2.60]\n", out, false),
      "");
  // Lines in another order than the program's; numbers not compared when told so.
  EXPECT_NE(printout_mismatch("  outputs in r/\nbkquake 0.1.0: 100 events in 1 s, 1 events/s\n",
                              out, true),
            "");
  EXPECT_EQ(
      printout_mismatch("  b = 0.5 ± 0.1 (binned MLE) on mu in [-1, 1], 7 events\n", out, false),
      "");
}

TEST(Tutorials, ThePrintoutMarkerNamesTheCommandAndItsOutputIsKept) {
  const Page page = parse_page(
      "```bash\nbuild/bkquake run  --out r\nls r\n```\n\n<!-- output of: build/bkquake run --out r "
      "-->\n```text\nline one\n```\n```text\nunmarked\n```\n");
  ASSERT_EQ(page.shown.size(), 1u);
  EXPECT_EQ(page.shown[0].command, "build/bkquake run --out r");
  EXPECT_EQ(page.shown[0].text, "line one\n");
  EXPECT_EQ(page.shown[0].after, 1u);
  EXPECT_EQ(page.unmarked_text, std::vector<int>{10});
  std::vector<Capture> captures = {{squeezed(page.shown[0].command), "o.txt"}};
  EXPECT_EQ(with_test_options(page.blocks[0], &captures),
            "{ build/bkquake run  --out r ; } | tee 'o.txt'\nls r\n");
  EXPECT_TRUE(captures[0].found);
  EXPECT_FALSE(captures[0].reduced);
}

// Every printout a tutorial or how-to shows is marked with the command it comes from, so the
// test above compares it (the how-to pages' commands are not run: a printout there needs its
// page added to the run first).
TEST(Tutorials, EveryShownPrintoutIsMarkedWithItsCommand) {
  for (const char* folder : {"tutorials", "how-to"}) {
    for (const auto& e : fs::directory_iterator(kSource / "docs" / folder)) {
      if (e.path().extension() != ".md") continue;
      const Page page = parse_page(slurp(e.path()));
      for (const int line : page.unmarked_text)
        ADD_FAILURE() << e.path() << ": the ```text block at line " << line
                      << " has no <!-- output of: COMMAND --> above it";
      if (std::string(folder) == "tutorials") {
        for (const int line : page.unmarked_images)
          ADD_FAILURE() << e.path() << ": the image at line " << line
                        << " has no <!-- figure: FILE --> above it";
      } else {
        EXPECT_TRUE(page.shown.empty()) << e.path() << " shows a printout the suite does not run";
      }
    }
  }
}

TEST(Tutorials, ThereAreTheFourTutorials) {
  const auto pages = tutorial_pages();
  for (const char* page : {"first-run", "brake-study", "stability", "rate-and-state"})
    EXPECT_NE(std::find(pages.begin(), pages.end(), page), pages.end()) << page;
}

class Tutorial : public testing::TestWithParam<std::string> {};

TEST_P(Tutorial, EveryCommandRunsAtReducedSize) {
  const fs::path page = page_path(GetParam());
  const Page parsed = parse_page(slurp(page));
  const auto& blocks = parsed.blocks;
  ASSERT_FALSE(blocks.empty()) << page << " has no ```bash block";
  // One folder per page and process: suites of several checkouts may run at once.
  const fs::path dir = fs::temp_directory_path() /
                       ("bkq_test_tutorial_" + GetParam() + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "build");
  fs::create_directory_symlink(kSource / "data", dir / "data");
  fs::create_directory_symlink(kSource / "analysis", dir / "analysis");
  fs::create_symlink(fs::absolute(BKQUAKE_BINARY), dir / "build" / "bkquake");
  // The shown printouts' commands, each kept from the first block before it that runs it.
  std::vector<Capture> captures;
  for (std::size_t k = 0; k < parsed.shown.size(); ++k)
    captures.push_back({squeezed(parsed.shown[k].command),
                        (dir / ("shown" + std::to_string(k) + ".txt")).string()});
  bool reduced = false;  // a block so far ran with test options
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    std::vector<Capture> these;
    for (std::size_t k = 0; k < captures.size(); ++k)
      if (!captures[k].found && parsed.shown[k].after > i) these.push_back(captures[k]);
    const std::string script = with_test_options(blocks[i], &these);
    reduced = reduced || !blocks[i].options.empty();
    for (Capture& c : these) {
      c.reduced = c.reduced || (c.found && reduced);
      for (Capture& all : captures)
        if (all.file == c.file) all = c;
    }
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
  // The figures the page shows are drawn by its blocks (scripts/remake_doc_examples.py copies
  // them into docs/img/ at the page's own sizes).
  for (const std::string& figure : parsed.figures)
    EXPECT_TRUE(fs::is_regular_file(dir / figure) && fs::file_size(dir / figure) > 0)
        << page.filename().string() << " shows a figure of " << figure
        << ", which its blocks did not write";
  for (std::size_t k = 0; k < parsed.shown.size(); ++k) {
    const ShownOutput& shown = parsed.shown[k];
    if (!captures[k].found) {
      ADD_FAILURE() << page.filename().string() << ": the printout at line " << shown.line
                    << " is of `" << shown.command << "`, which no ```bash block above it runs";
      continue;
    }
    const std::string why =
        printout_mismatch(shown.text, slurp(captures[k].file), !captures[k].reduced);
    EXPECT_EQ(why, "") << page.filename().string() << ", the printout at line " << shown.line
                       << " ("
                       << (captures[k].reduced ? "words only, the test runs it reduced"
                                               : "words and numbers")
                       << "); the program printed\n"
                       << slurp(captures[k].file)
                       << "scripts/remake_doc_examples.py remakes the page's printouts";
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
