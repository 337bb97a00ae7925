// Small helpers shared by the readers of catalog.csv and histogram.csv: split a CSV line
// (plain comma-separated numbers and names, no quoting: that is all bkquake writes),
// parse a number strictly, and find columns by header name. Errors are bkq::Error naming
// the file, the line and the column.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

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

}  // namespace bkq::csv
