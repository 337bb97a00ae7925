// Arrays indexed by block number that hold entries only for a window of blocks: the
// scratch of a step over a few ranges of a long chain. The kernels index their buffers
// with the block number j, as they index the chain state; a window hands them, for each
// array, an address p with p[j] the entry of block j, valid for every j in the window.
// So what a stepper or the event engine keeps besides the chain state grows with the
// blocks a step touches, not with the chain (README, "Performance": bytes per block).
//
// fit(ranges) before each step: the window then holds every block of the ranges and one
// more on each side (the neighbours the force kernels read; with periodic ends a range at
// either end of the chain also reads the other end, so the window becomes the whole
// chain). Entries that enter the window are 0, so every entry a kernel reads is finite;
// entries that stay in it keep their values. The window grows with room to spare on each
// side (kSlack blocks, or half its length), so an event that spreads block by block moves
// it a few times, not at every step.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "model/chain.hpp"

namespace bkq {

class BlockWindow {
 public:
  static constexpr int kSlack = 16;

  explicit BlockWindow(int arrays = 0) : arrays_(arrays) {}

  // The ranges of a step over a chain of n blocks.
  void fit(Ranges ranges, int n, bool periodic) {
    if (ranges.empty()) return;
    if (n != n_) {
      n_ = n;
      lo_ = hi_ = 0;
    }
    int lo = ranges.front().lo - 1, hi = ranges.front().hi + 1;
    for (const Range& r : ranges) lo = std::min(lo, r.lo - 1), hi = std::max(hi, r.hi + 1);
    if (periodic && (lo < 0 || hi > n)) lo = 0, hi = n;
    lo = std::max(lo, 0);
    hi = std::min(hi, n);
    if (lo >= lo_ && hi <= hi_) return;
    const int slack = std::max(kSlack, (hi - lo) / 2);
    move_to(std::max(lo - slack, 0), std::min(hi + slack, n_));
  }

  // Array k's entry of block j is data(k)[j], for j in the window. The address is formed
  // as an integer: the entries of blocks before the window do not exist, and a pointer
  // to one of them would lie outside the storage, which C++ leaves undefined.
  double* data(int k) {
    const auto first = reinterpret_cast<std::uintptr_t>(data_.data() + std::size_t(k) * len());
    return reinterpret_cast<double*>(first - std::uintptr_t(lo_) * sizeof(double));
  }
  int lo() const { return lo_; }
  int hi() const { return hi_; }

 private:
  int len() const { return hi_ - lo_; }

  void move_to(int lo, int hi) {
    const std::size_t len_new = static_cast<std::size_t>(hi - lo);
    release_if_oversized(spare_, len_new * arrays_);
    spare_.assign(len_new * arrays_, 0.0);
    const int a = std::max(lo, lo_), b = std::min(hi, hi_);
    for (int k = 0; k < arrays_ && a < b; ++k)
      std::copy(data_.begin() + std::ptrdiff_t(k) * len() + (a - lo_),
                data_.begin() + std::ptrdiff_t(k) * len() + (b - lo_),
                spare_.begin() + std::ptrdiff_t(k) * std::ptrdiff_t(len_new) + (a - lo));
    data_.swap(spare_);
    lo_ = lo;
    hi_ = hi;
    release_if_oversized(spare_, data_.size());
  }

  // What a large event grew stays allocated only while the window is of its size.
  static void release_if_oversized(std::vector<double>& v, std::size_t size) {
    if (v.capacity() > 4 * size + 1024) std::vector<double>().swap(v);
  }

  int arrays_ = 0, n_ = 0;
  int lo_ = 0, hi_ = 0;
  std::vector<double> data_, spare_;  // array k's entries at [k * len, (k + 1) * len)
};

}  // namespace bkq
