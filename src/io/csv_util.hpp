// The one CSV reader helper, shared by the readers of catalog.csv and histogram.csv: split a
// CSV line (plain comma-separated numbers and names, no quoting: that is all they hold),
// parse a number strictly, and find columns by the names their schema (io/schema.hpp)
// declares. Errors are bkq::Error naming the file, the line and the column. (Writing is
// CsvStream's, io/output.hpp, for streamed files, or whole text for the small ones.)
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/schema.hpp"

namespace bkq::csv {

// Splits on commas; strips a trailing '\r' and spaces around each field.
std::vector<std::string_view> split(std::string_view line);

// Strict parse of the whole field; throws bkq::Error
// "<file> line <L>: column '<col>': expected a number, got '<text>'".
double parse_double(std::string_view text, const std::string& file, std::int64_t line,
                    std::string_view column);
std::int64_t parse_int(std::string_view text, const std::string& file, std::int64_t line,
                       std::string_view column);

// Index of a column in the header, or -1.
int find_column(const std::vector<std::string_view>& header, std::string_view name);
// Index in the header of the column `name` of `schema`, or -1 when the file lacks it; a name
// the schema does not declare is a std::logic_error (a reader's bug).
int find_column(const std::vector<std::string_view>& header, const Schema& schema,
                std::string_view name);
// As find_column, but a missing column is bkq::Error "<file>: missing column '<name>'".
int require_column(const std::vector<std::string_view>& header, const Schema& schema,
                   std::string_view name, const std::string& file);

}  // namespace bkq::csv
