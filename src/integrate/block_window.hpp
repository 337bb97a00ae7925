// Arrays indexed by block number that hold entries only for a window of blocks: the
// scratch of a step over a few ranges of a long chain. The kernels index their buffers
// with the block number j, as they index the chain state; a window hands them, for each
// array, an address p with p[j] the entry of block j, valid for every j in the window.
// So what a stepper or the event engine keeps besides the chain state grows with the
// blocks a step touches, not with the chain (docs/validation/performance.md: bytes per block).
//
// fit(ranges) before a step: the window then holds every block of the ranges and `reach`
// more on each side (the neighbours the force kernels read: one for nearest neighbours, R
// for a coupling of range R; with periodic ends a range at either
// end of the chain also reads the other end, so the window becomes the whole chain). What
// the entries hold is left over from earlier steps, anywhere in the chain: the steps write
// every entry of their ranges before they read it, and the neighbours outside the ranges
// (stuck blocks) only enter multiplied by a stick flag of 0, for which any finite value
// does. Entries are finite: 0 when allocated, and after that what steps wrote (a step that
// goes non-finite ends the run). The storage grows by half again when a window does not
// fit, and is given back once the window needs less than a quarter of it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/chain.hpp"

namespace bkq {

class BlockWindow {
 public:
  explicit BlockWindow(int arrays = 0) : arrays_(arrays) {}

  // The ranges of a step over a chain of n blocks.
  void fit(Ranges ranges, int n, bool periodic, int reach = 1) {
    if (ranges.empty()) return;
    int lo = ranges.front().lo - reach, hi = ranges.front().hi + reach;
    for (const Range& r : ranges) lo = std::min(lo, r.lo - reach), hi = std::max(hi, r.hi + reach);
    if (periodic && (lo < 0 || hi > n)) lo = 0, hi = n;
    place(std::max(lo, 0), std::min(hi, n));
  }
  // Blocks [lo, hi).
  void place(int lo, int hi) {
    const std::size_t len = static_cast<std::size_t>(std::max(hi - lo, 0));
    if (len > cap_ || cap_ > 4 * len + kKeep) {
      cap_ = len + len / 2 + kKeep / 4;
      std::vector<double>(cap_ * arrays_, 0.0).swap(data_);
    }
    lo_ = lo;
    hi_ = hi;
  }

  // Array k's entry of block j is data(k)[j], for j in the window. The address is formed
  // as an integer: the entries of blocks before the window do not exist, and a pointer
  // to one of them would lie outside the storage, which C++ leaves undefined.
  double* data(int k) {
    const auto first = reinterpret_cast<std::uintptr_t>(data_.data() + std::size_t(k) * cap_);
    return reinterpret_cast<double*>(first - std::uintptr_t(lo_) * sizeof(double));
  }
  int lo() const { return lo_; }
  int hi() const { return hi_; }
  std::size_t capacity() const { return cap_; }  // blocks each array has room for

 private:
  static constexpr std::size_t kKeep = 256;  // room below which storage is never given back

  int arrays_ = 0;
  int lo_ = 0, hi_ = 0;
  std::size_t cap_ = 0;
  std::vector<double> data_;  // array k's entries at [k * cap_, k * cap_ + hi_ - lo_)
};

// Arrays over the blocks of a set of ranges: copies of the state taken at the start of a
// step. data(k, i)[j] is array k's entry of block j of range i. While the ranges lie close
// together they share one window over their span (joint(): data(k, i) is the same for
// every i); far apart, each range's entries follow the one before's, so that the storage
// holds the ranges' blocks, not their span. Storage as in BlockWindow; entries are left
// over.
class RangeArrays {
 public:
  explicit RangeArrays(int arrays) : window_(arrays) {}

  void fit(Ranges ranges) {
    start_.clear();
    if (ranges.empty()) return;
    int lo = ranges.front().lo, hi = ranges.front().hi, blocks = 0;
    for (const Range& r : ranges) {
      lo = std::min(lo, r.lo), hi = std::max(hi, r.hi);
      blocks += r.hi - r.lo;
    }
    joint_ = hi - lo <= 4 * blocks + 256;
    if (joint_) return window_.place(lo, hi);
    int total = 0;
    for (const Range& r : ranges) {
      start_.push_back(total - r.lo);
      total += r.hi - r.lo;
    }
    window_.place(0, total);
  }
  // Entries for every block of a chain of n, kept from one step to the next.
  void whole(int n) {
    joint_ = true;
    window_.place(0, n);
  }
  bool joint() const { return joint_; }
  double* data(int k, std::size_t i) {
    if (joint_) return window_.data(k);
    const auto first = reinterpret_cast<std::uintptr_t>(window_.data(k));
    return reinterpret_cast<double*>(first + std::intptr_t(start_[i]) * sizeof(double));
  }

 private:
  BlockWindow window_;
  std::vector<int> start_;  // per range: where block j's entry is in the window, less j
  bool joint_ = true;
};

}  // namespace bkq
