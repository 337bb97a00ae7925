// The general step (see general_path.hpp).
#include "engine/general_path.hpp"

#include <algorithm>

#include "engine/contacts.hpp"

namespace bkq {

bool GeneralStepPath::held_ranges(const Relaxation& rx) {
  // The fused held-range pass reads only j +- 1 and has no dashpots: a coupling of longer
  // range or viscous takes the general step.
  if (!rx.held_ranges || !rx.traits.fused_kernels || rx.forces.general_kernel()) return false;
  for (const Range& r : rx.active.ranges())
    if (rx.st.mobile[r.lo] != 0.0 || rx.st.mobile[r.hi - 1] != 0.0) return false;
  return true;
}

bool GeneralStepPath::advance(Relaxation& rx, PathReport& out) {
  const ChainForces& forces = rx.forces;
  ChainState& st = rx.st;
  const double dt = rx.dt;
  const ModelParams& p = forces.params();
  const bool crossing = rx.traits.stick_rule == StickRule::Crossing;
  const bool located = rx.traits.located_on_fixed_steps;
  Ranges ranges = rx.active.ranges();
  // A stepper that resolves transitions itself covers the blocks it released before the
  // contact pass, which then reads the copies over the grown ranges: for it they cover the
  // whole chain and keep what earlier steps left (as they always did).
  if (crossing)
    old_.fit(ranges);
  else
    old_.whole(forces.n());
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const Range& r = ranges[i];
    std::copy(st.wd.begin() + r.lo, st.wd.begin() + r.hi, old_.data(kWdOld, i) + r.lo);
    if (!crossing) {
      std::copy(st.mobile.begin() + r.lo, st.mobile.begin() + r.hi,
                old_.data(kMobileOld, i) + r.lo);
      std::copy(st.w.begin() + r.lo, st.w.begin() + r.hi, old_.data(kWOld, i) + r.lo);
    }
  }
  const double xd_old = st.xd;
  // The dashpots' power at the start of the step (trapezoidal rule with the end's).
  const double damper_old = forces.damper_power(st.wd.data(), ranges);
  const Substrate frozen = Substrate::frozen(st.s);
  if (held_ranges(rx)) {
    rx.stepper.step_held(forces, frozen, st, dt, ranges);
    if (rx.pad) ++pad_held_steps_;
  } else {
    rx.stepper.step(forces, frozen, st, dt, ranges);
  }
  double& dissipated = rx.dissipated;
  if (forces.viscous())
    dissipated += 0.5 * dt * (damper_old + forces.damper_power(st.wd.data(), ranges));
  out.steps = 1;
  for (const Range& r : ranges) out.block_steps += r.hi - r.lo;
  inside_.clear();
  if (!crossing) {
    collect_released_inside(rx);
    ranges = rx.active.ranges();
  }
  released_.clear();
  ContactScan scan;
  const double half_dt_m = 0.5 * dt * p.m_u;
  auto on_release = [&](int j) { released_.push_back(j); };
  if (old_.joint()) {
    const double* wd_old = old_.data(kWdOld, 0);
    dissipated +=
        located ? rx.stepper.step_work() : half_dt_m * dissipated_power(forces, st, wd_old, ranges);
    scan = settle_contacts(forces, st, wd_old, rx.anchor(), ranges, crossing, on_release);
  } else {
    // Range by range, each with its copy: the sums and the releases in the order of one
    // pass over all ranges.
    double power = 0;
    for (std::size_t i = 0; i < ranges.size(); ++i)
      power += dissipated_power(forces, st, old_.data(kWdOld, i), Ranges(&ranges[i], 1));
    dissipated += located ? rx.stepper.step_work() : half_dt_m * power;
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      const ContactScan part = settle_contacts(forces, st, old_.data(kWdOld, i), rx.anchor(),
                                               Ranges(&ranges[i], 1), crossing, on_release);
      scan.sliding += part.sliding;
      raise_max_speed(scan.max_speed, part.max_speed);
    }
  }
  if (rx.pad) dissipated += 0.5 * dt * p.c_p * (xd_old * xd_old + st.xd * st.xd);
  out.sliding_block_steps = scan.sliding;
  out.sliding = scan.sliding;
  out.max_speed = scan.max_speed;
  out.stick_time = rx.stepper.located_stick_time();
  out.released = released_;
  out.released_inside = inside_;
  return true;
}

void GeneralStepPath::collect_released_inside(Relaxation& rx) {
  // The stepper's own list first (it knows blocks that broke loose and stuck again inside
  // the step, and where they were), then any block whose flag went from stuck to sliding.
  for (const Stepper::Release& r : rx.stepper.releases_in_step()) inside_.push_back(r);
  const Ranges ranges = rx.active.ranges();
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const double* mobile_old = old_.data(kMobileOld, i);
    const double* w_old = old_.data(kWOld, i);
    for (int j = ranges[i].lo; j < ranges[i].hi; ++j)
      if (rx.st.mobile[j] != 0.0 && mobile_old[j] == 0.0) {
        // Stuck, so unmoved, until it broke loose inside the step. It may have slipped
        // earlier in the event: cover it again all the same.
        inside_.push_back(Stepper::Release{j, w_old[j]});
      }
  }
  for (const Stepper::Release& r : inside_) rx.active.cover(r.block);
}

}  // namespace bkq
