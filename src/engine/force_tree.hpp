// "Which stuck block fails next" as a query, not a scan. Every stuck block's
// spring force is f_j = g_j + k_p·anchor, where g_j depends only on the block and its
// neighbours and the anchor (substrate + pad) is shared by all. The tree keeps the largest
// and the smallest g_j with their blocks: O(log N) to change one block, O(1) to ask.
// Blocks that are sliding (or being integrated) are taken out. Ties go to the lowest
// index, so runs are deterministic.
//
// Layout (for a long chain, where an event's few changes would otherwise miss the cache
// at every level): the values g_j in buckets of kBucket blocks (one cache line), and over
// the buckets two binary trees (largest, smallest) whose nodes hold the value beside its
// block, so that recomputing a node reads its two children, side by side, and nothing
// else. About 16 bytes per block.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace bkq {

class ForceTree {
 public:
  static constexpr int kBucket = 8;

  explicit ForceTree(int n = 0) { reset(n); }

  // n blocks, all taken out.
  void reset(int n) {
    const int buckets = n > 0 ? (n + kBucket - 1) / kBucket : 1;
    size_ = 1;
    while (size_ < buckets) size_ *= 2;
    g_.assign(static_cast<std::size_t>(size_) * kBucket, kOut);
    max_.assign(2 * static_cast<std::size_t>(size_), Node{-HUGE_VAL, 0});
    min_.assign(2 * static_cast<std::size_t>(size_), Node{HUGE_VAL, 0});
    for (int b = 0; b < size_; ++b) max_[size_ + b].j = min_[size_ + b].j = b * kBucket;
    for (int i = size_ - 1; i >= 1; --i) pull(i);
  }

  void set(int j, double g) {
    g_[j] = g;
    update_bucket(j / kBucket);
  }
  // set(j, value(j)) for j in [lo, hi), with each bucket and ancestor recomputed once (the
  // tree is a function of its values, so this is the same tree as after the single sets).
  template <class Value>
  void set_range(int lo, int hi, Value&& value) {
    if (lo >= hi) return;
    for (int j = lo; j < hi; ++j) g_[j] = value(j);
    const int first = lo / kBucket, last = (hi - 1) / kBucket;
    for (int b = first; b <= last; ++b) scan(b);
    for (int a = (size_ + first) / 2, b = (size_ + last) / 2; a >= 1; a /= 2, b /= 2)
      for (int i = a; i <= b; ++i) pull(i);
  }
  void remove(int j) {
    g_[j] = kOut;
    update_bucket(j / kBucket);
  }

  int argmax() const { return max_[1].j; }
  int argmin() const { return min_[1].j; }
  double max() const { return max_[1].g; }  // -inf when empty
  double min() const { return min_[1].g; }  // +inf when empty

 private:
  // A block taken out: NaN, which no comparison below lets in.
  static constexpr double kOut = NAN;
  struct Node {
    double g;
    int j;
  };

  // The bucket's largest and smallest value, the first block of each in a tie; an empty
  // bucket gives -inf / +inf at its first block.
  void scan(int b) {
    const int first = b * kBucket;
    const double* g = g_.data() + first;
    Node hi{-HUGE_VAL, first}, lo{HUGE_VAL, first};
    for (int k = 0; k < kBucket; ++k) {
      if (g[k] > hi.g) hi = Node{g[k], first + k};
      if (g[k] < lo.g) lo = Node{g[k], first + k};
    }
    max_[size_ + b] = hi;
    min_[size_ + b] = lo;
  }
  void update_bucket(int b) {
    scan(b);
    for (int i = (size_ + b) / 2; i >= 1; i /= 2) pull(i);
  }
  // Ties to the left child, which holds the lower blocks.
  void pull(int i) {
    const Node &a = max_[2 * i], &b = max_[2 * i + 1];
    max_[i] = a.g >= b.g ? a : b;
    const Node &c = min_[2 * i], &d = min_[2 * i + 1];
    min_[i] = c.g <= d.g ? c : d;
  }

  int size_ = 1;                 // buckets, a power of two
  std::vector<double> g_;        // g_j, or kOut
  std::vector<Node> max_, min_;  // node i's children 2i, 2i + 1; bucket b's node size_ + b
};

}  // namespace bkq
