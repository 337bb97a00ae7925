// The event catalogue: one schema table lists each column once (name, units, meaning);
// that table writes the CSV header and is what the readers (bkquake fit, analysis/*.py)
// rely on. Rows are streamed as events happen.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/event_record.hpp"
#include "io/schema.hpp"

namespace bkq {

// The catalogue schema: column order is the CSV column order.
const Schema& catalog_schema();
// "event,load,trigger,..." (no newline).
std::string catalog_header();
// One CSV row (no newline), numbers printed round-trip exactly (%.17g or shortest).
std::string catalog_row(const EventRecord& e);

}  // namespace bkq
