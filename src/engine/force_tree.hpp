// "Which stuck block fails next" as a query, not a scan (SPEC §2). Every stuck block's
// spring force is f_j = g_j + k_p·anchor, where g_j depends only on the block and its
// neighbours and the anchor (substrate + pad) is shared by all. A segment tree over g_j
// keeps the index of the largest and of the smallest value: O(log N) to change one block,
// O(1) to ask. Blocks that are sliding (or being integrated) are taken out. Ties go to the
// lowest index, so runs are deterministic.
#pragma once

#include <cmath>
#include <vector>

namespace bkq {

class ForceTree {
 public:
  explicit ForceTree(int n = 0) { reset(n); }

  void reset(int n) {
    n_ = n;
    size_ = 1;
    while (size_ < n) size_ *= 2;
    hi_.assign(size_, -HUGE_VAL);
    lo_.assign(size_, HUGE_VAL);
    imax_.assign(2 * size_, 0);
    imin_.assign(2 * size_, 0);
    for (int j = 0; j < size_; ++j) imax_[size_ + j] = imin_[size_ + j] = j;
    for (int i = size_ - 1; i >= 1; --i) pull(i);
  }

  void set(int j, double g) {
    hi_[j] = g;
    lo_[j] = g;
    climb(j);
  }
  // set(j, value(j)) for j in [lo, hi), with each ancestor recomputed once (the tree is a
  // function of its leaves, so this is the same tree as after the single sets).
  template <class Value>
  void set_range(int lo, int hi, Value&& value) {
    if (lo >= hi) return;
    for (int j = lo; j < hi; ++j) hi_[j] = lo_[j] = value(j);
    for (int a = (size_ + lo) / 2, b = (size_ + hi - 1) / 2; a >= 1; a /= 2, b /= 2)
      for (int i = a; i <= b; ++i) pull(i);
  }
  void remove(int j) {
    hi_[j] = -HUGE_VAL;
    lo_[j] = HUGE_VAL;
    climb(j);
  }

  int argmax() const { return imax_[1]; }
  int argmin() const { return imin_[1]; }
  double max() const { return hi_[imax_[1]]; }  // -inf when empty
  double min() const { return lo_[imin_[1]]; }  // +inf when empty
  double value(int j) const { return hi_[j]; }

 private:
  void pull(int i) {
    const int a = imax_[2 * i], b = imax_[2 * i + 1];
    imax_[i] = hi_[a] >= hi_[b] ? a : b;
    const int c = imin_[2 * i], d = imin_[2 * i + 1];
    imin_[i] = lo_[c] <= lo_[d] ? c : d;
  }
  void climb(int j) {
    for (int i = (size_ + j) / 2; i >= 1; i /= 2) pull(i);
  }

  int n_ = 0, size_ = 1;
  std::vector<double> hi_, lo_;
  std::vector<int> imax_, imin_;
};

}  // namespace bkq
