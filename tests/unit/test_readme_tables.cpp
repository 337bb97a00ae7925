// The documentation's generated tables (pages under docs/, mostly docs/reference/) against
// their declarations: the scene-key table against parameter_table() (every key, default,
// allowed values, units, doc) and the column tables of catalog.csv, histogram.csv,
// timeseries.csv and accuracy.csv against their schemas. On a difference the failure prints
// the expected table; regenerate the pages with
//   build/bkquake readme-tables --update docs
// The schemas are also checked against the headers of the recorded golden outputs, so a
// schema cannot drift from what the program writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "io/accuracy_schema.hpp"
#include "io/catalog.hpp"
#include "io/histogram_csv.hpp"
#include "io/readme_tables.hpp"
#include "io/scene.hpp"
#include "io/timeseries.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = BKQUAKE_SOURCE_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string first_line(const fs::path& p) {
  std::ifstream f(p);
  std::string line;
  std::getline(f, line);
  return line;
}

// The cells of a markdown row "| a | b\| c |" -> {"a", "b| c"}.
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::string cur;
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '\\' && i + 1 < row.size() && row[i + 1] == '|') {
      cur += '|';
      ++i;
    } else if (row[i] == '|') {
      const auto b = cur.find_first_not_of(' ');
      const auto e = cur.find_last_not_of(' ');
      out.push_back(b == std::string::npos ? "" : cur.substr(b, e - b + 1));
      cur.clear();
    } else {
      cur += row[i];
    }
  }
  return out;
}

std::string uncode(const std::string& s) {
  return s.size() >= 2 && s.front() == '`' && s.back() == '`' ? s.substr(1, s.size() - 2) : s;
}

// The body rows (after the header and the |---| line) of a block.
std::vector<std::vector<std::string>> rows(const std::string& block) {
  std::vector<std::vector<std::string>> out;
  std::istringstream in(block);
  std::string line;
  int n = 0;
  while (std::getline(in, line))
    if (n++ >= 2) out.push_back(cells(line));
  return out;
}

const fs::path kDocs = kSource / "docs";

// The block of table `name` in the docs page that holds it; nullopt when none does.
std::optional<std::string> docs_block(const std::string& name) {
  const auto pages = read_doc_pages(kDocs);
  const DocPage* page = page_with_block(pages, name);
  if (!page) return std::nullopt;
  return readme_block(page->text, name);
}

TEST(ReadmeTables, EveryGeneratedTableMatchesItsDocsPage) {
  const auto pages = read_doc_pages(kDocs);
  ASSERT_GT(pages.size(), 10u);
  for (const auto& t : readme_tables()) {
    const DocPage* page = page_with_block(pages, t.name);
    ASSERT_TRUE(page) << "no page under docs/ holds the block " << readme_begin_marker(t.name)
                      << " ... " << readme_end_marker(t.name);
    const auto block = readme_block(page->text, t.name);
    ASSERT_TRUE(block);
    EXPECT_EQ(*block, t.markdown) << "docs/" << page->path << ": the " << t.name
                                  << " table differs from its declaration; regenerate it with\n"
                                     "  build/bkquake readme-tables --update docs\nexpected:\n"
                                  << t.markdown;
  }
  const auto updated = update_doc_pages(pages, readme_tables());
  ASSERT_EQ(updated.size(), pages.size());
  for (std::size_t i = 0; i < pages.size(); ++i)
    EXPECT_TRUE(updated[i].text == pages[i].text) << pages[i].path;
}

TEST(ReadmeTables, ATableInTwoPagesOrInNoneIsRefused) {
  std::vector<DocPage> pages = {{"a.md", "# a\n"}, {"b.md", "# b\n"}};
  for (const auto& t : readme_tables())
    pages[0].text +=
        readme_begin_marker(t.name) + "\n| stale |\n" + readme_end_marker(t.name) + "\n";
  const auto updated = update_doc_pages(pages, readme_tables());
  EXPECT_EQ(updated[0].text.find("| stale |"), std::string::npos);
  EXPECT_EQ(updated[1].text, pages[1].text);
  auto twice = pages;
  twice[1].text += readme_begin_marker("catalog.csv") + "\n\n" + readme_end_marker("catalog.csv");
  try {
    update_doc_pages(twice, readme_tables());
    ADD_FAILURE() << "a table in two pages was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("catalog.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("b.md"), std::string::npos) << e.what();
  }
  const std::vector<DocPage> none = {{"a.md", "# nothing\n"}};
  EXPECT_THROW(update_doc_pages(none, readme_tables()), std::exception);
}

