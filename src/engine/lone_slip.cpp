// The lone block's slide, integrated once (see lone_slip.hpp).
#include "engine/lone_slip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "engine/contacts.hpp"
#include "integrate/located.hpp"
#include "integrate/stepper.hpp"
#include "model/chain.hpp"
#include "model/stick.hpp"
#include "model/substrate.hpp"

namespace bkq {

LoneSlip integrate_lone_slip(const ModelParams& p, double stiffness, const Stepper& scheme,
                             double dt, std::int64_t max_steps, bool located) {
  LoneSlip out;
  out.stiffness = stiffness;
  // One block on a pulling spring of the lone block's stiffness: its spring force is
  // stiffness * (s - w), so with w = 0 and s = F0 / stiffness it starts at the threshold
  // and w is the displacement d.
  ModelParams q = p;
  if (q.kind == ModelKind::BKP) q.kind = ModelKind::BK;
  q.n = 1;
  q.rows = 1;  // a lattice's lone site too: one block, its springs folded into the stiffness
  q.k_p = stiffness;
  q.k_c = q.k_c_y = 0;
  q.coupling = Coupling::Nearest;
  q.boundary = q.boundary_y = Boundary::Free;
  q.m_x = q.k_p0 = q.c_p = 0;
  const ChainForces forces(q);
  const Friction& fr = forces.friction();
  // The scheme's own steps (unwrapped, if it came with located transitions), on a stepper of
  // one block: a copy of the caller's, so that any scheme, registered or not, is recorded.
  const Stepper& plain_scheme = scheme.scheme();
  auto stepper = plain_scheme.fresh(1);
  if (stepper->stick_rule() != StickRule::Crossing) {
    out.why_not = "the stepper resolves transitions itself";
    return out;
  }
  // Located: the wrapper steps; the plain scheme repeats each attempted step on a copy, so
  // that the margin of the velocity's sign at its end is measured where it is decided.
  std::unique_ptr<Stepper> plain;
  const LocatedTransitions* wrapper = nullptr;
  if (located) {
    plain = plain_scheme.fresh(1);
    stepper = with_located_transitions(std::move(stepper), 1);
    wrapper = static_cast<const LocatedTransitions*>(stepper.get());
  }
  ChainState st;
  st.resize(1);
  st.s = fr.threshold / stiffness;
  st.mobile[0] = 1.0;
  st.dir[0] = 1.0;
  const Substrate frozen = Substrate::frozen(st.s);
  const Range all[1] = {Range{0, 1}};
  const double half_dt_m = 0.5 * dt * q.m_u;
  double wd_old = 0, work = 0, d_max = 0, d_min = 0, max_speed = 0;
  std::int64_t sliding_steps = 0;
  out.velocity_margin = out.force_margin = HUGE_VAL;
  bool released = false;
  while (st.mobile[0] != 0.0) {
    if (static_cast<std::int64_t>(out.steps.size()) >= max_steps) {
      out.why_not = "the lone block did not stick within the step bound";
      return out;
    }
    wd_old = st.wd[0];
    if (located) {
      ChainState attempt = st;
      plain->step(forces, frozen, attempt, dt, all);
      out.velocity_margin = std::min(out.velocity_margin, std::abs(attempt.wd[0]));
      stepper->step(forces, frozen, st, dt, all);
      work += wrapper->step_work();
      if (st.mobile[0] == 0.0) {  // stuck at the located instant, where friction held f
        const double f = forces.spring_force(st.w.data(), 0, st.s);
        out.force_margin =
            std::min(out.force_margin, std::abs((fr.backslip ? std::abs(f) : f) - fr.threshold));
      }
    } else {
      stepper->step(forces, frozen, st, dt, all);
      work += half_dt_m * dissipated_power(forces, st, &wd_old, all);
      // The decisions the rule takes below, and how far each is from going the other way.
      const double y0 = wd_old, y1 = st.wd[0];
      out.velocity_margin = std::min(out.velocity_margin, std::abs(y1));
      if (stick::crossed(fr.backslip, y0, y1)) {
        const double f = forces.spring_force(st.w.data(), 0, st.s);
        out.force_margin =
            std::min(out.force_margin, std::abs((fr.backslip ? std::abs(f) : f) - fr.threshold));
      }
    }
    const ContactScan scan =
        settle_contacts(forces, st, &wd_old, st.s, all, !located, [&](int) { released = true; });
    if (released || !std::isfinite(st.w[0]) || !std::isfinite(st.wd[0])) {
      out.why_not = "the lone block's integration did not stay finite";
      return out;
    }
    LoneSlip::Step s;
    s.d = st.w[0];
    s.v = st.wd[0];
    s.dir = st.dir[0];
    s.t = st.t;
    s.work = work;
    d_max = std::max(d_max, s.d);
    d_min = std::min(d_min, s.d);
    s.d_max = d_max;
    s.d_min = d_min;
    raise_max_speed(max_speed, scan.max_speed);
    s.max_speed = max_speed;
    s.sliding = scan.sliding;
    sliding_steps += scan.sliding;
    s.sliding_steps = sliding_steps;
    out.steps.push_back(s);
  }
  if (out.steps.back().d == 0.0) {
    out.why_not = "the lone block does not move";
    return out;
  }
  if (located) out.stick_time = stepper->located_stick_time();
  out.usable = true;
  return out;
}

LoneSlipTolerance lone_slip_tolerance(const ModelParams& p, double position_scale, double dt,
                                      std::int64_t steps) {
  return lone_slip_tolerance(p, position_scale, dt, steps, 2.0 * p.k_c);
}

LoneSlipTolerance lone_slip_tolerance(const ModelParams& p, double position_scale, double dt,
                                      std::int64_t steps, double coupled) {
  // A direct step rounds positions of size position_scale, a few times eps * scale each
  // step; a spring force sees position errors through at most k_p + 2 C (its own position
  // through k_p + C, its partners' through C; C = 2 k_c in a chain). Over n steps the
  // force errors accumulate into the velocity (n dt / m_u) and both into the position.
  constexpr double kSafety = 10;  // ten times the worst case (lone_slip.hpp)
  const double eps = std::numeric_limits<double>::epsilon();
  const double n = static_cast<double>(std::max<std::int64_t>(steps, 1));
  const double stiffness = p.k_p + 2.0 * coupled;
  const double per_step = 4.0 * eps * (position_scale + p.threshold() / stiffness);
  const double force_rounding = stiffness * per_step;
  // (and velocities, of size at most F0/m_u * n dt, round by eps each operation)
  const double velocity =
      n * dt * force_rounding / p.m_u + 4.0 * eps * n * (p.threshold() / p.m_u * n * dt);
  const double position = n * dt * velocity + n * per_step;
  return LoneSlipTolerance{kSafety * (force_rounding + stiffness * position), kSafety * velocity};
}

}  // namespace bkq
