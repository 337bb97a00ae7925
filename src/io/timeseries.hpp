// The continuous run's sampled signals (timeseries.csv) and block trajectories
// (blocks.csv). The time-series columns are declared once in a schema that writes the
// header; rows are streamed every output.every.
#pragma once

#include <string>
#include <vector>

#include "io/schema.hpp"

namespace bkq {

// One sample of a continuous run, in the column order of timeseries_schema().
struct TimeSeriesRow {
  double t = 0, speed = 0, substrate = 0, pad_x = 0, pad_v = 0, pad_friction = 0;
  int sliding = 0;
};

const Schema& timeseries_schema();
// "t,speed,substrate,pad_x,pad_v,pad_friction,sliding" (no newline).
std::string timeseries_header();
// One CSV row (no newline), numbers printed round-trip exactly.
std::string timeseries_row(const TimeSeriesRow& r);

// Node status (Sinou, Chiello & Charroyer 2019 §4.3.4): the columns output.status = true appends
// to timeseries.csv: blocks stuck, sliding with positive relative velocity (the disc drags
// them) and with negative relative velocity (backslip); they add up to N.
struct NodeStatus {
  int stuck = 0, forward = 0, backward = 0;
};
const Schema& timeseries_status_schema();
// ",stuck,slip_forward,slip_backward" and ",<stuck>,<forward>,<backward>": appended to
// the header and each row.
std::string status_header_suffix();
std::string status_row_suffix(const NodeStatus& n);

// blocks.csv: one row of lab-frame displacements (and velocities) per sample.
std::string blocks_row(double t, const std::vector<double>& u);
// blocks.csv of the blocks first .. first+count-1 with their lab-frame velocities:
// "t,u{first},...,v{first},..." (output.block_first, output.block_count).
std::string blocks_header(int first, int count);
std::string blocks_row(double t, const std::vector<double>& u, const std::vector<double>& v);

}  // namespace bkq
