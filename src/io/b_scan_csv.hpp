// b_scan.csv, written by `bkquake fit --scan`: the binned maximum-likelihood b of every
// window between populated bins (stats/gutenberg_richter.hpp, scan_windows), and whether the
// automatic method counts it among the windows of b's systematic error. Columns declared
// once in b_scan_schema(); numbers shortest round-trip, empty when not finite.
#pragma once

#include <string>
#include <vector>

#include "io/schema.hpp"
#include "stats/gutenberg_richter.hpp"

namespace bkq {

const Schema& b_scan_schema();
std::string b_scan_csv(const std::vector<WindowFit>& rows);

}  // namespace bkq
