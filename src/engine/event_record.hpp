// What the engine reports about one slip event (event mode) or one slip episode of a
// continuous run. The catalogue's columns (io/catalog.hpp) are these fields.
#pragma once

#include <algorithm>
#include <cstdint>

namespace bkq {

struct EventRecord {
  std::int64_t event = 0;       // 1-based event number (after the transient)
  double load = 0;              // substrate displacement at the trigger
  int trigger = 0;              // 0-based index of the block that failed first
  int blocks = 0;               // number of distinct blocks that slipped
  double moment = 0;            // M = sum_j delta u_j
  double magnitude = 0;         // mu = ln M
  double duration = 0;          // from trigger until the last block re-stuck
  double max_speed = 0;         // largest |relative velocity| of any block during the event
  double pad_displacement = 0;  // change of pad position over the event (0 for BK)
  int first_block = 0;          // lowest index that slipped
  int last_block = 0;           // highest index that slipped
  double energy_residual = 0;   // (dE_stored + W_dissipated)/W_dissipated; see event_engine.hpp
  std::int64_t topplings = 0;   // OFC (engine/ofc.hpp): topplings in the avalanche; 0 otherwise
  // Lattices (engine/ofc.hpp): the row (across strike) of the trigger and the lowest and
  // highest row that slipped; trigger, first_block and last_block are then read along
  // strike. 0 on a chain or a single row.
  int trigger_row = 0;
  int first_row = 0;
  int last_row = 0;
  // Rate-and-state runs (engine/rsf_events.hpp): the times [s] of the first crossing of the
  // seismic slip rate and of the peak slip rate. 0 otherwise.
  double hypocentre_time = 0;
  double peak_time = 0;
};

// An event of a lattice of one column, which ran as the chain along y
// (model/parameters.hpp: line_as_chain): the chain's blocks are the column's rows.
inline void place_on_column(EventRecord& e) {
  e.trigger_row = e.trigger;
  e.first_row = e.first_block;
  e.last_row = e.last_block;
  e.trigger = e.first_block = e.last_block = 0;
}

// A lattice's event (sites j = y nx + x): the trigger and the bounding box of the sites
// that slipped, read as (x along strike, y across).
template <class Sites>
void place_on_lattice(EventRecord& e, int trigger, const Sites& slipped, int nx) {
  e.trigger = trigger % nx;
  e.trigger_row = trigger / nx;
  e.first_block = nx;
  e.last_block = -1;
  e.first_row = e.last_row = trigger / nx;
  for (int j : slipped) {
    e.first_block = std::min(e.first_block, j % nx);
    e.last_block = std::max(e.last_block, j % nx);
    e.first_row = std::min(e.first_row, j / nx);
    e.last_row = std::max(e.last_row, j / nx);
  }
}

}  // namespace bkq
