// Stick and slip transitions between steps, shared by the continuous driver and the event
// relaxation: the stick rule of model/stick.hpp applied to the covered ranges, block by
// block for short ranges, the chain ends and the releases (settle_block), and as one
// vectorised pass over long runs of interior blocks (settle_interior, contacts.cpp), which
// counts the releases and leaves them to settle_block in block order, so that `on_release`
// hears of them in the same order. Each block's transition depends only on the positions,
// which the pass does not change, so settling them all at once is the same as one by one.
// dissipated_power(), called before the pass, adds up the power the sliding blocks
// dissipate in friction (and the 1DOF damper) at the two ends of the step, with each
// block's direction frozen as in the step; the caller turns it into work (trapezoidal).
#pragma once

#include <cmath>

#include "model/chain.hpp"
#include "model/stick.hpp"

namespace bkq {

struct ContactScan {
  int sliding = 0;       // blocks sliding after the pass
  double max_speed = 0;  // largest |relative velocity| among them; NaN if any is NaN
};

namespace contacts_detail {

// Ranges shorter than this go block by block (settle_block): below it the vector loop's
// set-up costs more than the branches.
inline constexpr int kMinInteriorRun = 32;

// What settle_interior found.
struct InteriorPass {
  int sliding = 0;       // blocks sliding after it, not counting the releases
  double max_speed = 0;  // largest |relative velocity| among them; NaN if any is NaN
  int breaks = 0;        // stuck blocks that break loose (left stuck for now)
  int first_break = 0;   // the first of them (hi if none)
};

// Blocks lo..hi-1, none of them a chain end: every transition but the releases.
InteriorPass settle_interior(const ChainForces& forces, ChainState& st, const double* wd_old,
                             double anchor, int lo, int hi, bool crossing_rule);

// Block j; adds to the count of sliding blocks and the speed maximum.
template <class OnRelease>
void settle_block(const ChainForces& forces, ChainState& st, const double* wd_old, double anchor,
                  int j, bool crossing_rule, OnRelease& on_release, ContactScan& out) {
  const Friction& fr = forces.friction();
  const stick::Outcome o =
      stick::settle_one(fr, crossing_rule, st.mobile[j], st.dir[j], wd_old[j], st.wd[j],
                        [&] { return forces.holding_force(st.w.data(), st.wd.data(), j, anchor); });
  st.wd[j] = o.y;
  st.mobile[j] = o.mobile;
  st.dir[j] = o.dir;
  if (o.slides) {
    ++out.sliding;
    raise_max_speed(out.max_speed, std::abs(o.y));
  } else if (o.breaks) {
    ++out.sliding;
    on_release(j);
  }
}

}  // namespace contacts_detail

// Friction::step_power summed over the blocks that slid through the step (stick flags
// not yet settled; wd_old the velocities at its start, stuck blocks' exactly 0): each
// range in the order of RangePowerSum (model/friction.hpp), which the cluster path
// (integrate/cluster.hpp) uses too, and the ranges in order.
double dissipated_power(const ChainForces& forces, const ChainState& st, const double* wd_old,
                        Ranges ranges);

template <class OnRelease>
ContactScan settle_contacts(const ChainForces& forces, ChainState& st, const double* wd_old,
                            double anchor, Ranges ranges, bool crossing_rule,
                            OnRelease&& on_release) {
  using namespace contacts_detail;
  ContactScan out;
  auto block = [&](int j) {
    settle_block(forces, st, wd_old, anchor, j, crossing_rule, on_release, out);
  };
  const int n = forces.n();
  for (const Range& r : ranges) {
    // The vectorised pass writes the nearest-neighbour spring force out; a longer coupling
    // or dashpots go block by block through holding_force (with dashpots a block's force
    // reads its neighbours' velocities, which the pass settles in block order).
    if (r.hi - r.lo < kMinInteriorRun || forces.general_kernel()) {
      for (int j = r.lo; j < r.hi; ++j) block(j);
      continue;
    }
    int lo = r.lo, hi = r.hi;
    if (lo == 0) block(lo++);
    const bool last = hi == n;
    if (last) --hi;
    const InteriorPass pass = settle_interior(forces, st, wd_old, anchor, lo, hi, crossing_rule);
    out.sliding += pass.sliding;
    raise_max_speed(out.max_speed, pass.max_speed);
    // The releases it left, in block order (a block it has just stuck cannot break loose:
    // friction holds it).
    for (int j = pass.first_break, left = pass.breaks; left > 0 && j < hi; ++j) {
      if (st.mobile[j] != 0.0) continue;
      block(j);
      if (st.mobile[j] != 0.0) --left;
    }
    if (last) block(n - 1);
  }
  return out;
}

}  // namespace bkq
