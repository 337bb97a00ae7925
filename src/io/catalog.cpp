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

const Schema& ofc_catalog_schema() {
  namespace c = catalog_col;
  // The common columns keep their names; what they mean for the automaton.
  static const Schema schema = [] {
    Schema s = {
        {c::event, "", "1-based event (avalanche) number, counted after the transient", kInteger},
        {c::load, "stress",
         "cumulative uniform drive at the trigger (threshold F_th = 1); the clock of the "
         "relaxation"},
        {c::trigger, "", "site index x + model.blocks * y of the site driven to the threshold",
         kInteger},
        {c::blocks, "", "number of distinct sites that toppled", kInteger},
        {c::moment, "stress", "total stress released: sum over topplings of the site's stress"},
        {c::magnitude, "", "magnitude mu = ln(moment)"},
        {c::duration, "",
         "generations of the parallel update; with ofc.order = sequential, the depth of the "
         "longest causal chain (1: the trigger alone)"},
        {c::max_speed, "", "0 (the automaton has no speeds)"},
        {c::pad_displacement, "", "0 (no pad)"},
        {c::first_block, "", "lowest site index x + model.blocks * y that toppled", kInteger},
        {c::last_block, "", "highest site index x + model.blocks * y that toppled", kInteger},
        {c::energy_residual, "", "0 (no energy ledger)"},
        {c::topplings, "", "topplings in the avalanche (a site may topple more than once)",
         kInteger},
    };
    return s;
  }();
  return schema;
}

std::string catalog_header(bool with_topplings) {
  return header_of(with_topplings ? ofc_catalog_schema() : catalog_schema());
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

char* catalog_row_to(char* out, const EventRecord& e, bool with_topplings) {
  const CatalogCells cells = catalog_cells(e);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k > 0) *out++ = ',';
    out = cells[k].integer ? integer_to(out, cells[k].i) : format_real_to(out, cells[k].x);
  }
  if (with_topplings) {
    *out++ = ',';
    out = integer_to(out, e.topplings);
  }
  return out;
}

std::string catalog_row(const EventRecord& e, bool with_topplings) {
  char buf[kMaxCatalogRow];
  return std::string(buf, catalog_row_to(buf, e, with_topplings));
}

}  // namespace bkq
