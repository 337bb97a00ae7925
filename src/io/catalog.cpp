// The event catalogue schema: each column listed once with its units and
// meaning. catalog_header() and catalog_row() are both driven by the column order here,
// and numbers are written so they read back to the same double.
#include "io/catalog.hpp"

#include <charconv>

#include "core/format.hpp"
#include "io/json.hpp"

namespace bkq {

const Schema& catalog_schema() {
  namespace c = catalog_col;
  static const Schema schema = {
      {c::event, "", "1-based event number, counted after the transient", kInteger},
      {c::load, "length", "substrate displacement at the trigger"},
      {c::trigger, "", "0-based index of the block that failed first", kInteger},
      {c::blocks, "", "number of distinct blocks that slipped", kInteger},
      {c::moment, "length", "moment M = sum over blocks of their slip"},
      {c::magnitude, "", "magnitude mu = ln M"},
      {c::duration, "time", "time from the trigger until the last block re-stuck"},
      {c::max_speed, "length/time", "largest |relative velocity| of any block during the event"},
      {c::pad_displacement, "length", "change of the pad position over the event (0 for bk)"},
      {c::first_block, "", "lowest block index that slipped", kInteger},
      {c::last_block, "", "highest block index that slipped", kInteger},
      {c::energy_residual, "",
       "(change of stored energy + work against friction and dampers) / that work; 0 for an exact "
       "integration"},
  };
  return schema;
}

std::string catalog_header() {
  return header_of(catalog_schema());
}

namespace {

char* integer_to(char* out, std::int64_t v) {
  return std::to_chars(out, out + 24, v).ptr;
}

}  // namespace

CatalogCells catalog_cells(const EventRecord& e) {
  // Same order as catalog_schema(); a test checks the two stay in step.
  return {{{true, e.event, 0},
           {false, 0, e.load},
           {true, e.trigger, 0},
           {true, e.blocks, 0},
           {false, 0, e.moment},
           {false, 0, e.magnitude},
           {false, 0, e.duration},
           {false, 0, e.max_speed},
           {false, 0, e.pad_displacement},
           {true, e.first_block, 0},
           {true, e.last_block, 0},
           {false, 0, e.energy_residual}}};
}

char* catalog_row_to(char* out, const EventRecord& e) {
  const CatalogCells cells = catalog_cells(e);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k > 0) *out++ = ',';
    out = cells[k].integer ? integer_to(out, cells[k].i) : format_real_to(out, cells[k].x);
  }
  return out;
}

std::string catalog_row(const EventRecord& e) {
  char buf[kMaxCatalogRow];
  return std::string(buf, catalog_row_to(buf, e));
}

}  // namespace bkq
