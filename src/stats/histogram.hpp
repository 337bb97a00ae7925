// Streaming magnitude histogram: the observer that turns a stream of event magnitudes
// into the D(mu) and R(mu) distributions of Carlson & Langer (1989;
// Ferre 2018 section 2.2, eqs. 2.7-2.8). Memory grows with the magnitude range covered,
// never with the number of events, so unattended runs of millions of events stay flat.
//
// Bins have width w (default 0.2) and are anchored at integer multiples of w:
// bin k covers [k w, (k+1) w). Per bin k:
//   count_k              number of events with mu in the bin
//   D_k = count_k / w    events per unit magnitude
//   R_k = sum_{j>=k} count_j   events with magnitude >= mu_low = k w
//   D_rate, R_rate       the same divided by (total_load * N): per unit substrate
//                        displacement per block.
// Besides the counts it keeps n, min/max mu and the sums of mu and mu^2 (for the
// unbinned maximum-likelihood fit). The sums are accumulated in fixed point (mu
// quantised to 2^-40, about 1e-12) in 128-bit integers so that merging is exact and
// associative: the merge of the histograms of several parts equals, bit for bit,
// the histogram of the concatenated sample.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bkq {

class MagnitudeHistogram {
 public:
  static constexpr double kDefaultBinWidth = 0.2;

  explicit MagnitudeHistogram(double bin_width = kDefaultBinWidth);

  // Adds one event of magnitude mu (finite; bkq::Error otherwise).
  void add(double mu);
  // Exact merge; bkq::Error if the bin widths differ. Loading is summed, N must agree
  // (0 counts as unknown and takes the other's).
  void merge(const MagnitudeHistogram& other);

  // Substrate displacement accumulated over the recorded events and the chain length N,
  // for the rate columns.
  void set_loading(double total_load, int blocks);
  double total_load() const { return total_load_; }
  int blocks() const { return blocks_; }

  double bin_width() const { return w_; }
  std::int64_t events() const { return n_; }
  bool empty() const { return n_ == 0; }
  // Index range of the stored bins [first_bin, last_bin]; first/last are populated.
  std::int64_t first_bin() const { return k0_; }
  std::int64_t last_bin() const { return k0_ + static_cast<std::int64_t>(counts_.size()) - 1; }
  std::int64_t count(std::int64_t k) const;
  // Bin index of a magnitude: floor(mu / w).
  std::int64_t bin_of(double mu) const;
  double mu_low(std::int64_t k) const { return static_cast<double>(k) * w_; }
  double mu_high(std::int64_t k) const { return static_cast<double>(k + 1) * w_; }
  double D(std::int64_t k) const { return static_cast<double>(count(k)) / w_; }
  std::int64_t R(std::int64_t k) const;  // events with mu >= mu_low(k)
  std::int64_t count_range(std::int64_t k_lo, std::int64_t k_hi) const;  // bins k_lo..k_hi
  double rate_norm() const { return total_load_ * blocks_; }

  double min_mu() const { return min_mu_; }
  double max_mu() const { return max_mu_; }
  double mean_mu() const;
  double sum_mu() const;
  double sum_mu2() const;
  // False after from_bins: the sums then come from bin centres, min/max from bin edges.
  bool exact_moments() const { return exact_moments_; }

  // A histogram rebuilt from bin counts alone (as read back from histogram.csv): the
  // moments then come from bin centres, min/max from bin edges (exact_moments() false).
  struct Bin {
    std::int64_t k;  // bin index: the bin is [k w, (k + 1) w)
    std::int64_t count;
  };
  static MagnitudeHistogram from_bins(double bin_width, const std::vector<Bin>& bins,
                                      double total_load, int blocks);

  bool operator==(const MagnitudeHistogram& o) const = default;

  // The complete internal state, for checkpoints (src/io/checkpoint.hpp):
  // from_state(h.state()) == h, so a resumed run ends with the same histogram.csv.
  struct State {
    double bin_width = kDefaultBinWidth;
    std::int64_t first_bin = 0;
    std::vector<std::int64_t> counts;
    std::int64_t events = 0;
    __int128 sum_q = 0, sum_q2 = 0;
    double min_mu = 0, max_mu = 0;
    bool exact_moments = true;
    double total_load = 0;
    int blocks = 0;
  };
  State state() const;
  // Throws bkq::Error when the state is inconsistent (bin width, counts against events).
  static MagnitudeHistogram from_state(const State& s);

 private:
  void add_count(std::int64_t k, std::int64_t c);

  double w_;
  std::int64_t k0_ = 0;
  std::vector<std::int64_t> counts_;
  std::int64_t n_ = 0;
  __int128 sum_q_ = 0;   // sum of round(mu * 2^40)
  __int128 sum_q2_ = 0;  // sum of round(mu * 2^40)^2
  double min_mu_ = 0;
  double max_mu_ = 0;
  bool exact_moments_ = true;
  double total_load_ = 0;
  int blocks_ = 0;
};

}  // namespace bkq
