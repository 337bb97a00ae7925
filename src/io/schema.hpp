// A file's columns declared once: name, units, number format and meaning. The writer takes
// its header from the schema and the reader finds its columns by the same names; the docs
// tables of output columns are tested against the schemas.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace bkq {

// How a column's numbers are printed (the `format` of a ColumnSpec).
inline constexpr const char* kShortest = "shortest round-trip";  // reads back to the same double
inline constexpr const char* kInteger = "integer";
inline constexpr const char* kText = "text";  // a word, or a quoted string

struct ColumnSpec {
  const char* name;
  const char* units;  // "" for counts and dimensionless numbers
  const char* doc;
  const char* format = kShortest;  // how the numbers are printed
};

using Schema = std::vector<ColumnSpec>;

// The column called `name`; std::logic_error when the schema has none (a reader asking
// for a column its file does not declare is a bug, not bad input).
inline const ColumnSpec& column(const Schema& schema, std::string_view name) {
  for (const auto& c : schema)
    if (c.name == name) return c;
  throw std::logic_error("schema: no column '" + std::string(name) + "'");
}

// "a,b,c" (no newline).
inline std::string header_of(const Schema& schema) {
  std::string s;
  for (const auto& c : schema) {
    if (!s.empty()) s += ',';
    s += c.name;
  }
  return s;
}

}  // namespace bkq
