// A file's columns declared once: name, units, number format and meaning. The writer takes
// its header from the schema and the reader finds its columns by the same names; the README
// tables of output columns are tested against the schemas.
#pragma once

#include <string>
#include <vector>

namespace bkq {

struct ColumnSpec {
  const char* name;
  const char* units;  // "" for counts and dimensionless numbers
  const char* doc;
  const char* format = "shortest round-trip";  // how the numbers are printed
};

using Schema = std::vector<ColumnSpec>;

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
