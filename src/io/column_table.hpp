// A whole output table read into typed columns, for callers that want every row at once
// (the Python module's bkquake.load) rather than a stream of events (io/catalog_reader.hpp,
// which the statistics use). Column types come from the file's schema (io/schema.hpp): a
// column declared kInteger is read as 64-bit integers, any other as doubles; a column the
// schema does not declare is read as doubles. Each column's storage is sized exactly once
// (the rows are counted first), so reading a table costs the arrays and one read buffer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/schema.hpp"

namespace bkq {

struct TableColumn {
  std::string name;
  bool integer = false;
  std::vector<std::int64_t> i;  // integer columns
  std::vector<double> x;        // the others
};

struct ColumnTable {
  std::string file;
  std::int64_t rows = 0;
  std::vector<TableColumn> columns;  // in the file's column order
};

// A headed CSV (the header names the columns; blank lines are skipped); every problem is a
// bkq::Error naming the file, the line and the column, as the streaming readers say it.
ColumnTable read_csv_table(const std::filesystem::path& path, const Schema& schema);

// An event catalogue, catalog.csv or catalog.h5 (told apart by the file's first bytes).
ColumnTable read_catalog_table(const std::filesystem::path& path);

}  // namespace bkq
