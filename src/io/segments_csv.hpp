// segments.csv: one row per speed segment of a continuous run (Ferre 2018 §4.2, eqs. 4.1-4.4;
// statistics in stats/segment_stats.hpp), columns declared once in segments_schema(): the
// segment, its time span and speed, then for each signal S of kSegmentSignals the mean,
// its block error, the amplitude and its block error. Written by the segment observer,
// read back by `bkquake spectrum --segment`, special-law and the friction study.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/schema.hpp"
#include "stats/segment_stats.hpp"

namespace bkq {

// The signals, in column order: pad friction, pad position, pad velocity.
inline constexpr std::array<const char*, 3> kSegmentSignals = {"pad_friction", "pad_position",
                                                               "pad_velocity"};

struct SegmentRow {
  std::int64_t segment = 0;  // 0-based
  double t_start = 0, t_end = 0, speed = 0;
  std::array<SegmentStat, 3> stats;  // kSegmentSignals order
};

const Schema& segments_schema();
std::string segments_header();
std::string segments_row(const SegmentRow& r);
// Reads every row; bkq::Error naming the file and line on a malformed one.
std::vector<SegmentRow> read_segments_csv(const std::filesystem::path& path);

// The tabulated special friction law (`bkquake special-law`, read by friction.law = table):
// relative speed and friction per unit block mass, speeds increasing.
const Schema& special_law_schema();

// friction_study.csv (`bkquake friction-study`): one row per configuration, seed, run and
// segment, the pad friction statistics and the pad-position amplitude scaled by m_x.
const Schema& friction_study_schema();

// A numeric CSV with a header line (lines starting with '#' skipped): the named columns,
// in the order asked. bkq::Error "<file>: missing column '<name>'" or on a bad number.
std::vector<std::vector<double>> read_numeric_columns(const std::filesystem::path& path,
                                                      const std::vector<std::string>& names);

}  // namespace bkq
