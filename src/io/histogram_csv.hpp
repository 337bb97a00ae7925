// histogram.csv: the columns of histogram_schema(), one row per bin from the first to the
// last populated bin (empty bins in between included). Bin edges are printed %.12g, counts
// as integers, the other numbers shortest round-trip; the rate columns are "nan" when the
// loading is unknown.
#pragma once

#include <filesystem>
#include <string>

#include "io/schema.hpp"
#include "stats/histogram.hpp"

namespace bkq {

// Column order is the CSV column order.
const Schema& histogram_schema();

std::string histogram_csv(const MagnitudeHistogram& h);
void write_histogram_csv(const MagnitudeHistogram& h, const std::filesystem::path& path);
// Reads a histogram.csv written by write_histogram_csv (columns found by the schema's names;
// only mu_low, mu_high and count are used). The bin width is taken from the file and must agree
// with bin_width when that is > 0. Loading comes from the caller (summary.json).
MagnitudeHistogram read_histogram_csv(const std::filesystem::path& path, double total_load,
                                      int blocks, double bin_width = 0);

}  // namespace bkq
