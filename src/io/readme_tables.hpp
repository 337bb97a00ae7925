// The README's tables of scene keys and output columns, generated from their declarations
// (the parameter table of io/scene.hpp and the file schemas of io/*), so the README is
// regenerated rather than hand-edited: `bkquake readme-tables --update README.md` rewrites
// the text between the `<!-- begin generated: NAME -->` and `<!-- end generated: NAME -->`
// markers, and tests/unit/test_readme_tables.cpp fails when the README and the
// declarations differ.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/schema.hpp"

namespace bkq {

struct ReadmeTable {
  std::string name;      // the marker name: "scene-keys", "catalog.csv", ...
  std::string markdown;  // the table, one line per row, each ending in '\n'
};

// Every generated table, in README order.
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

}  // namespace bkq
