// Reading and writing the table of a tabulated friction law (see friction_table.hpp).
#include "io/friction_table.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.hpp"
#include "core/fnv1a.hpp"
#include "core/format.hpp"
#include "io/csv_util.hpp"
#include "io/input_file.hpp"

namespace bkq {

const Schema& friction_table_schema() {
  static const Schema schema = {
      {friction_table_col::speed, "length/time",
       "relative speed y >= 0 of block and substrate, strictly increasing"},
      {friction_table_col::friction, "force/mass",
       "|phi(y)|: friction per unit block mass opposing the motion, >= 0"},
  };
  return schema;
}

FrictionTable read_friction_table(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream f = open_input(path, "friction table");
  namespace col = friction_table_col;
  const Schema& schema = friction_table_schema();
  auto at = [&](std::int64_t line) { return file + " line " + std::to_string(line) + ": "; };
  std::string line;
  std::int64_t lineno = 0;
  auto skipped = [](const std::string& l) {
    const auto first = l.find_first_not_of(" \t\r");
    return first == std::string::npos || l[first] == '#';
  };
  while (std::getline(f, line)) {
    ++lineno;
    if (!skipped(line)) break;
    line.clear();
  }
  check_read(f, path, "friction table", lineno);
  if (line.empty()) throw Error(file + ": no header line, expected '" + header_of(schema) + "'");
  const std::string header_line = line;
  const auto header = csv::split(header_line);
  const std::int64_t header_at = lineno;
  auto need = [&](const char* name) {
    const int c = csv::find_column(header, schema, name);
    if (c < 0)
      throw Error(at(header_at) + "missing column '" + name + "' in the header, expected '" +
                  header_of(schema) + "'");
    return static_cast<std::size_t>(c);
  };
  const std::size_t c_speed = need(col::speed), c_friction = need(col::friction);

  FrictionTable t;
  while (std::getline(f, line)) {
    ++lineno;
    if (skipped(line)) continue;
    const auto fields = csv::split(line);
    if (fields.size() != header.size())
      throw Error(at(lineno) + "expected " + std::to_string(header.size()) + " fields, got " +
                  std::to_string(fields.size()));
    const double y = csv::parse_double(fields[c_speed], file, lineno, col::speed);
    const double phi = csv::parse_double(fields[c_friction], file, lineno, col::friction);
    if (!std::isfinite(y) || y < 0)
      throw Error(at(lineno) + "speed must be finite and >= 0, got " +
                  std::string(fields[c_speed]));
    if (!t.speed.empty() && !(y > t.speed.back()))
      throw Error(at(lineno) + "speed " + std::string(fields[c_speed]) +
                  " is not above the previous row's " + format_real(t.speed.back()) +
                  " (speeds must increase strictly)");
    if (!std::isfinite(phi) || phi < 0)
      throw Error(at(lineno) + "friction must be finite and >= 0, got " +
                  std::string(fields[c_friction]));
    t.speed.push_back(y);
    t.friction.push_back(phi);
  }
  check_read(f, path, "friction table", lineno);
  if (t.speed.empty()) throw Error(file + ": no rows after the header, expected at least one");
  return t;
}

std::string friction_table_csv(const FrictionTable& table,
                               const std::vector<std::string>& comments) {
  std::string s;
  for (const auto& c : comments) s += "# " + c + "\n";
  s += header_of(friction_table_schema()) + "\n";
  for (std::size_t i = 0; i < table.speed.size(); ++i)
    s += format_real(table.speed[i]) + "," + format_real(table.friction[i]) + "\n";
  return s;
}

std::string file_checksum(const std::filesystem::path& path) {
  std::ifstream f = open_input(path, "friction table", std::ios::binary);
  std::string bytes;
  char buf[1 << 16];
  while (f.read(buf, sizeof buf) || f.gcount() > 0) {
    bytes.append(buf, static_cast<std::size_t>(f.gcount()));
    if (!f) break;
  }
  check_read(f, path, "friction table", 0);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64(bytes)));
  return hex;
}

}  // namespace bkq
