// Streaming reader of an event catalogue (catalog.csv or catalog.h5, told apart by the
// file's first bytes; schema in io/catalog.hpp) for the
// statistics: rows are read one at a time, columns are found by the names catalog_schema()
// declares (no column order is assumed), and every problem is a bkq::Error that names the
// file and the line, e.g. "catalog.csv line 17: moment must be > 0, got -0.3".
// Required: a header line and the column `moment` (or, failing that, `magnitude`).
// Optional: event, load, trigger, blocks, duration, first_block, last_block (the event
// classes need blocks and the extent; bkquake seismicity the others), and a lattice's
// trigger_row, first_row, last_row; an OFC catalogue's topplings. The magnitude used is
// ln(moment) (Ferre 2018 eq. 2.6). A row is refused when a time (load) or duration is not
// finite, an index is not in [0, 1e9], or first_block > last_block (first_row > last_row):
// bkquake writes the lowest and highest block that slipped.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/event_record.hpp"

namespace bkq {

// A catalogue row read back; the columns a file lacks stay 0.
using CatalogEvent = EventRecord;

class CatalogH5Reader;

class CatalogReader {
 public:
  explicit CatalogReader(const std::filesystem::path& path);
  ~CatalogReader();
  // Reads the next event; false at the end of the file. Blank lines are skipped.
  bool next(CatalogEvent& e);
  bool has_extent() const { return c_blocks_ >= 0 && c_first_ >= 0 && c_last_ >= 0; }
  bool has_load() const { return c_load_ >= 0; }
  bool has_trigger() const { return c_trigger_ >= 0; }
  bool has_duration() const { return c_duration_ >= 0; }
  bool has_topplings() const { return c_topplings_ >= 0; }  // an OFC catalogue
  // A lattice's catalogue (model.rows > 1): trigger_row, first_row and last_row.
  bool has_rows() const { return c_trigger_row_ >= 0 && c_first_row_ >= 0 && c_last_row_ >= 0; }
  std::int64_t events_read() const { return events_; }
  // The catalogue of a run still writing it: a last row without its line end is the row
  // being written, and ends the reading instead of being refused as a cut.
  void set_growing() { growing_ = true; }
  // Where the last event read stands, for a message: "<file> line 17" ("row 17" in HDF5).
  std::string where() const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::ifstream in_;
  std::string line_;
  std::int64_t lineno_ = 1;
  std::int64_t events_ = 0;
  bool growing_ = false;
  std::size_t n_fields_ = 0;
  int c_event_ = -1, c_load_ = -1, c_blocks_ = -1, c_first_ = -1, c_last_ = -1;
  int c_moment_ = -1, c_magnitude_ = -1, c_trigger_ = -1, c_duration_ = -1;
  int c_trigger_row_ = -1, c_first_row_ = -1, c_last_row_ = -1, c_topplings_ = -1;
  // Refuses a row no run writes (see the file comment), naming `where`.
  void check_row(const CatalogEvent& e, const std::string& where) const;
  // catalog.h5: the columns in the order of the c_ indices above, read a block at a time.
  bool next_h5(CatalogEvent& e);
  std::unique_ptr<CatalogH5Reader> h5_;
  std::vector<double> block_;
  std::size_t block_row_ = 0, block_rows_ = 0;
};

// bkq::Error "<file>: need at least 2 events to fit, found <n>" when n < 2.
void require_events_to_fit(const std::string& file, std::int64_t n);

}  // namespace bkq
