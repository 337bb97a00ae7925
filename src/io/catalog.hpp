// The event catalogue: one schema table lists each column once (name, units, meaning);
// that table writes the CSV header and is what the readers (bkquake fit, analysis/*.py)
// rely on. Rows are streamed as events happen.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/event_record.hpp"
#include "io/schema.hpp"

namespace bkq {

// The catalogue's column names, each spelled once: the schema and the readers use these.
namespace catalog_col {
inline constexpr const char* event = "event";
inline constexpr const char* load = "load";
inline constexpr const char* trigger = "trigger";
inline constexpr const char* blocks = "blocks";
inline constexpr const char* moment = "moment";
inline constexpr const char* magnitude = "magnitude";
inline constexpr const char* duration = "duration";
inline constexpr const char* max_speed = "max_speed";
inline constexpr const char* pad_displacement = "pad_displacement";
inline constexpr const char* first_block = "first_block";
inline constexpr const char* last_block = "last_block";
inline constexpr const char* energy_residual = "energy_residual";
inline constexpr const char* topplings = "topplings";  // OFC catalogues only
}  // namespace catalog_col

// The catalogue schema: column order is the CSV column order.
const Schema& catalog_schema();
// The OFC automaton's catalogue (engine/ofc.hpp): the same columns, read as the schema's
// docs say for a lattice of sites, then `topplings`.
const Schema& ofc_catalog_schema();
// "event,load,trigger,..." (no newline); with_topplings: the OFC catalogue's header.
std::string catalog_header(bool with_topplings = false);
// The columns' count, and one row's values in schema order: integer columns in `i`, the
// others in `x`. Every catalogue format writes these.
inline constexpr std::size_t kCatalogColumns = 12;
struct CatalogCell {
  bool integer;
  std::int64_t i;
  double x;
};
using CatalogCells = std::array<CatalogCell, kCatalogColumns>;
CatalogCells catalog_cells(const EventRecord& e);

// One CSV row (no newline): integers as integers, reals shortest round-trip; with_topplings
// appends the OFC catalogue's topplings column.
std::string catalog_row(const EventRecord& e, bool with_topplings = false);
// The longest row catalog_row_to writes.
inline constexpr std::size_t kMaxCatalogRow = 512;
// catalog_row's text written at `out` (room for kMaxCatalogRow); returns the end. The
// streamed catalog formats straight into its write buffer with this.
char* catalog_row_to(char* out, const EventRecord& e, bool with_topplings = false);

}  // namespace bkq
