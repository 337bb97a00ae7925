// The cluster kernel path (see cluster_path.hpp).
#include "engine/cluster_path.hpp"

#include <algorithm>

namespace bkq {

bool ClusterPath::ready(const Relaxation& rx, ClusterRelaxation& r) {
  // One covered range (so every sliding block is inside it) and at most kMaxCluster
  // blocks between its ends, which are stuck blocks (a sliding block at a free chain end
  // takes the general step; the stepper refuses the laws it has no code for:
  // kClusterKernel). The kernels read j +- 1 and have no dashpots: a coupling of longer
  // range or viscous takes the general step.
  const Ranges ranges = rx.active.ranges();
  if (!rx.cluster || !rx.traits.cluster_kernel || ranges.size() != 1 || rx.forces.general_kernel())
    return false;
  const Range& range = ranges.front();
  r.lo = range.lo;
  r.k = range.hi - range.lo - 2;
  if (r.k < 1 || r.k > kMaxCluster) return false;
  return rx.st.mobile[range.lo] == 0.0 && rx.st.mobile[range.hi - 1] == 0.0;
}

bool ClusterPath::advance(Relaxation& rx, PathReport& out) {
  ClusterRelaxation r;
  if (!ready(rx, r)) return false;
  const int k = r.k;
  const double dt = rx.dt;
  r.anchor = rx.anchor();
  r.sub = SubstrateState{rx.st.s, 0.0, 0.0};
  r.dt = dt;
  r.half_dt_m = 0.5 * dt * rx.forces.params().m_u;
  // Stop at the step where the general path would give up on the event, and, with more
  // than one interior block, at the next shrink (it may split the range). A lone sliding
  // block keeps its range exactly as the shrink would leave it.
  r.max_steps = rx.max_steps + 1 - rx.steps;
  if (k > 1)
    r.max_steps = std::min<std::int64_t>(r.max_steps, kShrinkEvery - rx.steps % kShrinkEvery);
  r.state = &rx.st;
  r.dissipated = &rx.dissipated;
  if (rx.pad) {
    // What the pad's form reads: the force tree's extremes over the far stuck blocks, the
    // pad damper's weight.
    r.far_max = rx.active.tree().max();
    r.far_min = rx.active.tree().min();
    r.half_dt_cp = 0.5 * dt * rx.forces.params().c_p;
  }
  if (!rx.traits.cluster_kernel(rx.forces, r)) return false;
  // A shrink due inside a lone block's run changed nothing; the one due after the last
  // step, if any, the driver does.
  steps_.all += r.steps;
  if (k > 1) steps_.multi_block += r.steps;
  const Range& range = rx.active.ranges().front();
  out.steps = r.steps;
  out.block_steps = (range.hi - range.lo) * r.steps;
  out.sliding_block_steps = r.sliding_block_steps;
  out.sliding = r.sliding;
  out.max_speed = r.max_speed;
  std::copy(r.released.begin(), r.released.begin() + r.n_released, released_);
  out.released = std::span<const int>(released_, r.n_released);
  return true;
}

}  // namespace bkq
