// The table of a tabulated friction law (friction.law = table, friction.table = FILE;
// model/laws/table.hpp): a CSV file of relative speed and friction per unit block mass,
// its columns declared once in friction_table_schema(). '#' lines (provenance) and blank
// lines are skipped; the header names the columns (others are ignored); speeds are >= 0
// and strictly increasing, friction finite and >= 0. `bkquake special-law` writes one.
#pragma once

#include <filesystem>
#include <string>

#include "io/schema.hpp"
#include "model/parameters.hpp"

namespace bkq {

namespace friction_table_col {
inline constexpr const char* speed = "speed";
inline constexpr const char* friction = "friction";
}  // namespace friction_table_col

const Schema& friction_table_schema();

// Reads and checks a table; a bad file is a bkq::Error naming the file, the line and
// what is wrong.
FrictionTable read_friction_table(const std::filesystem::path& path);

// The table as CSV text (header and rows, numbers shortest round-trip), after `comments`
// written as '#' lines.
std::string friction_table_csv(const FrictionTable& table,
                               const std::vector<std::string>& comments = {});

// FNV-1a 64 of the file's bytes as 16 hex digits (recorded in the effective scene).
std::string file_checksum(const std::filesystem::path& path);

}  // namespace bkq
