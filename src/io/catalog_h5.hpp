// The event catalogue as HDF5 (output.catalog = hdf5 or hdf5-deflate): catalog.h5 holds
// one table, the dataset "catalog", whose compound rows have the columns of
// catalog_schema() in order (the OFC automaton's, ofc_catalog_schema(), adds topplings;
// integer columns as 64-bit integers, the others as doubles), in
// chunks of 8192 rows: stored as they are (hdf5, the cheap one) or shuffled and deflated
// (hdf5-deflate: a quarter of the size at several times the cost; docs/validation/performance.md).
// The provenance lines and the effective scene are attributes of the dataset
// ("provenance", "scene"). Readable by any HDF5 reader, e.g. Debian's python3-h5py:
// h5py.File("catalog.h5")["catalog"][:] is a structured array.
//
// Written in HDF5's single-writer mode (SWMR, file format 1.10): the file on disk is
// consistent at every moment, so a run killed with SIGKILL leaves a file that a resume can
// open; the resume cuts the table back to the rows of its checkpoint. Every HDF5 call is
// checked and HDF5's own error printing is off: a damaged or foreign file is a bkq::Error
// of one line naming it. Without HDF5 at build time every function here throws that
// output.catalog = hdf5 is not available.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/event_record.hpp"
#include "io/catalog.hpp"

namespace bkq {

// Whether this build has HDF5.
bool hdf5_available();

// True when the file at `path` begins with the HDF5 signature.
bool is_hdf5_file(const std::string& path);

class CatalogH5Writer {
 public:
  // Creates catalog.h5 at `path` with `attributes` (name, text) on the table, compressed
  // (shuffle + deflate at `deflate_level`) when deflate_level > 0; or, with `append_after`
  // >= 0, opens the existing file of a resumed run (whose compression stays), checks its
  // table and cuts it back to its first `append_after` rows.
  CatalogH5Writer(const std::string& path,
                  const std::vector<std::pair<std::string, std::string>>& attributes,
                  std::int64_t append_after = -1, int deflate_level = 0, CatalogLayout layout = {});
  ~CatalogH5Writer();
  CatalogH5Writer(const CatalogH5Writer&) = delete;
  CatalogH5Writer& operator=(const CatalogH5Writer&) = delete;

  void append(const EventRecord& e);
  // line_hash (core/fnv1a.hpp) of every row's bytes (the row type's 8-byte cells as written)
  // from the first row on; a resumed writer starts from the checkpoint's value.
  std::uint64_t checksum() const;
  void set_checksum(std::uint64_t sum);
  // Writes the buffered rows and flushes the file to disk; returns the rows in the table.
  std::int64_t sync();
  // sync(), then closes; idempotent.
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Checks that `path` is a catalogue table with at least `rows` rows and, with `checksum`,
// that those rows hash to it (CatalogH5Writer::checksum: an edited row is found, as in
// catalog.csv; `layout`: the columns the rows have beyond the common ones; a table with
// other columns is refused); a resume's check, before anything is
// changed. bkq::Error naming the file.
void check_catalog_h5(const std::string& path, std::int64_t rows,
                      std::optional<std::uint64_t> checksum = std::nullopt,
                      CatalogLayout layout = {});

// Reads the columns `names` (each must be a column of the catalogue schema) of a catalog.h5
// in blocks. A column the file lacks is reported by has(); reading it gives nothing.
class CatalogH5Reader {
 public:
  CatalogH5Reader(const std::string& path, const std::vector<std::string>& names);
  ~CatalogH5Reader();
  CatalogH5Reader(const CatalogH5Reader&) = delete;
  CatalogH5Reader& operator=(const CatalogH5Reader&) = delete;

  bool has(std::size_t column) const;
  std::int64_t rows() const;
  // Reads the next block of rows into `out` (row-major, names.size() doubles a row;
  // integers converted to double); returns the number of rows read, 0 at the end.
  std::int64_t next_block(std::vector<double>& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bkq
