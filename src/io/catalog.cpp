// The event catalogue schema: each column listed once with its units and
// meaning. catalog_header() and catalog_row() are both driven by the column order here,
// and numbers are written so they read back to the same double.
#include "io/catalog.hpp"

#include <charconv>

#include "core/format.hpp"
#include "io/json.hpp"

namespace bkq {

namespace {

// A column beyond the common ones, declared once: its schema entry and the record's cell.
struct ExtraColumn {
  ColumnSpec spec;
  CatalogCell (*cell)(const EventRecord&);
};
using ExtraColumns = std::vector<ExtraColumn>;

CatalogCell integer_cell(std::int64_t i) {
  return {true, i, 0};
}
CatalogCell real_cell(double x) {
  return {false, 0, x};
}

const ExtraColumns& topplings_column() {
  static const ExtraColumns c = {
      {{catalog_col::topplings, "", "topplings in the avalanche (a site may topple more than once)",
        kInteger},
       [](const EventRecord& e) { return integer_cell(e.topplings); }},
  };
  return c;
}

const ExtraColumns& row_columns() {
  namespace c = catalog_col;
  // The event's bounding box is [first_block, last_block] x [first_row, last_row]: the
  // lowest and highest coordinates, also on a periodic axis (an event across the seam
  // spans the whole axis there).
  static const ExtraColumns s = {
      {{c::trigger_row, "", "row y (0-based, across strike) of the trigger; model.rows > 1 only",
        kInteger},
       [](const EventRecord& e) { return integer_cell(e.trigger_row); }},
      {{c::first_row, "", "lowest row y that slipped; model.rows > 1 only", kInteger},
       [](const EventRecord& e) { return integer_cell(e.first_row); }},
      {{c::last_row, "", "highest row y that slipped; model.rows > 1 only", kInteger},
       [](const EventRecord& e) { return integer_cell(e.last_row); }},
  };
  return s;
}

const ExtraColumns& rsf_columns() {
  namespace c = catalog_col;
  static const ExtraColumns s = {
      {{c::hypocentre_time, "s",
        "time of the first crossing of rsf.v_threshold (load = drive.speed x this); "
        "friction.law = rsf only"},
       [](const EventRecord& e) { return real_cell(e.hypocentre_time); }},
      {{c::peak_time, "s", "time of the event's peak slip rate; friction.law = rsf only"},
       [](const EventRecord& e) { return real_cell(e.peak_time); }},
      {{c::peak_slip_rate, "m/s",
        "the event's peak slip rate of any block (max_speed in the law's units); friction.law = "
        "rsf only"},
       [](const EventRecord& e) { return real_cell(e.max_speed); }},
  };
  return s;
}

// The layout's extra columns in order.
std::vector<const ExtraColumns*> extras_of(CatalogLayout layout) {
  std::vector<const ExtraColumns*> x;
  if (layout.topplings) x.push_back(&topplings_column());
  if (layout.rows) x.push_back(&row_columns());
  if (layout.rsf) x.push_back(&rsf_columns());
  return x;
}

Schema specs_of(const ExtraColumns& c) {
  Schema s;
  for (const auto& x : c) s.push_back(x.spec);
  return s;
}

}  // namespace

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
        {c::trigger, "",
         "column x (0-based, along strike) of the site driven to the threshold; its row is "
         "trigger_row",
         kInteger},
        {c::blocks, "", "number of distinct sites that toppled", kInteger},
        {c::moment, "stress", "total stress released: sum over topplings of the site's stress"},
        {c::magnitude, "", "magnitude mu = ln(moment)"},
        {c::duration, "",
         "generations of the parallel update; with ofc.order = sequential, the depth of the "
         "longest causal chain (1: the trigger alone)"},
        {c::max_speed, "", "0 (the automaton has no speeds)"},
        {c::pad_displacement, "", "0 (no pad)"},
        {c::first_block, "", "lowest column x that toppled", kInteger},
        {c::last_block, "", "highest column x that toppled", kInteger},
        {c::energy_residual, "", "0 (no energy ledger)"},
    };
    s.push_back(topplings_column()[0].spec);
    return s;
  }();
  return schema;
}

const Schema& lattice_row_columns() {
  static const Schema s = specs_of(row_columns());
  return s;
}

const Schema& rsf_catalog_columns() {
  static const Schema s = specs_of(rsf_columns());
  return s;
}

const Schema& catalog_schema(CatalogLayout layout) {
  // One schema per layout (2^3), built on first use from the declarations above.
  static const std::array<Schema, 8> schemas = [] {
    std::array<Schema, 8> all;
    for (int bits = 0; bits < 8; ++bits) {
      const CatalogLayout l{
          .topplings = (bits & 1) != 0, .rows = (bits & 2) != 0, .rsf = (bits & 4) != 0};
      // The OFC schema already ends with topplings.
      Schema s = l.topplings ? ofc_catalog_schema() : catalog_schema();
      for (const ExtraColumns* x : extras_of(l))
        if (x != &topplings_column())
          for (const auto& c : *x) s.push_back(c.spec);
      all[bits] = std::move(s);
    }
    return all;
  }();
  return schemas[(layout.topplings ? 1 : 0) | (layout.rows ? 2 : 0) | (layout.rsf ? 4 : 0)];
}

std::string catalog_header(CatalogLayout layout) {
  return header_of(catalog_schema(layout));
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

std::size_t catalog_extra_cells(const EventRecord& e, CatalogLayout layout, CatalogCell* out) {
  // Same order as catalog_schema(layout) after the common columns.
  std::size_t n = 0;
  for (const ExtraColumns* x : extras_of(layout))
    for (const auto& c : *x) out[n++] = c.cell(e);
  return n;
}

char* catalog_row_to(char* out, const EventRecord& e, CatalogLayout layout) {
  const CatalogCells cells = catalog_cells(e);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k > 0) *out++ = ',';
    out = cells[k].integer ? integer_to(out, cells[k].i) : format_real_to(out, cells[k].x);
  }
  CatalogCell extra[kMaxExtraColumns];
  const std::size_t n = catalog_extra_cells(e, layout, extra);
  for (std::size_t k = 0; k < n; ++k) {
    *out++ = ',';
    out = extra[k].integer ? integer_to(out, extra[k].i) : format_real_to(out, extra[k].x);
  }
  return out;
}

std::string catalog_row(const EventRecord& e, CatalogLayout layout) {
  char buf[kMaxCatalogRow];
  return std::string(buf, catalog_row_to(buf, e, layout));
}

}  // namespace bkq
