// Implementation of the event classes (definitions in event_classes.hpp).
#include "stats/event_classes.hpp"

namespace bkq {

const char* to_string(EventClass c) {
  switch (c) {
    case EventClass::single_block:
      return "single_block";
    case EventClass::localised:
      return "localised";
    case EventClass::delocalised:
      return "delocalised";
  }
  return "?";
}

EventClass classify_event(int blocks, int first_block, int last_block, int n, Boundary boundary) {
  if (blocks <= 1) return EventClass::single_block;
  if (blocks >= n - 1) return EventClass::delocalised;
  if (boundary == Boundary::Free && (first_block <= 0 || last_block >= n - 1))
    return EventClass::delocalised;
  return EventClass::localised;
}

EventClass classify_lattice_event(int blocks, int first_block, int last_block, int first_row,
                                  int last_row, int nx, int ny) {
  if (blocks <= 1) return EventClass::single_block;
  const std::int64_t sites = static_cast<std::int64_t>(nx) * ny;
  if (2 * static_cast<std::int64_t>(blocks) >= sites) return EventClass::delocalised;
  if (last_block - first_block + 1 >= nx || last_row - first_row + 1 >= ny)
    return EventClass::delocalised;
  return EventClass::localised;
}

void EventClassCounts::add(EventClass c) {
  switch (c) {
    case EventClass::single_block:
      ++single_block;
      break;
    case EventClass::localised:
      ++localised;
      break;
    case EventClass::delocalised:
      ++delocalised;
      break;
  }
}

double EventClassCounts::fraction(EventClass c) const {
  const std::int64_t n = total();
  if (n == 0) return 0;
  const std::int64_t k = c == EventClass::single_block ? single_block
                         : c == EventClass::localised  ? localised
                                                       : delocalised;
  return static_cast<double>(k) / static_cast<double>(n);
}

}  // namespace bkq
