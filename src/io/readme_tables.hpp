// The documentation's tables of scene keys and output columns, generated from their
// declarations (the parameter table of io/scene.hpp and the file schemas of io/*), so the
// reference pages are regenerated rather than hand-edited: `bkquake readme-tables --update
// docs` rewrites the text between the `<!-- begin generated: NAME -->` and
// `<!-- end generated: NAME -->` markers in whichever page under docs/ holds them, and
// tests/unit/test_readme_tables.cpp fails when the pages and the declarations differ.
// (The command keeps its name from when the tables lived in README.md.)
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/schema.hpp"

namespace bkq {

struct ReadmeTable {
  std::string name;      // the marker name: "scene-keys", "catalog.csv", ...
  std::string markdown;  // the table, one line per row, each ending in '\n'
};

// Every generated table.
std::vector<ReadmeTable> readme_tables();

// The markdown table of every scene key: key, default, allowed values, units, meaning.
std::string scene_key_table();
// The markdown table of a file's columns: column, units, format, meaning.
std::string column_table(const Schema& schema);

std::string readme_begin_marker(const std::string& name);
std::string readme_end_marker(const std::string& name);
// The text between the markers of `name` (from the line after the begin marker to the line
// before the end marker); nullopt when the markers are missing or out of order.
std::optional<std::string> readme_block(const std::string& readme, const std::string& name);
// `readme` with every generated block replaced by readme_tables(); bkq::Error naming the
// first table whose markers are missing.
std::string update_readme(const std::string& readme);

// `text` with each generated block it holds replaced by its table; the names of the tables
// it holds are appended to `found` when given. Blocks it lacks are left alone.
std::string update_blocks(const std::string& text, const std::vector<ReadmeTable>& tables,
                          std::vector<std::string>* found = nullptr);

// A markdown page of the documentation: its path relative to the docs folder ('/'-separated)
// and its text.
struct DocPage {
  std::string path;
  std::string text;
};
// Every `*.md` file under `dir`, sorted by path. Symbolic links are not followed (docs/img/
// links to the plots under data/reference/). bkq::Error when `dir` is not a folder.
std::vector<DocPage> read_doc_pages(const std::filesystem::path& dir);
// The page that holds the block of table `name`; nullptr when none does.
const DocPage* page_with_block(const std::vector<DocPage>& pages, const std::string& name);
// `pages` with every generated block replaced by its table; bkq::Error naming a table whose
// block no page holds, or that two pages hold.
std::vector<DocPage> update_doc_pages(const std::vector<DocPage>& pages,
                                      const std::vector<ReadmeTable>& tables);

}  // namespace bkq
