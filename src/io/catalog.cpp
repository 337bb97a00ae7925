// The event catalogue schema (SPEC §5): each column listed once with its units and
// meaning. catalog_header() and catalog_row() are both driven by the column order here,
// and numbers are written so they read back to the same double.
#include "io/catalog.hpp"

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

std::string catalog_row(const EventRecord& e) {
  // Same order as catalog_schema(); a test checks the two stay in step.
  std::string s;
  s.reserve(200);
  s += std::to_string(e.event);
  s += ',' + format_real(e.load);
  s += ',' + std::to_string(e.trigger);
  s += ',' + std::to_string(e.blocks);
  s += ',' + format_real(e.moment);
  s += ',' + format_real(e.magnitude);
  s += ',' + format_real(e.duration);
  s += ',' + format_real(e.max_speed);
  s += ',' + format_real(e.pad_displacement);
  s += ',' + std::to_string(e.first_block);
  s += ',' + std::to_string(e.last_block);
  s += ',' + format_real(e.energy_residual);
  return s;
}

}  // namespace bkq