TEST(ReadmeTables, SceneKeyRowsCarryEveryFieldOfTheParameterTable) {
  // Read back independently of the generator: each row names one key with its default,
  // allowed values, units and doc, in table order, and no key is missing or extra.
  const auto block = docs_block("scene-keys");
  ASSERT_TRUE(block);
  const auto body = rows(*block);
  const auto& table = parameter_table();
  ASSERT_EQ(body.size(), table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    const ParamSpec& p = table[i];
    ASSERT_EQ(body[i].size(), 5u) << p.key;
    EXPECT_EQ(uncode(body[i][0]), p.key);
    EXPECT_EQ(uncode(body[i][1]), p.default_value) << p.key;
    EXPECT_EQ(uncode(body[i][2]), allowed_text(p)) << p.key;
    EXPECT_EQ(body[i][3], p.units) << p.key;
    EXPECT_EQ(body[i][4], p.doc) << p.key;
  }
}

TEST(ReadmeTables, ColumnRowsCarryEveryFieldOfTheSchemas) {
  const std::vector<std::pair<std::string, const Schema*>> files = {
      {"catalog.csv", &catalog_schema()},
      {"histogram.csv", &histogram_schema()},
      {"timeseries.csv", &timeseries_schema()},
      {"accuracy.csv", &accuracy_schema()}};
  for (const auto& [name, schema] : files) {
    const auto block = docs_block(name);
    ASSERT_TRUE(block) << name;
    const auto body = rows(*block);
    ASSERT_EQ(body.size(), schema->size()) << name;
    for (std::size_t i = 0; i < schema->size(); ++i) {
      const ColumnSpec& c = (*schema)[i];
      ASSERT_EQ(body[i].size(), 4u) << name << " " << c.name;
      EXPECT_EQ(uncode(body[i][0]), c.name) << name;
      EXPECT_EQ(body[i][1], c.units) << name << " " << c.name;
      EXPECT_EQ(body[i][2], c.format) << name << " " << c.name;
      EXPECT_EQ(body[i][3], c.doc) << name << " " << c.name;
    }
  }
}

TEST(ReadmeTables, SchemasMatchTheHeadersTheProgramWrote) {
  const fs::path golden = kSource / "tests" / "golden";
  EXPECT_EQ(first_line(golden / "bk_rk4_free" / "catalog.csv"), header_of(catalog_schema()));
  EXPECT_EQ(first_line(golden / "bk_rk4_free" / "histogram.csv"), header_of(histogram_schema()));
  EXPECT_EQ(first_line(golden / "merge" / "histogram.csv"), header_of(histogram_schema()));
  EXPECT_EQ(first_line(golden / "bkp_continuous_theta" / "timeseries.csv"),
            header_of(timeseries_schema()));
  EXPECT_EQ(first_line(golden / "accuracy" / "accuracy.csv"), header_of(accuracy_schema()));
}

// Every CSV file any recorded run wrote has a generated table in the docs, and its header is
// that table's column list, so no output file or column goes undocumented.
// blocks.csv is the one exception: its columns (t, u0 ... u{N-1}) depend on N and are
// described in words.
TEST(ReadmeTables, EveryCsvTheProgramWritesHasItsTableInTheDocs) {
  std::map<std::string, std::string> documented;  // file name -> header from its table
  for (const auto& t : readme_tables()) {
    if (t.name.size() < 4 || t.name.substr(t.name.size() - 4) != ".csv") continue;
    std::string header;
    std::istringstream rows(t.markdown);
    std::string row;
    std::getline(rows, row);  // | column | ...
    std::getline(rows, row);  // |---|
    while (std::getline(rows, row)) {
      const auto c = cells(row);
      if (c.empty() || c[0].size() < 2) continue;
      header += (header.empty() ? "" : ",") + c[0].substr(1, c[0].size() - 2);
    }
    documented[t.name] = header;
  }
  int seen = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kSource / "tests" / "golden")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".csv" || name == "blocks.csv") continue;
    ++seen;
    ASSERT_TRUE(documented.count(name)) << entry.path() << " has no generated table in docs/";
    EXPECT_EQ(first_line(entry.path()), documented[name]) << entry.path();
  }
  EXPECT_GT(seen, 30);
}

