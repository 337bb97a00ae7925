// The change of state at a located transition, shared by the steppers that locate
// transitions themselves (Adaptive, Located): at st.t every block of `ranges` whose event
// has fired changes state, and block `who` (the located one) always does, since its event
// may lie a rounding level short of firing. A sliding block whose velocity reached zero
// sticks if friction holds its spring force, else it slides on the way the spring pulls
// (backslip laws: back the way it came; clst91: forwards, since f > threshold > 0); a stuck
// block whose force broke the threshold starts sliding from rest. Blocks that break loose
// are recorded once per step (released_mark[j] == stamp) with their position then.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "integrate/stepper.hpp"

namespace bkq {

// Returns the number of blocks that changed state; `last_stick_time` becomes st.t when one
// stuck.
inline std::int64_t apply_transitions(const ChainForces& forces, const Substrate& sub,
                                      ChainState& st, int who, Ranges ranges,
                                      std::vector<std::uint64_t>& released_mark,
                                      std::uint64_t stamp, std::vector<Stepper::Release>& releases,
                                      double& last_stick_time) {
  const Friction& fr = forces.friction();
  const double anchor = sub.at(st.t).s + (forces.params().pad_moves() ? st.x : 0.0);
  std::int64_t changed = 0;
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) {
      const double f = forces.spring_force(st.w.data(), j, anchor);
      if (st.mobile[j] != 0.0) {
        if (j != who && !(st.dir[j] * st.wd[j] <= 0.0)) continue;
        st.wd[j] = 0.0;
        if (fr.holds(f)) {
          st.mobile[j] = 0.0;
          last_stick_time = st.t;
        } else {
          st.dir[j] = std::copysign(1.0, f);
        }
      } else {
        if (j != who && !fr.breaks(f)) continue;
        st.mobile[j] = 1.0;
        st.wd[j] = 0.0;
        st.dir[j] = std::copysign(1.0, f);
        if (released_mark[j] != stamp) {
          released_mark[j] = stamp;
          releases.push_back({j, st.w[j]});
        }
      }
      ++changed;
    }
  return changed;
}

}  // namespace bkq
