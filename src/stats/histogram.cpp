// Implementation of the streaming magnitude histogram (see histogram.hpp).
#include "stats/histogram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/error.hpp"
#include "stats/csv_util.hpp"

namespace bkq {

namespace {
constexpr double kQuantum = 1099511627776.0;   // 2^40: fixed-point scale of the mu sums
constexpr std::int64_t kMaxBins = 10'000'000;  // guards memory against absurd magnitudes

std::string edge(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  return buf;
}
}  // namespace

MagnitudeHistogram::MagnitudeHistogram(double bin_width) : w_(bin_width) {
  if (!(bin_width > 0) || !std::isfinite(bin_width))
    throw Error("bin_width: expected a value > 0, got " + csv::format_double(bin_width));
}

std::int64_t MagnitudeHistogram::bin_of(double mu) const {
  return static_cast<std::int64_t>(std::floor(mu / w_));
}

void MagnitudeHistogram::add_count(std::int64_t k, std::int64_t c) {
  if (counts_.empty()) {
    k0_ = k;
    counts_.assign(1, c);
    return;
  }
  if (k < k0_) {
    if (last_bin() - k >= kMaxBins) throw Error("magnitude histogram: magnitude range too wide");
    counts_.insert(counts_.begin(), static_cast<std::size_t>(k0_ - k), 0);
    k0_ = k;
  } else if (k > last_bin()) {
    if (k - k0_ >= kMaxBins) throw Error("magnitude histogram: magnitude range too wide");
    counts_.resize(static_cast<std::size_t>(k - k0_ + 1), 0);
  }
  counts_[static_cast<std::size_t>(k - k0_)] += c;
}

void MagnitudeHistogram::add(double mu) {
  if (!std::isfinite(mu) || std::fabs(mu) > 1000)
    throw Error("magnitude histogram: magnitude must be finite, got " + csv::format_double(mu));
  add_count(bin_of(mu), 1);
  const auto q = static_cast<__int128>(std::llround(mu * kQuantum));
  sum_q_ += q;
  sum_q2_ += q * q;
  min_mu_ = n_ == 0 ? mu : std::min(min_mu_, mu);
  max_mu_ = n_ == 0 ? mu : std::max(max_mu_, mu);
  ++n_;
}

void MagnitudeHistogram::merge(const MagnitudeHistogram& o) {
  if (o.w_ != w_)
    throw Error("cannot merge histograms with different bin widths: " + csv::format_double(w_) +
                " and " + csv::format_double(o.w_));
  if (blocks_ != 0 && o.blocks_ != 0 && blocks_ != o.blocks_)
    throw Error("cannot merge histograms of different chains: N = " + std::to_string(blocks_) +
                " and N = " + std::to_string(o.blocks_));
  if (o.n_ == 0) {
    total_load_ += o.total_load_;
    if (blocks_ == 0) blocks_ = o.blocks_;
    return;
  }
  // Grow once to the union range, then add counts.
  add_count(o.first_bin(), 0);
  add_count(o.last_bin(), 0);
  for (std::int64_t k = o.first_bin(); k <= o.last_bin(); ++k) add_count(k, o.count(k));
  min_mu_ = n_ == 0 ? o.min_mu_ : std::min(min_mu_, o.min_mu_);
  max_mu_ = n_ == 0 ? o.max_mu_ : std::max(max_mu_, o.max_mu_);
  n_ += o.n_;
  sum_q_ += o.sum_q_;
  sum_q2_ += o.sum_q2_;
  exact_moments_ = exact_moments_ && o.exact_moments_;
  total_load_ += o.total_load_;
  if (blocks_ == 0) blocks_ = o.blocks_;
}

void MagnitudeHistogram::set_loading(double total_load, int blocks) {
  total_load_ = total_load;
  blocks_ = blocks;
}

std::int64_t MagnitudeHistogram::count(std::int64_t k) const {
  if (counts_.empty() || k < k0_ || k > last_bin()) return 0;
  return counts_[static_cast<std::size_t>(k - k0_)];
}

std::int64_t MagnitudeHistogram::count_range(std::int64_t k_lo, std::int64_t k_hi) const {
  if (counts_.empty()) return 0;
  k_lo = std::max(k_lo, k0_);
  k_hi = std::min(k_hi, last_bin());
  std::int64_t s = 0;
  for (std::int64_t k = k_lo; k <= k_hi; ++k) s += counts_[static_cast<std::size_t>(k - k0_)];
  return s;
}

std::int64_t MagnitudeHistogram::R(std::int64_t k) const {
  return counts_.empty() ? 0 : count_range(k, last_bin());
}

double MagnitudeHistogram::sum_mu() const {
  return static_cast<double>(static_cast<long double>(sum_q_) / kQuantum);
}
double MagnitudeHistogram::sum_mu2() const {
  return static_cast<double>(static_cast<long double>(sum_q2_) / (kQuantum * kQuantum));
}
double MagnitudeHistogram::mean_mu() const {
  return n_ == 0 ? std::nan("") : sum_mu() / static_cast<double>(n_);
}

std::string MagnitudeHistogram::csv() const {
  std::ostringstream out;
  out << "mu_low,mu_high,count,D,R,D_rate,R_rate\n";
  if (counts_.empty()) return out.str();
  const double norm = rate_norm();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::int64_t r = n_;
  for (std::int64_t k = k0_; k <= last_bin(); ++k) {
    const std::int64_t c = count(k);
    const double d = static_cast<double>(c) / w_;
    const double rr = static_cast<double>(r);
    out << edge(mu_low(k)) << ',' << edge(mu_high(k)) << ',' << c << ',' << csv::format_double(d)
        << ',' << r << ',' << csv::format_double(norm > 0 ? d / norm : nan) << ','
        << csv::format_double(norm > 0 ? rr / norm : nan) << '\n';
    r -= c;
  }
  return out.str();
}

void MagnitudeHistogram::write_csv(const std::filesystem::path& path) const {
  std::ofstream f(path);
  if (!f) throw Error(path.string() + ": cannot open for writing");
  f << csv();
  if (!f) throw Error(path.string() + ": write failed");
}

MagnitudeHistogram::State MagnitudeHistogram::state() const {
  return State{w_,      k0_,     counts_,        n_,          sum_q_, sum_q2_,
               min_mu_, max_mu_, exact_moments_, total_load_, blocks_};
}

MagnitudeHistogram MagnitudeHistogram::from_state(const State& s) {
  MagnitudeHistogram h(s.bin_width);
  std::int64_t total = 0;
  for (std::int64_t c : s.counts) {
    if (c < 0) throw Error("magnitude histogram: negative bin count " + std::to_string(c));
    total += c;
  }
  if (total != s.events || static_cast<std::int64_t>(s.counts.size()) > kMaxBins)
    throw Error("magnitude histogram: " + std::to_string(s.counts.size()) + " bins holding " +
                std::to_string(total) + " events, expected " + std::to_string(s.events));
  h.k0_ = s.first_bin;
  h.counts_ = s.counts;
  h.n_ = s.events;
  h.sum_q_ = s.sum_q;
  h.sum_q2_ = s.sum_q2;
  h.min_mu_ = s.min_mu;
  h.max_mu_ = s.max_mu;
  h.exact_moments_ = s.exact_moments;
  h.total_load_ = s.total_load;
  h.blocks_ = s.blocks;
  return h;
}

MagnitudeHistogram MagnitudeHistogram::read_csv(const std::filesystem::path& path,
                                                double total_load, int blocks, double bin_width) {
  const std::string file = path.string();
  std::ifstream f(path);
  if (!f) throw Error(file + ": cannot open");
  std::string header_line;
  if (!std::getline(f, header_line)) throw Error(file + ": empty file, expected a header line");
  const auto header = csv::split(header_line);
  const int c_lo = csv::find_column(header, "mu_low");
  const int c_hi = csv::find_column(header, "mu_high");
  const int c_n = csv::find_column(header, "count");
  for (auto [c, name] : {std::pair{c_lo, "mu_low"}, {c_hi, "mu_high"}, {c_n, "count"}})
    if (c < 0) throw Error(file + ": missing column '" + name + "'");

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
    const Row r{csv::parse_double(fields[static_cast<std::size_t>(c_lo)], file, lineno, "mu_low"),
                csv::parse_double(fields[static_cast<std::size_t>(c_hi)], file, lineno, "mu_high"),
                csv::parse_int(fields[static_cast<std::size_t>(c_n)], file, lineno, "count"),
                lineno};
    if (r.n < 0)
      throw Error(file + " line " + std::to_string(lineno) + ": count must be >= 0, got " +
                  std::to_string(r.n));
    rows.push_back(r);
  }
  double w = bin_width;
  if (!rows.empty()) {
    const double wf = rows.front().hi - rows.front().lo;
    if (w > 0 && std::fabs(wf - w) > 1e-9 * std::max(1.0, w))
      throw Error(file + ": bin width " + csv::format_double(wf) + " differs from the expected " +
                  csv::format_double(w));
    if (!(w > 0)) w = std::round(wf * 1e9) / 1e9;  // undo the %.12g rounding of the edges
  }
  if (!(w > 0)) w = kDefaultBinWidth;
  MagnitudeHistogram h(w);
  h.set_loading(total_load, blocks);
  h.exact_moments_ = false;
  long double s1 = 0, s2 = 0;
  bool first = true;
  for (const Row& r : rows) {
    const auto k = static_cast<std::int64_t>(std::llround(r.lo / w));
    if (std::fabs(r.lo - static_cast<double>(k) * w) > 1e-6 * w ||
        std::fabs(r.hi - r.lo - w) > 1e-6 * w)
      throw Error(file + " line " + std::to_string(r.line) + ": bin [" + csv::format_double(r.lo) +
                  ", " + csv::format_double(r.hi) + ") is not on the grid of width " +
                  csv::format_double(w));
    if (r.n == 0) continue;
    h.add_count(k, r.n);
    const double centre = (static_cast<double>(k) + 0.5) * w;
    s1 += static_cast<long double>(r.n) * centre;
    s2 += static_cast<long double>(r.n) * centre * centre;
    h.min_mu_ = first ? h.mu_low(k) : std::min(h.min_mu_, h.mu_low(k));
    h.max_mu_ = first ? h.mu_high(k) : std::max(h.max_mu_, h.mu_high(k));
    first = false;
    h.n_ += r.n;
  }
  h.sum_q_ = static_cast<__int128>(s1 * kQuantum);
  h.sum_q2_ = static_cast<__int128>(s2 * kQuantum * kQuantum);
  return h;
}

}  // namespace bkq
