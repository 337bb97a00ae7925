// Stick and slip transitions between steps (the Crossing rule of stepper.hpp), shared by
// the continuous driver and the event relaxation. One pass over the ranges:
//  - a sliding block whose relative velocity changed sign during the step (or is exactly
//    0; for clst91, became <= 0 since it may not slide backwards) is stuck with zero
//    velocity if friction can hold its spring force at the new position; otherwise it
//    keeps sliding the other way (backslip laws) or stays at zero velocity, still sliding
//    (clst91); a sliding block's direction of sliding is updated to its new velocity;
//  - a stuck block whose spring force exceeds the static threshold breaks loose with
//    zero relative velocity; `on_release(j)` is told.
// Optionally (a non-null `work`) it adds up the power sliding blocks dissipate in friction
// (and the 1DOF damper) at the two ends of the step, with each block's direction frozen
// as in the step: the caller turns the sum into work by the trapezoidal rule.
#pragma once

#include <algorithm>
#include <cmath>

#include "model/chain.hpp"

namespace bkq {

struct ContactScan {
  int sliding = 0;        // blocks sliding after the pass
  double max_speed = 0;   // largest |relative velocity| among them; NaN if any is NaN
};

template <class OnRelease>
ContactScan settle_contacts(const ChainForces& forces, ChainState& st, const double* wd_old, double anchor,
                            Ranges ranges, bool crossing_rule, OnRelease&& on_release,
                            double* power_sum = nullptr) {
  const Friction& fr = forces.friction();
  const double damper = forces.params().c_u / forces.params().m_u;
  double* w = st.w.data();
  double* wd = st.wd.data();
  double* mob = st.mobile.data();
  ContactScan out;
  for (const Range& r : ranges) {
    for (int j = r.lo; j < r.hi; ++j) {
      if (mob[j] != 0.0) {
        if (power_sum) {
          const double y0 = wd_old[j], y1 = wd[j];
          *power_sum += fr.power(y0, st.dir[j]) + fr.power(y1, st.dir[j]) + damper * (y0 * y0 + y1 * y1);
        }
        if (crossing_rule) {
          const double y0 = wd_old[j], y1 = wd[j];
          const bool crossed = fr.backslip ? (y0 * y1 < 0.0 || y1 == 0.0) : y1 <= 0.0;
          if (crossed) {
            if (fr.holds(forces.spring_force(w, j, anchor))) {
              wd[j] = 0.0;
              mob[j] = 0.0;
              continue;
            }
            if (!fr.backslip) wd[j] = 0.0;
          }
        }
        if (wd[j] != 0.0) st.dir[j] = std::copysign(1.0, wd[j]);
        ++out.sliding;
        // A non-finite velocity must survive into max_speed (std::max would drop a NaN).
        const double speed = std::abs(wd[j]);
        if (!(speed <= out.max_speed) && out.max_speed == out.max_speed) out.max_speed = speed;
      } else {
        const double f = forces.spring_force(w, j, anchor);
        if (fr.breaks(f)) {
          mob[j] = 1.0;
          st.dir[j] = std::copysign(1.0, f);  // it starts sliding the way its spring pulls
          ++out.sliding;
          on_release(j);
        }
      }
    }
  }
  return out;
}

}  // namespace bkq
