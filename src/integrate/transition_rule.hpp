// The transition rules' per-block decisions and sums, written once for every path that
// applies them: the general step (engine/contacts.hpp, engine/general_path.cpp), the
// located stepper (integrate/located.cpp), the cluster kernels (integrate/cluster.hpp), the
// lone-slip record (engine/lone_slip.cpp) and the event engine's pad test. Each path calls
// these with its own storage (the chain's arrays, a cluster's registers), so the
// operations, and hence the bits, are the same on every path.
//   Crossing  after a step, the stick rule of model/stick.hpp block by block; the step's
//             work is the trapezoidal rule on each block's power, summed per range in the
//             order of RangePowerSum.
//   Located   after an attempted step, `fired` says whether a block's transition has
//             happened inside it (the step is then cut at the located instant); the work
//             of each piece is the trapezoidal rule on the sliding blocks' powers, summed
//             in block order.
//   Both      with the pad moving, a stuck block far from the sliding ones breaks loose
//             when the pad's swing takes its spring force past the threshold (far_failure).
#pragma once

#include "model/friction.hpp"
#include "model/stick.hpp"

namespace bkq::transition {

// Crossing: block-step power (Friction's step_power_given) of a block with stick flag
// `mobile` through the step (stuck: exactly 0 times the power).
template <bool Backslip>
inline double crossing_power(double mobile, double m0, double y0, double m1, double y1, double dir,
                             double damper) {
  return mobile * step_power_given<Backslip>(m0, y0, m1, y1, dir, damper);
}

// Crossing: the powers term(0), ..., term(count - 1) of a range's blocks, in block order,
// summed as RangePowerSum sums them (four places at a time, so that it vectorises).
template <class Term>
inline double range_power(int count, Term&& term) {
  RangePowerSum sum;
  int m = 0;
  for (; m + 4 <= count; m += 4)
    for (int k = 0; k < 4; ++k) sum.add(k, term(m + k));
  for (; m < count; ++m) sum.add(m, term(m));
  return sum.total();
}

// Crossing: what becomes of one block at the end of a step (model/stick.hpp, the form
// that releases a block that breaks loose); spring_force() is asked only where the rule
// looks at it.
template <class SpringForce>
inline stick::Outcome settle(const Friction& fr, double mobile, double dir, double y0, double y1,
                             SpringForce&& spring_force) {
  return stick::settle_one(fr, true, mobile, dir, y0, y1, spring_force);
}

// Located: has the block's transition happened by the end of the attempted step? A
// sliding block (mobile != 0) once its velocity y has reached zero against its direction
// of sliding (dir y <= 0), a stuck one once its spring force breaks the threshold
// (spring_force() is asked only then).
inline bool stopped(double dir, double y) {
  return dir * y <= 0.0;
}
template <class SpringForce>
inline bool fired(const Friction& fr, double mobile, double dir, double y,
                  SpringForce&& spring_force) {
  return mobile != 0.0 ? stopped(dir, y) : fr.breaks(spring_force());
}

// Located: the work of a piece of length tau, given the sliding blocks' powers summed in
// block order (Friction's step_power, per unit mass).
inline double located_work(double tau, double m_u, double power_sum) {
  return 0.5 * tau * m_u * power_sum;
}

// Both: with the pad moving, which far stuck block the anchor's swing breaks: +1 the one
// of largest anchor-free force g_max (g_max + k_p anchor > threshold), -1 (with backslip)
// the one of smallest g_min, 0 none.
inline int far_failure(const Friction& fr, double k_p, double g_max, double g_min, double anchor) {
  if (g_max + k_p * anchor > fr.threshold) return 1;
  if (fr.backslip && g_min + k_p * anchor < -fr.threshold) return -1;
  return 0;
}

}  // namespace bkq::transition
