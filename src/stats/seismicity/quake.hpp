// The event the seismicity statistics see (stats/seismicity/*): a catalogue row reduced to
// time, size, place and extent, with the mainshock class already decided. Time is the
// catalogue's clock (substrate displacement `load` of an event-driven run, the episode
// start of a continuous one); place is a block index along the chain ("along strike"), and
// on a lattice also the row across it.
#pragma once

#include <cmath>
#include <cstdint>

namespace bkq::seis {

struct Quake {
  std::int64_t event = 0;
  double t = 0;             // time (the catalogue's clock)
  double moment = 0;        // M = sum of slips
  double mu = 0;            // ln M
  double duration = 0;      // from trigger to the last re-stick; 0 when the catalogue lacks it
  int trigger = 0;          // hypocentre (block index; a lattice's column x)
  int trigger_row = 0;      // a lattice's hypocentre row y; 0 on a chain
  int first = 0, last = 0;  // the slipped extent; first > last when unknown
  int blocks = 0;           // blocks that slipped; 0 when unknown
  bool mainshock = false;
  bool has_extent() const { return last >= first; }
  int length() const { return has_extent() ? last - first + 1 : blocks; }
};

// Moment magnitude Mw = (2/3) log10 M + const (Hanks & Kanamori 1979, J. Geophys. Res. 84,
// 2348, with M in the model's units and the constant free), and its differences:
// a difference in mu = ln M is 1.5 ln 10 (about 3.45) times the difference in Mw.
inline constexpr double kMuPerMw = 1.5 * 2.302585092994045684;
inline double mw_of_moment(double moment, double offset = 0) {
  return (2.0 / 3.0) * std::log10(moment) + offset;
}

}  // namespace bkq::seis
