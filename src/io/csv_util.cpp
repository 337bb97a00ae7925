// Implementation of the CSV helpers (see csv_util.hpp).
#include "io/csv_util.hpp"

#include <charconv>
#include <cmath>

#include "core/error.hpp"

namespace bkq::csv {

namespace {
std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

[[noreturn]] void bad_number(std::string_view text, const std::string& file, std::int64_t line,
                             std::string_view column) {
  throw Error(file + " line " + std::to_string(line) + ": column '" + std::string(column) +
              "': expected a number, got '" + std::string(text) + "'");
}
}  // namespace

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  while (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    if (comma == std::string_view::npos) {
      out.push_back(trim(line.substr(start)));
      break;
    }
    out.push_back(trim(line.substr(start, comma - start)));
    start = comma + 1;
  }
  return out;
}

double parse_double(std::string_view text, const std::string& file, std::int64_t line,
                    std::string_view column) {
  if (text == "nan" || text == "NaN") return std::nan("");
  if (text == "inf") return HUGE_VAL;
  if (text == "-inf") return -HUGE_VAL;
  std::string_view t = text;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double x = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size())
    bad_number(text, file, line, column);
  return x;
}

std::int64_t parse_int(std::string_view text, const std::string& file, std::int64_t line,
                       std::string_view column) {
  std::int64_t x = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size()) {
    // Accept integral values written as doubles ("3.0", "1e3").
    const double d = parse_double(text, file, line, column);
    if (!std::isfinite(d) || d != std::floor(d) || std::fabs(d) > 9e15)
      throw Error(file + " line " + std::to_string(line) + ": column '" + std::string(column) +
                  "': expected an integer, got '" + std::string(text) + "'");
    return static_cast<std::int64_t>(d);
  }
  return x;
}

int find_column(const std::vector<std::string_view>& header, std::string_view name) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  return -1;
}

int find_column(const std::vector<std::string_view>& header, const Schema& schema,
                std::string_view name) {
  return find_column(header, column(schema, name).name);
}

int require_column(const std::vector<std::string_view>& header, const Schema& schema,
                   std::string_view name, const std::string& file) {
  const int c = find_column(header, schema, name);
  if (c < 0) throw Error(file + ": missing column '" + std::string(name) + "'");
  return c;
}

}  // namespace bkq::csv
