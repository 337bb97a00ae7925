// The stick rule (Crossing, integrate/stepper.hpp): what becomes of one block at the end
// of a step, in one place for every path that applies it (engine/contacts.hpp, block by
// block and branch-free over long runs; the cluster loop, integrate/cluster.hpp; the lone
// slip's record, engine/lone_slip.cpp).
//  - A sliding block whose velocity relative to the substrate went from y0 to y1 has
//    crossed zero if it changed sign or is exactly 0 (for a law without backslip: if
//    y1 <= 0). Then it sticks, with zero velocity, if friction holds its spring force f;
//    otherwise it slides on, the other way (backslip) or at zero velocity (no backslip).
//    A block that slides on slides the way its velocity points (unchanged at 0).
//  - A stuck block breaks loose if its spring force exceeds the static threshold; the
//    caller releases it (it slides the way its spring pulls).
// The rule is written without branches, so a loop over many blocks vectorises; the force
// matters only where needs_force() says so, and a caller may pass anything elsewhere.
#pragma once

#include <cmath>

#include "model/friction.hpp"

namespace bkq::stick {

// Has a sliding block whose velocity went from y0 to y1 crossed zero? (Backslip: the
// law's flag as a constant, for the branch-free form below.)
template <bool Backslip>
inline bool crossed(double y0, double y1) {
  if constexpr (Backslip)
    return (y0 * y1 < 0.0) | (y1 == 0.0);
  else
    return y1 <= 0.0;
}
inline bool crossed(bool backslip, double y0, double y1) {
  return backslip ? crossed<true>(y0, y1) : crossed<false>(y0, y1);
}

// Does the rule look at the spring force of this block after this step?
inline bool needs_force(const Friction& fr, bool crossing_rule, double mobile, double y0,
                        double y1) {
  return mobile == 0.0 || (crossing_rule && crossed(fr.backslip, y0, y1));
}

struct Outcome {
  double y;       // velocity after the rule
  double mobile;  // stick flag (a block that breaks loose is left stuck: see `breaks`)
  double dir;     // direction of sliding
  bool slides;    // a sliding block that slides on
  bool breaks;    // a stuck block that breaks loose
};

// What the rule did besides the state it leaves.
struct Transition {
  bool slides;  // a sliding block that slides on
  bool breaks;  // a stuck block that breaks loose (left stuck: the caller releases it)
};

// The rule for one block in place: velocity y (y1 at the end of the step on entry), stick
// flag `mobile` and direction `dir` become their values after the rule; y0 is the velocity
// at the start of the step, f the spring force. `crossing_rule` false leaves sliding
// blocks sliding (a stepper that resolved its transitions itself). Backslip is
// fr.backslip as a constant. This is the form a loop over many blocks calls: GCC
// vectorises it into fewer instructions than the form returning an Outcome (compare with
// build/bench_steppers).
template <bool Backslip>
inline Transition settle_in_place(const Friction& fr, bool crossing_rule, double y0, double f,
                                  double& y, double& mobile, double& dir) {
  const double y1 = y, m = mobile, d = dir;
  const bool sliding = m != 0.0;
  const bool cross = crossing_rule & sliding & crossed<Backslip>(y0, y1);
  const bool stick = cross & fr.holds(f);
  const bool slides = sliding & !stick;
  const double y_after = cross & (stick | !Backslip) ? 0.0 : y1;
  y = y_after;
  mobile = stick ? 0.0 : m;
  dir = slides & (y_after != 0.0) ? std::copysign(1.0, y_after) : d;
  return Transition{slides, static_cast<bool>(!sliding & fr.breaks(f))};
}

// The same, taking the block's values and returning them: stick flag `mobile`, direction
// `dir`, velocity y0 at the start of the step and y1 at its end, spring force f.
inline Outcome settle(const Friction& fr, bool crossing_rule, double mobile, double dir, double y0,
                      double y1, double f) {
  double y = y1;
  const Transition t = fr.backslip
                           ? settle_in_place<true>(fr, crossing_rule, y0, f, y, mobile, dir)
                           : settle_in_place<false>(fr, crossing_rule, y0, f, y, mobile, dir);
  return Outcome{y, mobile, dir, t.slides, t.breaks};
}

// The direction a block that breaks loose under spring force f slides in.
inline double release_direction(double f) {
  return std::copysign(1.0, f);
}

// The same rule for one block, with branches: for the short runs of the event relaxation,
// where the branches predict well and the spring force is computed only where the rule
// looks at it. A stuck block that breaks loose is released here (mobile 1, sliding the
// way its spring pulls: release_direction), unlike settle(), which leaves that to the
// caller. A test holds the two forms against each other.
template <class SpringForce>
inline Outcome settle_one(const Friction& fr, bool crossing_rule, double mobile, double dir,
                          double y0, double y1, SpringForce&& spring_force) {
  if (mobile != 0.0) {
    if (crossing_rule && crossed(fr.backslip, y0, y1)) {
      if (fr.holds(spring_force())) return Outcome{0.0, 0.0, dir, false, false};
      if (!fr.backslip) y1 = 0.0;
    }
    return Outcome{y1, mobile, y1 != 0.0 ? std::copysign(1.0, y1) : dir, true, false};
  }
  const double f = spring_force();
  if (fr.breaks(f)) return Outcome{y1, 1.0, release_direction(f), false, true};
  return Outcome{y1, mobile, dir, false, false};
}

}  // namespace bkq::stick
