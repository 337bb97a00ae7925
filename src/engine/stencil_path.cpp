// The stencil kernel path (see stencil_path.hpp).
#include "engine/stencil_path.hpp"

#include <algorithm>

namespace bkq {

bool StencilPath::advance(Relaxation& rx, PathReport& out) {
  const ChainForces& forces = rx.forces;
  if (!rx.stencil || rx.traits.stencil_kernel == nullptr ||
      rx.traits.stick_rule != StickRule::Crossing || !forces.general_kernel() || forces.viscous() ||
      forces.rayleigh() || rx.pad)
    return false;
  const Ranges ranges = rx.active.ranges();
  r_.state = &rx.st;
  r_.build(forces, ranges);
  if (!r_.usable) return false;
  r_.dissipated = &rx.dissipated;
  r_.anchor = rx.anchor();
  r_.sub = SubstrateState{rx.st.s, 0.0, 0.0};
  r_.dt = rx.dt;
  r_.half_dt_m = 0.5 * rx.dt * forces.params().m_u;
  // Stop at the step where the general path would give up on the event.
  r_.max_steps = rx.max_steps + 1 - rx.steps;
  r_.steps_before = rx.steps;
  r_.event = rx.active.uncovers();
  r_.refit_every = kShrinkEvery;
  if (!rx.traits.stencil_kernel(forces, r_)) return false;
  steps_ += r_.steps;
  out.steps = r_.steps;
  out.block_steps = static_cast<std::int64_t>(r_.site.size()) * r_.steps;
  out.sliding_block_steps = r_.sliding_block_steps;
  out.sliding = r_.sliding;
  out.max_speed = r_.max_speed;
  out.stick_time = rx.stepper.located_stick_time();
  out.released = r_.released;
  return true;
}

}  // namespace bkq
