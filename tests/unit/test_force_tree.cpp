// The force tree (engine/force_tree.hpp) against a plain scan: after random sets, removals
// and range sets, its largest and smallest values and their blocks (the lowest block in a
// tie) are the scan's, for chain lengths around its bucket and power-of-two boundaries.
// And the block window and range arrays (integrate/block_window.hpp): they hold what the
// ranges need, each entry its own, and give back what a wide window grew.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "engine/force_tree.hpp"
#include "integrate/block_window.hpp"

namespace bkq {
namespace {

struct Scan {
  double max = -HUGE_VAL, min = HUGE_VAL;
  int argmax = -1, argmin = -1;
};

Scan scan(const std::vector<double>& g, const std::vector<bool>& in) {
  Scan s;
  for (int j = 0; j < static_cast<int>(g.size()); ++j) {
    if (!in[j]) continue;
    if (s.argmax < 0 || g[j] > s.max) s.max = g[j], s.argmax = j;
    if (s.argmin < 0 || g[j] < s.min) s.min = g[j], s.argmin = j;
  }
  return s;
}

TEST(ForceTree, AgreesWithAScan) {
  std::mt19937_64 rng(11);
  for (const int n : {1, 2, 7, 8, 9, 15, 16, 17, 63, 64, 65, 100, 1000}) {
    ForceTree tree(n);
    EXPECT_EQ(tree.max(), -HUGE_VAL);
    EXPECT_EQ(tree.min(), HUGE_VAL);
    std::vector<double> g(n, 0.0);
    std::vector<bool> in(n, false);
    // Few distinct values, so that ties are common.
    std::uniform_int_distribution<int> value(-5, 5), block(0, n - 1), op(0, 9);
    for (int step = 0; step < 4000; ++step) {
      const int j = block(rng), kind = op(rng);
      if (kind < 5) {
        g[j] = value(rng);
        in[j] = true;
        tree.set(j, g[j]);
      } else if (kind < 8) {
        in[j] = false;
        tree.remove(j);
      } else {
        const int hi = std::min(n, j + 1 + block(rng) % 20);
        for (int k = j; k < hi; ++k) g[k] = value(rng), in[k] = true;
        tree.set_range(j, hi, [&](int k) { return g[k]; });
      }
      const Scan s = scan(g, in);
      if (s.argmax < 0) {
        ASSERT_EQ(tree.max(), -HUGE_VAL) << "n " << n << " step " << step;
        ASSERT_EQ(tree.min(), HUGE_VAL) << "n " << n << " step " << step;
        continue;
      }
      ASSERT_EQ(tree.max(), s.max) << "n " << n << " step " << step;
      ASSERT_EQ(tree.argmax(), s.argmax) << "n " << n << " step " << step;
      ASSERT_EQ(tree.min(), s.min) << "n " << n << " step " << step;
      ASSERT_EQ(tree.argmin(), s.argmin) << "n " << n << " step " << step;
    }
  }
}

TEST(BlockWindow, HoldsTheRangesAndTheirNeighboursAndGivesBackWhatItGrew) {
  const int n = 100000;
  BlockWindow window(2);
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> block(0, n - 1), width(1, 40);
  for (int step = 0; step < 300; ++step) {
    // One or two ranges, now and then far apart (a wide window).
    const int lo = block(rng), hi = std::min(n, lo + width(rng));
    std::vector<Range> ranges = {Range{lo, hi}};
    if (step % 50 == 7 && hi + 60000 < n) ranges.push_back(Range{hi + 50000, hi + 50010});
    window.fit(ranges, n, false);
    const int first = std::max(ranges.front().lo - 1, 0);
    const int last = std::min(ranges.back().hi + 1, n);
    ASSERT_EQ(window.lo(), first);
    ASSERT_EQ(window.hi(), last);
    // Every entry there is finite (left over or 0) and its own.
    for (int k = 0; k < 2; ++k)
      for (int j = first; j < last; ++j) {
        ASSERT_TRUE(std::isfinite(window.data(k)[j])) << "step " << step << " block " << j;
        window.data(k)[j] = k * n + j;
      }
    for (int k = 0; k < 2; ++k)
      for (int j = first; j < last; ++j) ASSERT_EQ(window.data(k)[j], k * n + j);
    // A narrow window after a wide one does not keep the wide one's storage.
    if (ranges.size() == 1) {
      ASSERT_LE(window.capacity(), 4u * static_cast<unsigned>(last - first) + 256u);
    }
  }
  window.fit(std::vector<Range>{Range{0, 3}}, n, true);  // periodic: both ends
  EXPECT_EQ(window.lo(), 0);
  EXPECT_EQ(window.hi(), n);
}

TEST(RangeArrays, GiveEachRangeAndArrayItsOwnEntries) {
  RangeArrays arrays(3);
  const std::vector<Range> ranges = {Range{5, 9}, Range{40, 41}, Range{1000, 1020}};
  arrays.fit(ranges);
  for (int k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < ranges.size(); ++i)
      for (int j = ranges[i].lo; j < ranges[i].hi; ++j) arrays.data(k, i)[j] = 10000 * k + j;
  for (int k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < ranges.size(); ++i)
      for (int j = ranges[i].lo; j < ranges[i].hi; ++j)
        EXPECT_EQ(arrays.data(k, i)[j], 10000 * k + j);
  EXPECT_FALSE(arrays.joint());  // far apart: the blocks, not the span
  // Close together: one window, one address per array for all ranges.
  const std::vector<Range> close = {Range{5, 9}, Range{40, 41}};
  arrays.fit(close);
  EXPECT_TRUE(arrays.joint());
  EXPECT_EQ(arrays.data(2, 0), arrays.data(2, 1));
  for (const Range& r : close)
    for (int j = r.lo; j < r.hi; ++j) arrays.data(1, 0)[j] = j;
  for (const Range& r : close)
    for (int j = r.lo; j < r.hi; ++j) EXPECT_EQ(arrays.data(1, 1)[j], j);
}

}  // namespace
}  // namespace bkq
