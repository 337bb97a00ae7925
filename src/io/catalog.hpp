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
// Lattices of more than one row only (model.rows > 1).
inline constexpr const char* trigger_row = "trigger_row";
inline constexpr const char* first_row = "first_row";
inline constexpr const char* last_row = "last_row";
// Rate-and-state runs only (friction.law = rsf).
inline constexpr const char* hypocentre_time = "hypocentre_time";
inline constexpr const char* peak_time = "peak_time";
inline constexpr const char* peak_slip_rate = "peak_slip_rate";
}  // namespace catalog_col

// Which columns a catalogue has beyond the common ones: `topplings` (the OFC automaton),
// the rows of a lattice with more than one row (trigger_row, first_row, last_row), and a
// rate-and-state run's times and peak slip rate (hypocentre_time, peak_time,
// peak_slip_rate), in that order. A chain or a single row writes no row columns, so its
// catalogue keeps the columns it always had.
struct CatalogLayout {
  bool topplings = false;
  bool rows = false;
  bool rsf = false;
  std::size_t extra_columns() const { return (topplings ? 1 : 0) + (rows ? 3 : 0) + (rsf ? 3 : 0); }
  bool operator==(const CatalogLayout&) const = default;
};
// Every column any catalogue declares: what the readers look for.
inline constexpr CatalogLayout kEveryCatalogColumn{.topplings = true, .rows = true, .rsf = true};

// The catalogue schema: column order is the CSV column order.
const Schema& catalog_schema();
// The OFC automaton's catalogue (engine/ofc.hpp): the same columns, read as the schema's
// docs say for a lattice of sites, then `topplings`.
const Schema& ofc_catalog_schema();
// The schema of a layout: catalog_schema() or ofc_catalog_schema(), then the row columns
// when layout.rows.
const Schema& catalog_schema(CatalogLayout layout);
// The three row columns, as every layout with rows declares them.
const Schema& lattice_row_columns();
// The rate-and-state columns, as a layout with rsf declares them.
const Schema& rsf_catalog_columns();
// "event,load,trigger,..." (no newline) of a layout.
std::string catalog_header(CatalogLayout layout = {});
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

// One CSV row (no newline): integers as integers, reals shortest round-trip; the layout's
// extra columns after the common ones.
std::string catalog_row(const EventRecord& e, CatalogLayout layout = {});
// The longest row catalog_row_to writes.
inline constexpr std::size_t kMaxCatalogRow = 512;
// catalog_row's text written at `out` (room for kMaxCatalogRow); returns the end. The
// streamed catalog formats straight into its write buffer with this.
char* catalog_row_to(char* out, const EventRecord& e, CatalogLayout layout = {});
// The layout's extra cells (integers and reals) in schema order; returns how many (at most
// kMaxExtraColumns).
inline constexpr std::size_t kMaxExtraColumns = 7;
std::size_t catalog_extra_cells(const EventRecord& e, CatalogLayout layout, CatalogCell* out);

}  // namespace bkq