// What the program prints, read through the binary (not the generator): `bkquake --help`
// and each command's --help it lists, against docs/reference/commands.md's blocks.
std::string output_of(const std::string& args) {
  const fs::path out = fs::temp_directory_path() / "bkq_test_readme_tables_help.txt";
  const std::string cmd =
      std::string(BKQUAKE_BINARY) + " " + args + " > " + out.string() + " 2>/dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return slurp(out);
}

std::string as_fenced(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return "```text\n" + text + "\n```\n";
}

TEST(ReadmeTables, TheCommandsPageShowsWhatEveryCommandsHelpPrints) {
  const std::string usage = output_of("--help");
  EXPECT_EQ(docs_block("help"), as_fenced(usage));
  std::vector<std::string> commands;  // each `  bkquake NAME` line of the usage, once
  std::istringstream in(usage);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("  bkquake ", 0) != 0) continue;
    const std::string name = line.substr(10, line.find(' ', 10) - 10);
    if (name.rfind("--", 0) == 0) continue;
    if (std::find(commands.begin(), commands.end(), name) == commands.end())
      commands.push_back(name);
  }
  EXPECT_GE(commands.size(), 10u);
  const std::string page = slurp(kDocs / "reference" / "commands.md");
  for (const auto& name : commands) {
    const auto block = readme_block(page, "help " + name);
    ASSERT_TRUE(block) << "docs/reference/commands.md has no block for " << name;
    EXPECT_EQ(*block, as_fenced(output_of(name + " --help"))) << name;
  }
}

TEST(ReadmeTables, UpdateRewritesOnlyTheMarkedBlocks) {
  std::string readme = "# title\n\nintro\n";
  for (const auto& t : readme_tables())
    readme +=
        readme_begin_marker(t.name) + "\n| stale |\n" + readme_end_marker(t.name) + "\ntext\n";
  const std::string updated = update_readme(readme);
  EXPECT_EQ(updated.rfind("# title\n\nintro\n", 0), 0u);
  for (const auto& t : readme_tables()) EXPECT_EQ(readme_block(updated, t.name), t.markdown);
  EXPECT_EQ(updated.find("| stale |"), std::string::npos);
  EXPECT_EQ(update_readme(updated), updated);
  EXPECT_THROW(update_readme("# no markers\n"), std::exception);
}

TEST(ReadmeTables, TheCommandRegeneratesACopyOfTheDocs) {
  const fs::path dir = fs::temp_directory_path() / "bkq_test_readme_tables";
  fs::remove_all(dir);
  const fs::path copy = dir / "docs";
  const auto pages = read_doc_pages(kDocs);
  const DocPage* keys = page_with_block(pages, "scene-keys");
  ASSERT_TRUE(keys);
  for (const auto& p : pages) {
    fs::create_directories((copy / p.path).parent_path());
    std::string text = p.text;
    if (&p == keys) {
      const auto at = text.find("| `model.kind` |");
      ASSERT_NE(at, std::string::npos);
      text.insert(at, "| `stale.key` | | | | |\n");
    }
    std::ofstream(copy / p.path, std::ios::binary) << text;
  }
  const std::string cmd = std::string(BKQUAKE_BINARY) + " readme-tables --update " + copy.string() +
                          " > " + (dir / "out.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "out.txt");
  for (const auto& p : pages) EXPECT_TRUE(slurp(copy / p.path) == p.text) << p.path;
  const std::string out = slurp(dir / "out.txt");
  EXPECT_NE(out.find(keys->path + ": tables updated"), std::string::npos) << out;
  EXPECT_EQ(out.find("tables updated", out.find("tables updated") + 1), std::string::npos) << out;
}

}  // namespace
}  // namespace bkq
