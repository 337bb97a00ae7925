// histogram.csv: mu_low,mu_high,count,D,R,D_rate,R_rate, one row per bin from the first
// to the last populated bin (empty bins in between included). The rate columns are "nan"
// when the loading is unknown.
#pragma once

#include <filesystem>
#include <string>

#include "stats/histogram.hpp"

namespace bkq {

std::string histogram_csv(const MagnitudeHistogram& h);
void write_histogram_csv(const MagnitudeHistogram& h, const std::filesystem::path& path);
// Reads a histogram.csv written by write_histogram_csv (columns found by header name; only
// mu_low, mu_high and count are used). The bin width is taken from the file and must agree
// with bin_width when that is > 0. Loading comes from the caller (summary.json).
MagnitudeHistogram read_histogram_csv(const std::filesystem::path& path, double total_load,
                                      int blocks, double bin_width = 0);

}  // namespace bkq
