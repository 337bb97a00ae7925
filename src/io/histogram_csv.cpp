// histogram.csv, written and read: the columns of histogram_schema(), bin edges printed
// %.12g, the other numbers shortest round-trip. The histogram itself (stats/histogram.hpp)
// knows no file format.
#include "io/histogram_csv.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/csv_util.hpp"
#include "io/input_file.hpp"

namespace bkq {

namespace {
// The column names, each spelled once: the schema and the reader below use these.
namespace histogram_col {
constexpr const char* mu_low = "mu_low";
constexpr const char* mu_high = "mu_high";
constexpr const char* count = "count";
constexpr const char* D = "D";
constexpr const char* R = "R";
constexpr const char* D_rate = "D_rate";
constexpr const char* R_rate = "R_rate";
}  // namespace histogram_col

constexpr const char* kEdgeFormat = "%.12g";  // the edges are multiples of the bin width

std::string edge(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, kEdgeFormat, x);
  return buf;
}
}  // namespace

const Schema& histogram_schema() {
  namespace c = histogram_col;
  static const Schema schema = {
      {c::mu_low, "", "lower edge of the magnitude bin", kEdgeFormat},
      {c::mu_high, "", "upper edge of the magnitude bin", kEdgeFormat},
      {c::count, "", "events with mu_low <= magnitude < mu_high", kInteger},
      {c::D, "", "D(mu): events per unit magnitude, count / bin width"},
      {c::R, "", "R(mu): events with magnitude >= mu_low", kInteger},
      {c::D_rate, "1/length", "D per unit substrate loading per block (nan when unknown)"},
      {c::R_rate, "1/length", "R per unit substrate loading per block (nan when unknown)"},
  };
  return schema;
}

std::string histogram_csv(const MagnitudeHistogram& h) {
  std::ostringstream out;
  out << header_of(histogram_schema()) << '\n';
  if (h.empty()) return out.str();
  const double norm = h.rate_norm();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::int64_t r = h.events();
  for (std::int64_t k = h.first_bin(); k <= h.last_bin(); ++k) {
    const std::int64_t c = h.count(k);
    const double d = static_cast<double>(c) / h.bin_width();
    const double rr = static_cast<double>(r);
    out << edge(h.mu_low(k)) << ',' << edge(h.mu_high(k)) << ',' << c << ',' << format_real(d)
        << ',' << r << ',' << format_real(norm > 0 ? d / norm : nan) << ','
        << format_real(norm > 0 ? rr / norm : nan) << '\n';
    r -= c;
  }
  return out.str();
}

void write_histogram_csv(const MagnitudeHistogram& h, const std::filesystem::path& path) {
  std::ofstream f(path);
  if (!f) throw Error(path.string() + ": cannot open for writing");
  f << histogram_csv(h);
  if (!f) throw Error(path.string() + ": write failed");
}

MagnitudeHistogram read_histogram_csv(const std::filesystem::path& path, double total_load,
                                      int blocks, double bin_width) {
  const std::string file = path.string();
  std::ifstream f = open_input(path, "histogram");
  std::string header_line;
  if (!std::getline(f, header_line)) {
    check_read(f, path, "histogram", 0);
    throw Error(file + ": empty file, expected a header line");
  }
  const auto header = csv::split(header_line);
  namespace col = histogram_col;
  const Schema& schema = histogram_schema();
  const int c_lo = csv::require_column(header, schema, col::mu_low, file);
  const int c_hi = csv::require_column(header, schema, col::mu_high, file);
  const int c_n = csv::require_column(header, schema, col::count, file);

  struct Row {
    double lo, hi;
    std::int64_t n;
    std::int64_t line;
  };
  std::vector<Row> rows;
  std::string line;
  std::int64_t lineno = 1;
  while (std::getline(f, line)) {
    ++lineno;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = csv::split(line);
    if (fields.size() != header.size())
      throw Error(file + " line " + std::to_string(lineno) + ": expected " +
                  std::to_string(header.size()) + " fields, got " + std::to_string(fields.size()));
    auto field = [&](int c) { return fields[static_cast<std::size_t>(c)]; };
    const Row r{csv::parse_double(field(c_lo), file, lineno, col::mu_low),
                csv::parse_double(field(c_hi), file, lineno, col::mu_high),
                csv::parse_int(field(c_n), file, lineno, col::count), lineno};
    if (r.n < 0)
      throw Error(file + " line " + std::to_string(lineno) + ": " + std::string(col::count) +
                  " must be >= 0, got " + std::to_string(r.n));
    rows.push_back(r);
  }
  check_read(f, path, "histogram", lineno);
  double w = bin_width;
  if (!rows.empty()) {
    const double wf = rows.front().hi - rows.front().lo;
    if (w > 0 && std::fabs(wf - w) > 1e-9 * std::max(1.0, w))
      throw Error(file + ": bin width " + format_real(wf) + " differs from the expected " +
                  format_real(w));
    if (!(w > 0)) w = std::round(wf * 1e9) / 1e9;  // undo the %.12g rounding of the edges
  }
  if (!(w > 0)) w = MagnitudeHistogram::kDefaultBinWidth;
  std::vector<MagnitudeHistogram::Bin> bins;
  for (const Row& r : rows) {
    const auto k = static_cast<std::int64_t>(std::llround(r.lo / w));
    if (std::fabs(r.lo - static_cast<double>(k) * w) > 1e-6 * w ||
        std::fabs(r.hi - r.lo - w) > 1e-6 * w)
      throw Error(file + " line " + std::to_string(r.line) + ": bin [" + format_real(r.lo) + ", " +
                  format_real(r.hi) + ") is not on the grid of width " + format_real(w));
    bins.push_back({k, r.n});
  }
  return MagnitudeHistogram::from_bins(w, bins, total_load, blocks);
}

}  // namespace bkq
