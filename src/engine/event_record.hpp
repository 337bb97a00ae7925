// What the engine reports about one slip event (event mode) or one slip episode of a
// continuous run. The catalogue's columns (io/catalog.hpp) are these fields.
#pragma once

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
};

}  // namespace bkq
