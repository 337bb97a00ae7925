// Implementation of the whole-table readers (see column_table.hpp). The CSV is read in
// large chunks and each field parsed with std::from_chars in place; a field the quick parse
// does not take (a sign, nan, inf, an integer written as 3.0, or text) goes to the strict
// parsers of io/csv_util.hpp, which accept it or throw their one-line error.
#include "io/column_table.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.hpp"
#include "io/catalog.hpp"
#include "io/catalog_h5.hpp"
#include "io/csv_util.hpp"
#include "io/input_file.hpp"

namespace bkq {

namespace {

constexpr std::size_t kChunk = std::size_t{4} << 20;

struct File {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f;
  explicit File(const std::string& path) : f(std::fopen(path.c_str(), "rb"), &std::fclose) {
    if (!f) throw Error(path + ": cannot open");
  }
};

// Newlines in the file: an upper bound of its rows, so every column is allocated once.
std::int64_t count_newlines(const std::string& path) {
  File in(path);
  std::vector<char> buf(kChunk);
  std::int64_t n = 0;
  while (const std::size_t got = std::fread(buf.data(), 1, buf.size(), in.f.get()))
    n += std::count(buf.data(), buf.data() + got, '\n');
  if (std::ferror(in.f.get())) throw Error(path + ": read error");
  return n;
}

bool blank(std::string_view s) {
  return s.find_first_not_of(" \t\r") == std::string_view::npos;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

bool ends_in_digit(std::string_view s) {
  return !s.empty() && s.back() >= '0' && s.back() <= '9';
}

class CsvTableReader {
 public:
  CsvTableReader(const std::filesystem::path& path, const Schema& schema) {
    t_.file = path.string();
    const std::int64_t max_rows = count_newlines(t_.file);
    File in(t_.file);
    std::string buf;
    std::size_t start = 0;  // where the unread part of buf begins
    bool header_done = false;
    std::vector<char> chunk(kChunk);
    while (true) {
      const std::size_t got = std::fread(chunk.data(), 1, chunk.size(), in.f.get());
      if (std::ferror(in.f.get()))
        throw Error(t_.file + ": read error after line " + std::to_string(lineno_));
      buf.erase(0, start);
      start = 0;
      buf.append(chunk.data(), got);
      const bool at_end = got == 0;
      while (true) {
        const std::size_t nl = buf.find('\n', start);
        if (nl == std::string::npos && !(at_end && start < buf.size())) break;
        const std::size_t end = nl == std::string::npos ? buf.size() : nl;
        const std::string_view line(buf.data() + start, end - start);
        start = end + (nl == std::string::npos ? 0 : 1);
        ++lineno_;
        if (!header_done) {
          header(line, schema, max_rows);
          header_done = true;
        } else if (!blank(line)) {
          row(line);
        }
      }
      if (at_end) break;
    }
    if (!header_done) throw Error(t_.file + ": empty file, expected a header line");
  }

  ColumnTable take() { return std::move(t_); }

 private:
  void header(std::string_view line, const Schema& schema, std::int64_t max_rows) {
    if (blank(line)) throw Error(t_.file + ": empty file, expected a header line");
    for (const std::string_view name : csv::split(line)) {
      TableColumn c;
      c.name = std::string(name);
      for (const ColumnSpec& s : schema)
        if (s.name == name) c.integer = std::string_view(s.format) == kInteger;
      if (c.integer)
        c.i.reserve(static_cast<std::size_t>(max_rows));
      else
        c.x.reserve(static_cast<std::size_t>(max_rows));
      t_.columns.push_back(std::move(c));
    }
  }

  void row(std::string_view line) {
    while (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    std::size_t k = 0;
    std::size_t pos = 0;
    while (true) {
      const std::size_t comma = line.find(',', pos);
      const std::string_view field = trim(
          line.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos));
      if (k < t_.columns.size()) parse(t_.columns[k], field);
      ++k;
      if (comma == std::string_view::npos) break;
      pos = comma + 1;
    }
    if (k != t_.columns.size())
      throw Error(t_.file + " line " + std::to_string(lineno_) + ": expected " +
                  std::to_string(t_.columns.size()) + " fields, got " + std::to_string(k));
    ++t_.rows;
  }

  void parse(TableColumn& c, std::string_view field) {
    const char* end = field.data() + field.size();
    if (c.integer) {
      std::int64_t v = 0;
      const auto r = std::from_chars(field.data(), end, v);
      if (field.empty() || r.ec != std::errc() || r.ptr != end)
        v = csv::parse_int(field, t_.file, lineno_, c.name);
      c.i.push_back(v);
    } else {
      double v = 0;
      // Only numbers ending in a digit take the quick path: from_chars also reads words
      // (INF, nan(...)) that the strict parser refuses.
      const auto r = std::from_chars(field.data(), end, v);
      if (!ends_in_digit(field) || r.ec != std::errc() || r.ptr != end)
        v = csv::parse_double(field, t_.file, lineno_, c.name);
      c.x.push_back(v);
    }
  }

  ColumnTable t_;
  std::int64_t lineno_ = 0;
};

// Every column any catalogue declares (the OFC automaton's topplings, a lattice's rows):
// a file's own columns are those it has.
const Schema& any_catalog_schema() {
  return catalog_schema(kEveryCatalogColumn);
}

ColumnTable read_h5_catalog(const std::filesystem::path& path) {
  std::vector<std::string> names;
  for (const ColumnSpec& s : any_catalog_schema()) names.emplace_back(s.name);
  CatalogH5Reader reader(path.string(), names);
  ColumnTable t;
  t.file = path.string();
  const auto rows = static_cast<std::size_t>(reader.rows());
  std::vector<std::size_t> present;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (!reader.has(k)) continue;
    present.push_back(k);
    TableColumn c;
    c.name = names[k];
    c.integer = std::string_view(any_catalog_schema()[k].format) == kInteger;
    if (c.integer)
      c.i.reserve(rows);
    else
      c.x.reserve(rows);
    t.columns.push_back(std::move(c));
  }
  // The reader hands every column as doubles (integers up to 2^53 exactly), a row at a time.
  std::vector<double> block;
  while (const std::int64_t n = reader.next_block(block)) {
    for (std::int64_t r = 0; r < n; ++r) {
      const double* v = block.data() + static_cast<std::size_t>(r) * names.size();
      for (std::size_t j = 0; j < present.size(); ++j) {
        TableColumn& c = t.columns[j];
        if (c.integer)
          c.i.push_back(static_cast<std::int64_t>(v[present[j]]));
        else
          c.x.push_back(v[present[j]]);
      }
    }
    t.rows += n;
  }
  return t;
}

}  // namespace

ColumnTable read_csv_table(const std::filesystem::path& path, const Schema& schema) {
  check_input_file(path, "table");
  return CsvTableReader(path, schema).take();
}

ColumnTable read_catalog_table(const std::filesystem::path& path) {
  check_input_file(path, "catalogue");
  if (is_hdf5_file(path.string())) return read_h5_catalog(path);
  return read_csv_table(path, any_catalog_schema());
}

}  // namespace bkq
