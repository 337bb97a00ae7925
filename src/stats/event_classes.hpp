// Event classes of Carlson & Langer (1989) and Carlson et al. (1991) (Ferre 2018 section 2.2:
// "microscopic", "localized" and "delocalized" events), made operational for a chain of
// N blocks. Every event falls in exactly one class, tested in this order:
//   single-block  blocks == 1 (the "microscopic" one-block events);
//   delocalised   the slip reached the chain's ends or spanned it: blocks >= N - 1, or,
//                 with a free boundary, first_block == 0 or last_block == N - 1 (a pulse
//                 that reaches a free end is reflected, the signature of great events);
//   localised     everything else (2 <= blocks < N - 1, away from the free ends).
// With a periodic boundary there are no ends, so only the span criterion applies. The
// boundary is the model's (model/parameters.hpp), so there is one Boundary type.
// On a lattice of nx columns by ny rows (N = nx ny sites; `blocks` counts the sites that
// slipped or toppled) the classes are by sites relative to N and by the event's bounding
// box, whatever the boundaries:
//   single-block  one site;
//   delocalised   at least half the sites (2 blocks >= N), or the bounding box spans the
//                 lattice from edge to edge along strike (all nx columns) or across (all ny
//                 rows): a rupture through the whole fault one way;
//   localised     everything else.
#pragma once

#include <cstdint>

#include "model/parameters.hpp"

namespace bkq {

enum class EventClass { single_block, localised, delocalised };
const char* to_string(EventClass c);

// blocks: number of blocks that slipped; first/last: 0-based lowest/highest index; n: N.
EventClass classify_event(int blocks, int first_block, int last_block, int n, Boundary boundary);
// A lattice of nx x ny sites (ny > 1): columns first_block..last_block and rows
// first_row..last_row, the bounding box of the sites that slipped.
EventClass classify_lattice_event(int blocks, int first_block, int last_block, int first_row,
                                  int last_row, int nx, int ny);

struct EventClassCounts {
  std::int64_t single_block = 0;
  std::int64_t localised = 0;
  std::int64_t delocalised = 0;

  void add(EventClass c);
  std::int64_t total() const { return single_block + localised + delocalised; }
  double fraction(EventClass c) const;
};

}  // namespace bkq
