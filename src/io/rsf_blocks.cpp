// Reading per-block rate-and-state parameters; see rsf_blocks.hpp.
#include "io/rsf_blocks.hpp"

#include <cmath>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "io/csv_util.hpp"
#include "io/input_file.hpp"

namespace bkq {

std::vector<rsf::Params> read_rsf_blocks(const std::filesystem::path& path, int blocks,
                                         const rsf::Params& base) {
  const std::string file = path.string();
  const std::string what = "rsf.blocks file";
  std::ifstream f = open_input(path, what);
  const auto at = [&](std::int64_t line) { return file + " line " + std::to_string(line) + ": "; };
  const auto skipped = [](const std::string& l) {
    const auto first = l.find_first_not_of(" \t\r");
    return first == std::string::npos || l[first] == '#';
  };
  std::string line;
  std::int64_t lineno = 0;
  while (std::getline(f, line) && (++lineno, skipped(line))) line.clear();
  check_read(f, path, what, lineno);
  const std::string header = "block,a,b,dc";
  std::string got = line;
  std::erase_if(got, [](char c) { return c == ' ' || c == '\t' || c == '\r'; });
  if (got != header)
    throw Error(at(lineno) + "expected the header '" + header + "', got '" + line + "'");
  std::vector<rsf::Params> out;
  while (std::getline(f, line)) {
    ++lineno;
    if (skipped(line)) continue;
    const auto fields = csv::split(line);
    if (fields.size() != 4)
      throw Error(at(lineno) + "expected 4 fields (block,a,b,dc), got " +
                  std::to_string(fields.size()));
    const double block = csv::parse_double(fields[0], file, lineno, "block");
    if (block != static_cast<double>(out.size()))
      throw Error(at(lineno) + "block " + std::string(fields[0]) + ": expected block " +
                  std::to_string(out.size()) + " (one row per block, in order)");
    if (static_cast<int>(out.size()) == blocks)
      throw Error(at(lineno) + "more rows than the chain's " + std::to_string(blocks) + " blocks");
    rsf::Params p = base;
    p.a = csv::parse_double(fields[1], file, lineno, "a");
    p.b_rsf = csv::parse_double(fields[2], file, lineno, "b");
    p.dc = csv::parse_double(fields[3], file, lineno, "dc");
    if (!(std::isfinite(p.a) && p.a > 0 && p.a <= 10))
      throw Error(at(lineno) + "a: expected a value in (0, 10], got " + std::string(fields[1]));
    if (!(std::isfinite(p.b_rsf) && p.b_rsf >= 0 && p.b_rsf <= 10))
      throw Error(at(lineno) + "b: expected a value in [0, 10], got " + std::string(fields[2]));
    if (!(std::isfinite(p.dc) && p.dc > 0 && p.dc <= 1e6))
      throw Error(at(lineno) + "dc: expected a value in (0, 1e+06], got " + std::string(fields[3]));
    out.push_back(p);
  }
  check_read(f, path, what, lineno);
  if (static_cast<int>(out.size()) != blocks)
    throw Error(file + ": " + std::to_string(out.size()) + " rows, expected one per block (" +
                std::to_string(blocks) + ")");
  return out;
}

const Schema& slow_slip_schema() {
  static const Schema s = {
      {"episode", "", "1-based episode number", kInteger},
      {"kind", "",
       "slow (some block above rsf.slow_slip_threshold, none reaching rsf.v_threshold) or "
       "afterslip (the same after a seismic event's end, counted from that end)",
       kText},
      {"start", "s",
       "time the episode starts (first crossing of the slow threshold, or the "
       "event's end for afterslip)"},
      {"duration", "s", "until the last block falls below the slow threshold"},
      {"blocks", "", "blocks that slipped faster than the slow threshold", kInteger},
      {"moment", "m", "sum over those blocks of their slip over the episode"},
      {"peak_slip_rate", "m/s", "largest slip rate of any block in the episode"},
      {"peak_time", "s", "time of that peak"},
      {"trigger", "", "block (x along strike) that crossed first", kInteger},
      {"first_block", "", "lowest x that slipped", kInteger},
      {"last_block", "", "highest x that slipped", kInteger},
      {"trigger_row", "", "row y of the trigger (0 on a chain)", kInteger},
      {"first_row", "", "lowest row y that slipped (0 on a chain)", kInteger},
      {"last_row", "", "highest row y that slipped (0 on a chain)", kInteger},
  };
  return s;
}

}  // namespace bkq
