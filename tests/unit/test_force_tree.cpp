// The force tree (engine/force_tree.hpp) against a plain scan: after random sets, removals
// and range sets, its largest and smallest values and their blocks (the lowest block in a
// tie) are the scan's, for chain lengths around its bucket and power-of-two boundaries.
// And the block window (integrate/block_window.hpp): entries keep their values while the
// window moves over them, new ones are 0.
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

TEST(BlockWindow, KeepsEntriesAndStartsNewOnesAtZero) {
  const int n = 1000;
  BlockWindow window(2);
  std::vector<double> truth(2 * n, 0.0);
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> block(0, n - 1), width(1, 40);
  for (int step = 0; step < 500; ++step) {
    // One or two ranges, far apart now and then.
    const int lo = block(rng), hi = std::min(n, lo + width(rng));
    std::vector<Range> ranges = {Range{lo, hi}};
    if (step % 7 == 0 && hi + 100 < n) ranges.push_back(Range{hi + 50, hi + 60});
    window.fit(ranges, n, step % 11 == 0);
    for (const Range& r : ranges) {
      ASSERT_LE(window.lo(), std::max(r.lo - 1, 0));
      ASSERT_GE(window.hi(), std::min(r.hi + 1, n));
    }
    // Entries inside the window hold what was written while they stayed in it; whatever
    // left the window and came back is 0 again.
    for (int k = 0; k < 2; ++k)
      for (int j = window.lo(); j < window.hi(); ++j) {
        ASSERT_EQ(window.data(k)[j], truth[k * n + j]) << "step " << step << " block " << j;
      }
    for (int k = 0; k < 2; ++k)
      for (const Range& r : ranges)
        for (int j = r.lo; j < r.hi; ++j) window.data(k)[j] = truth[k * n + j] = step + 0.5 * k;
    // What is outside the window is forgotten.
    for (int j = 0; j < n; ++j)
      if (j < window.lo() || j >= window.hi()) truth[j] = truth[n + j] = 0.0;
  }
}

}  // namespace
}  // namespace bkq
