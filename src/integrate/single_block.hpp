// The event engine's commonest case, one block sliding between two neighbours that hold
// (78% of the carlson-langer scene's events never involve a second block), advanced by a
// scheme's scalar form instead of its range loops.
//
// While block j slides alone and its neighbours hold, nothing else in the chain moves
// (the pad is held: the caller checks), so the block is a one-degree-of-freedom system
// with fixed neighbour positions. A Crossing stepper (rk2, rk4, verlet) supplies its
// step for one block as a scalar function; run_single_block() runs it step after step
// with the Crossing rule of engine/contacts.hpp, adds the dissipated power to the energy
// balance the way the engine does, and watches both neighbours. It returns after the
// first step at whose end the block is stuck, a neighbour broke loose, the speed is not
// finite, or the step budget ran out: the caller then does its usual end-of-step
// bookkeeping, and the general path takes over if the event goes on.
//
// Every operation is the one the general path performs, in the same order (the
// neighbours' stage positions equal their positions, since they hold), so the events
// are the same bit for bit; tests/regression/test_events.cpp runs both paths and
// compares the catalogs.
#pragma once

#include <cmath>
#include <cstdint>

#include "model/chain.hpp"

namespace bkq {

struct SingleBlockRelaxation {
  // Set by the caller.
  int block = 0;               // interior: 0 < block < n - 1, neighbours stuck
  double anchor = 0;           // substrate + pad (the pad is held)
  SubstrateState sub;          // the frozen substrate
  double dt = 0;
  double half_dt_m = 0;        // trapezoidal weight of the dissipated power: dt m_u / 2
  std::int64_t max_steps = 0;  // return after this many steps at most
  // Advanced: the block's entries of the state, and the time.
  ChainState* state = nullptr;
  double* dissipated = nullptr;  // += half_dt_m * power, step by step
  // What happened.
  std::int64_t steps = 0;
  std::int64_t sliding_block_steps = 0;  // sliding blocks at the end of each step, summed
  double max_speed = 0;                  // NaN if the speed became NaN
  int sliding = 0;                       // sliding blocks after the last step
  int released[2] = {0, 0};              // neighbours that broke loose then, by index
  int n_released = 0;
};

// Runs the loop described above with the scheme's scalar step
//   advance(acceleration, w, y, h)
// where acceleration(w, y) is the block's acceleration at position w and velocity y
// with its direction of sliding frozen for the step.
template <class Advance>
void run_single_block(const ChainForces& forces, SingleBlockRelaxation& r, Advance&& advance) {
  forces.with_switches([&]<FrictionLaw Law, bool Neighbours, bool Damper>() {
    const Friction& fr = forces.friction();
    const double damper = forces.params().c_u / forces.params().m_u;
    ChainState& st = *r.state;
    double* w_all = st.w.data();
    const int j = r.block;
    const double wl = w_all[j - 1], wr = w_all[j + 1], anchor = r.anchor, dt = r.dt, half_dt_m = r.half_dt_m;
    const SubstrateState sub = r.sub;
    // Everything the loop carries lives in locals (written back once at the end), so the
    // stores into the state cannot force reloads; the sums are formed in the same order.
    double w = w_all[j], y = st.wd[j], dir = st.dir[j], t = st.t, dissipated = *r.dissipated;
    double max_speed = r.max_speed;
    std::int64_t steps = 0, sliding_block_steps = 0;
    int sliding = 1, n_released = 0;
    bool stuck = false;
    auto acceleration = [&](double ws, double ys) {
      return forces.acceleration<Law, Damper, false>(forces.interior_force<Neighbours>(wl, ws, wr, anchor), ys, dir,
                                                     sub);
    };
    for (bool done = false; !done;) {
      const double y0 = y;
      advance(acceleration, w, y, dt);
      t += dt;
      ++steps;
      w_all[j] = w;  // the neighbours' spring forces below read it
      dissipated += half_dt_m * fr.step_power(y0, y, dir, damper);

      // The Crossing rule (as settle_contacts applies it) for the block, then its
      // neighbours' holds.
      stuck = fr.stops(y0, y, [&] { return forces.spring_force(w_all, j, anchor); });
      sliding = 0;
      if (stuck) {
        y = 0.0;
      } else {
        if (y != 0.0) dir = std::copysign(1.0, y);
        sliding = 1;
        raise_max_speed(max_speed, std::abs(y));
      }
      n_released = 0;
      for (const int k : {j - 1, j + 1})
        if (fr.breaks(forces.spring_force(w_all, k, anchor))) r.released[n_released++] = k;
      sliding += n_released;
      sliding_block_steps += sliding;
      done = stuck || n_released > 0 || !std::isfinite(y) || steps >= r.max_steps;
    }
    st.wd[j] = y;
    st.dir[j] = dir;
    if (stuck) st.mobile[j] = 0.0;
    st.t = t;
    *r.dissipated = dissipated;
    r.max_speed = max_speed;
    r.steps = steps;
    r.sliding_block_steps = sliding_block_steps;
    r.sliding = sliding;
    r.n_released = n_released;
  });
}

}  // namespace bkq
