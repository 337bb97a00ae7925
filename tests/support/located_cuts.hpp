// What the cuts of located transitions step (integrate/located.hpp), for the tests and the
// benchmarks that study them: a watcher the located wrapper tells of each step it cuts.
//   cuts             steps cut at a located instant inside them;
//   cut_blocks       the blocks of the step's ranges summed over those cuts: each cut steps
//                    them all to the instant (the whole-range cut), one scheme step more;
//   stretch_blocks   the same sum over the sliding stretch of each cut's block only: the
//                    block, the sliding blocks next to it on either side and the stuck block
//                    that ends each side. Without a moving pad a stuck block decouples the
//                    two sides for the step (flags are frozen), so a cut of that stretch
//                    alone would do; this is what such cuts would step (not done).
#pragma once

#include <algorithm>
#include <cstdint>

#include "integrate/located.hpp"
#include "model/chain.hpp"

namespace bkq {

class LocatedCutCounts final : public LocatedTransitions::CutWatcher {
 public:
  void cut(const ChainForces& forces, const ChainState& st, int who, Ranges ranges) override {
    ++cuts;
    for (const Range& r : ranges) cut_blocks += r.hi - r.lo;
    stretch_blocks += sliding_stretch(forces, st, who);
  }

  std::int64_t cuts = 0, cut_blocks = 0, stretch_blocks = 0;

 private:
  // Out from `who` over sliding blocks on each side, then the stuck block that ends the
  // stretch (none past a free end; a periodic chain wraps, at most once round).
  static int sliding_stretch(const ChainForces& forces, const ChainState& st, int who) {
    const int n = forces.n();
    const bool periodic = forces.params().boundary == Boundary::Periodic;
    int count = 1;
    for (int side : {-1, 1}) {
      int j = who;
      for (int seen = 1; seen < n; ++seen) {
        int k = j + side;
        if (k < 0 || k >= n) {
          if (!periodic) break;
          k = (k + n) % n;
        }
        if (k == who) break;
        ++count;
        if (st.mobile[k] == 0.0) break;
        j = k;
      }
    }
    return std::min(count, n);
  }
};

}  // namespace bkq
