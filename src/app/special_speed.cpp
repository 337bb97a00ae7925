// The special speed of Ferre 2018 eq. 4.8; see special_speed.hpp.
#include "app/special_speed.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "engine/continuous.hpp"
#include "engine/initial_state.hpp"
#include "integrate/stepper.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"

namespace bkq {

SpecialSpeed special_speed(ModelParams p) {
  if (p.kind == ModelKind::BKP) p.kind = ModelKind::BK;  // the pad held still
  const ChainForces forces(p);
  const double period = 2 * std::numbers::pi * std::sqrt(p.m_u / p.k_p);
  const double dt = period / 20000;
  const std::unique_ptr<Stepper> stepper = make_stepper("rk4", p.n, 1e-8);
  check_time_step(*stepper, p, dt);
  ChainState st = initial_state(forces, 0, 0.0, false);
  const double d0 = p.threshold() / p.k_p;
  // Just past the threshold (relative 1e-12), so the stick rule lets every block go at t = 0.
  for (double& w : st.w) w = -d0 * (1 + 1e-12);
  ContinuousDriver driver(forces, *stepper, Substrate::constant(0.0), st, dt);
  if (driver.sliding() == 0) throw Error("special-speed: the chain did not break loose");
  double t_prev = 0, v_prev = 0, v_prev2 = 0;
  const auto max_steps = static_cast<std::int64_t>(1000 * 20000);
  for (std::int64_t i = 0; i < max_steps; ++i) {
    driver.step();
    const double v = driver.state().wd[0];
    if (i > 1 && (v <= 0 || driver.sliding() == 0)) {
      // Extrapolate the last two velocities (before any stick clamp) to zero.
      const double slope = (v_prev - v_prev2) / dt;
      const double t_zero = slope < 0 ? t_prev - v_prev / slope : driver.state().t;
      SpecialSpeed s;
      s.t_death = t_zero;
      s.v_special = d0 / t_zero;
      s.dt = dt;
      return s;
    }
    v_prev2 = v_prev;
    v_prev = v;
    t_prev = driver.state().t;
  }
  throw Error(
      "special-speed: the released chain did not return to rest relative to the substrate "
      "within 1000 periods (friction.law = none?)");
}

}  // namespace bkq
