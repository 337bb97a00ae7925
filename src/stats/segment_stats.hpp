// Statistics of a speed segment (Ferre 2018 §4.2, eqs. 4.1-4.4), streamed: the input signal is
// fed one value at a time and nothing is kept but per-block moments. The input (the last
// half of the segment) holds a known number n of values, split into M contiguous blocks of
// floor(n/M) values, the remainder going to the last block.
//   mean       (4.1)  S = sum S_i / n over the whole input
//   amplitude  (4.2)  A = sqrt(2) sqrt(sum (S_i - S)^2 / n), about the whole input's mean
//   errors     (4.3-4.4) for Y = mean or amplitude: Y_j computed on block j alone (a block's
//              amplitude about that block's own mean), sigma = sqrt(sum_j (Y_j - Y)^2 / M)
//              with Y the whole input's value, eps = sigma / sqrt(M).
// Moments are kept with Welford's update and combined exactly (Chan et al.), so a signal
// with a large offset loses no digits to sums of squares.
#pragma once

#include <cstdint>
#include <vector>

namespace bkq {

struct SegmentStat {
  double mean = 0, mean_err = 0, amp = 0, amp_err = 0;
};

class BlockedMoments {
 public:
  // n values will be added; M = min(blocks, n) blocks (at least 1).
  BlockedMoments(std::int64_t n, int blocks);
  void add(double x);
  std::int64_t added() const { return added_; }
  std::int64_t expected() const { return n_; }
  int blocks() const { return static_cast<int>(parts_.size()); }
  // The statistics of what was added (all zero when nothing was).
  SegmentStat result() const;
  // Its state, for checkpoints: the count added, then n, mean, m2 of each block; restored
  // by set_state on an object built with the same n and blocks (false if it does not fit).
  std::vector<double> state() const;
  bool set_state(const std::vector<double>& s);

 private:
  struct Part {
    std::int64_t n = 0;
    double mean = 0, m2 = 0;
  };
  std::int64_t n_, block_size_, added_ = 0;
  std::vector<Part> parts_;
};

// The steps i (time i dt, i = 1, 2, ...) whose time lies in the input of a segment
// [t_start, t_end]: t_start + (t_end - t_start)/2 < i dt <= t_end, with a tolerance of
// 1e-9 dt for rounding. first > last when there are none.
struct StepRange {
  std::int64_t first = 1, last = 0;
  std::int64_t count() const { return last >= first ? last - first + 1 : 0; }
};
StepRange input_steps(double t_start, double t_end, double dt);

}  // namespace bkq
