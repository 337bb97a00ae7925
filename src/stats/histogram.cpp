// Implementation of the streaming magnitude histogram (see histogram.hpp).
#include "stats/histogram.hpp"
#include "core/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.hpp"

namespace bkq {

namespace {
constexpr double kQuantum = 1099511627776.0;   // 2^40: fixed-point scale of the mu sums
constexpr std::int64_t kMaxBins = 10'000'000;  // guards memory against absurd magnitudes

}  // namespace

MagnitudeHistogram::MagnitudeHistogram(double bin_width) : w_(bin_width) {
  if (!(bin_width > 0) || !std::isfinite(bin_width))
    throw Error("bin_width: expected a value > 0, got " + format_real(bin_width));
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
    throw Error("magnitude histogram: magnitude must be finite, got " + format_real(mu));
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
    throw Error("cannot merge histograms with different bin widths: " + format_real(w_) + " and " +
                format_real(o.w_));
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

MagnitudeHistogram MagnitudeHistogram::from_bins(double bin_width, const std::vector<Bin>& bins,
                                                 double total_load, int blocks) {
  MagnitudeHistogram h(bin_width);
  h.set_loading(total_load, blocks);
  h.exact_moments_ = false;
  long double s1 = 0, s2 = 0;
  bool first = true;
  for (const Bin& b : bins) {
    if (b.count < 0)
      throw Error("magnitude histogram: negative bin count " + std::to_string(b.count));
    if (b.count == 0) continue;
    h.add_count(b.k, b.count);
    const double centre = (static_cast<double>(b.k) + 0.5) * bin_width;
    s1 += static_cast<long double>(b.count) * centre;
    s2 += static_cast<long double>(b.count) * centre * centre;
    h.min_mu_ = first ? h.mu_low(b.k) : std::min(h.min_mu_, h.mu_low(b.k));
    h.max_mu_ = first ? h.mu_high(b.k) : std::max(h.max_mu_, h.mu_high(b.k));
    first = false;
    h.n_ += b.count;
  }
  h.sum_q_ = static_cast<__int128>(s1 * kQuantum);
  h.sum_q2_ = static_cast<__int128>(s2 * kQuantum * kQuantum);
  return h;
}

}  // namespace bkq
