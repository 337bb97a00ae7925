// `bkquake readme-tables [--update DOCS_DIR | --update PAGE.md]` (not listed in --help: a
// maintainer's tool): prints the documentation's generated blocks with their markers, or
// rewrites them in place: in every page under a docs folder (each block in the one page
// that holds its markers), or in one markdown file that holds the tables
// (io/readme_tables.hpp). Besides io's tables of scene keys and output columns, the docs
// get the text `bkquake --help` prints (block "help") and each listed command's `--help`
// (blocks "help run", "help fit", ...), all made from the command table.
#include <filesystem>
#include <iostream>
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

// io's tables, then the help texts.
std::vector<ReadmeTable> doc_blocks() {
  auto blocks = readme_tables();
  blocks.push_back({"help", fenced(usage_text())});
  for (const Command& command : command_table())
    if (command.listed) blocks.push_back({"help " + command.name, fenced(help_text(command))});
  return blocks;
}

int cmd_readme_tables(const Args& args) {
  if (!args.has("update")) {
    for (const auto& t : doc_blocks())
      std::cout << readme_begin_marker(t.name) << "\n"
                << t.markdown << readme_end_marker(t.name) << "\n\n";
    return 0;
  }
  const std::string path = args.text("update");
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

}  // namespace

Command readme_tables_command_row() {
  Command c{"readme-tables",
            "regenerate the documentation's generated blocks",
            "",
            0,
            "Prints the documentation's generated blocks (scene keys, output columns, every\n"
            "command's --help) with their markers, or rewrites them in place.\n",
            {opt::text("update", "DOCS_DIR|PAGE.md",
                       "rewrite the blocks in every page under DOCS_DIR, or in one page")},
            cmd_readme_tables};
  c.listed = false;
  return c;
}

}  // namespace bkq
