// `bkquake readme-tables [--update DOCS_DIR | --update PAGE.md]` (not listed in --help: a
// maintainer's tool): prints the documentation's generated blocks with their markers, or
// rewrites them in place: in every page under a docs folder (each block in the one page
// that holds its markers), or in one markdown file that holds the tables
// (io/readme_tables.hpp). Besides io's tables of scene keys and output columns, the docs
// get the text `bkquake --help` prints (block "help") and each listed command's `--help`
// (blocks "help run", "help fit", ...), captured from the commands themselves.
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/ini.hpp"
#include "io/output.hpp"
#include "io/readme_tables.hpp"

namespace bkq {

namespace {

// A help text as a fenced block, trailing blank lines dropped.
std::string fenced(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return "```text\n" + text + "\n```\n";
}

// What `bkquake COMMAND --help` prints, captured from the command itself.
std::string help_of(const CommandEntry& command) {
  std::ostringstream captured;
  std::streambuf* const saved = std::cout.rdbuf(captured.rdbuf());
  try {
    command.run({"--help"});
  } catch (...) {
    std::cout.rdbuf(saved);
    throw;
  }
  std::cout.rdbuf(saved);
  return captured.str();
}

// io's tables, then the help texts.
std::vector<ReadmeTable> doc_blocks() {
  auto blocks = readme_tables();
  blocks.push_back({"help", fenced(usage_text())});
  for (const auto& command : listed_commands())
    blocks.push_back({std::string("help ") + command.name, fenced(help_of(command))});
  return blocks;
}

}  // namespace

int cmd_readme_tables(const std::vector<std::string>& args) {
  if (args.empty()) {
    for (const auto& t : doc_blocks())
      std::cout << readme_begin_marker(t.name) << "\n"
                << t.markdown << readme_end_marker(t.name) << "\n\n";
    return 0;
  }
  if (args.size() != 2 || args[0] != "--update")
    throw Error("readme-tables: usage: bkquake readme-tables [--update DOCS_DIR | PAGE.md]");
  const std::string& path = args[1];
  if (std::filesystem::is_directory(path)) {
    const auto before = read_doc_pages(path);
    const auto after = update_doc_pages(before, doc_blocks());
    int changed = 0;
    for (std::size_t i = 0; i < before.size(); ++i) {
      if (after[i].text == before[i].text) continue;
      write_file_atomic((std::filesystem::path(path) / after[i].path).string(), after[i].text);
      std::cout << path << "/" << after[i].path << ": tables updated\n";
      ++changed;
    }
    if (changed == 0) std::cout << path << ": tables already up to date\n";
    return 0;
  }
  const std::string before = read_text_file(path, "README");
  const std::string after = update_readme(before);
  if (after != before) write_file_atomic(path, after);
  std::cout << path << (after != before ? ": tables updated\n" : ": tables already up to date\n");
  return 0;
}

}  // namespace bkq
