// The event catalogue as a file being written, whatever its format (output.catalog): the
// catalog observer (app/observers/catalog.hpp) writes through this, so a format is one
// implementation here. catalog.csv: rows formatted straight into a large buffer, one
// write per buffer (io/output.hpp CsvStream); catalog.h5: io/catalog_h5.hpp.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/event_record.hpp"
#include "io/catalog.hpp"
#include "io/settings.hpp"

namespace bkq {

// The catalogue's columns for a run of these settings: the OFC automaton's topplings, the row
// columns of a lattice with more than one row, a rate-and-state run's times and peak rate.
inline CatalogLayout catalog_layout(const Settings& s) {
  return {.topplings = s.ofc.on, .rows = s.lattice.ny > 1, .rsf = s.rsf.on};
}

// "catalog.csv", "catalog.h5"; nullptr for CatalogFormat::None.
const char* catalog_file_name(CatalogFormat format);

class CatalogFile {
 public:
  virtual ~CatalogFile() = default;
  virtual void append(const EventRecord& e) = 0;
  // Hands what is buffered to the file (no sync), so readers see every row so far.
  virtual void flush() = 0;
  // Everything appended is on disk when this returns. Returns what a checkpoint records of
  // the file: its size in bytes (csv), or 0 (hdf5, whose rows are the events done).
  virtual std::uint64_t sync() = 0;
  // Syncs and closes; throws on failure. Idempotent.
  virtual void close() = 0;
  // line_hash (core/fnv1a.hpp) of every line of the file so far (csv) or of every row's
  // cells (hdf5); a resumed run sets the checksum of the rows it continues.
  virtual std::optional<std::uint64_t> checksum() const { return std::nullopt; }
  virtual void set_checksum(std::uint64_t) {}
};

// Opens the catalogue at `path` in `format` (not None). A new file gets the header (csv)
// or the `attributes` (hdf5: provenance and effective scene); with `resumed_rows` >= 0 the
// file of a resumed run is continued after its first `resumed_rows` rows (a csv file has
// already been cut back to its checkpoint by then). `deflate`: a new catalog.h5 is
// compressed (output.catalog = hdf5-deflate). `layout`: the columns beyond the common ones
// (the OFC catalogue's topplings, a lattice's rows).
std::unique_ptr<CatalogFile> open_catalog_file(
    CatalogFormat format, const std::string& path,
    const std::vector<std::pair<std::string, std::string>>& attributes,
    std::int64_t resumed_rows = -1, bool deflate = false, CatalogLayout layout = {});

}  // namespace bkq
