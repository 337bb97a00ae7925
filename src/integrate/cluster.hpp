// The event engine's commonest cases, a few blocks sliding between two neighbours that
// hold (most events of the shipped scenes), advanced by a scheme's Method over the
// cluster's registers (ClusterLayout, integrate/layouts.hpp) instead of its range loops.
//
// A cluster is one covered range [lo, lo + K + 2) whose two end blocks are stuck: K
// interior blocks, some sliding, some stuck, and nothing else in the chain moving but
// the pad, where it moves (Pad). With K a compile-time constant the whole cluster lives
// in registers. run_cluster() runs the scheme's step after step and after each one does
// what the engine's general path does, in the same order: it adds the dissipated power to
// the energy balance (dissipated_power's sum), applies the Crossing rule and the release
// test to every block of the range in block order (settle_contacts' rule,
// engine/contacts.hpp), and with the pad adds the pad damper's work and tests whether the
// pad's swing broke a far stuck block (the force tree's extremes, constant while the
// cluster runs). It returns after the first step at whose end every block is stuck, a
// block broke loose, a speed is not finite, or the step budget ran out: the caller then
// does its usual end-of-step bookkeeping, and the general path takes over if the event
// goes on in another shape.
//
// With the pad moving it is one more element of the scheme's stages, exactly as
// ChainLayout advances it (the anchor at each stage is the substrate plus the pad's stage
// position; the pad's acceleration reads the stage's sum of block positions, formed from
// the cluster's terms in block order). The stuck end blocks add exactly zero to every
// sum, so they are left out.
//
// Every operation is the one the general path performs, in the same order (the stuck
// ends' stage positions equal their positions), so the events are the same bit for bit;
// tests/regression/test_cluster.cpp and test_pad_paths.cpp run both paths and compare.
//
// Only these shapes are compiled (docs/developer/build-time.md): located transitions, a
// cluster at a free chain end and the other cases of kClusterKernel below take the general
// path, which gives the same events bit for bit.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "integrate/layouts.hpp"
#include "integrate/transition_rule.hpp"
#include "model/chain.hpp"
#include "model/stick.hpp"

namespace bkq {

// Largest number of blocks a cluster may have between its ends (the code is instantiated
// for each size up to it).
inline constexpr int kMaxCluster = 8;

struct ClusterRelaxation {
  // Set by the caller.
  int lo = 0;          // the range is [lo, lo + k + 2); its end blocks are stuck,
  int k = 1;           // k interior blocks, 1..kMaxCluster, between them
  double anchor = 0;   // substrate + pad (the pad held; not read when it moves)
  SubstrateState sub;  // the frozen substrate
  double dt = 0;
  double half_dt_m = 0;        // trapezoidal weight of the dissipated power: dt m_u / 2
  std::int64_t max_steps = 0;  // return after this many steps at most
  // With the pad moving: the force tree's largest and smallest anchor-free force g over
  // the uncovered stuck blocks, and the pad damper's trapezoidal weight.
  double far_max = -HUGE_VAL, far_min = HUGE_VAL;
  double half_dt_cp = 0;
  // Advanced: the range's entries of the state, and the time.
  ChainState* state = nullptr;
  double* dissipated = nullptr;  // += half_dt_m * power, step by step
  // What happened.
  std::int64_t steps = 0;
  std::int64_t sliding_block_steps = 0;         // sliding blocks at the end of each step, summed
  double max_speed = 0;                         // NaN if a speed became NaN
  int sliding = 0;                              // sliding blocks after the last step
  std::array<int, kMaxCluster + 2> released{};  // blocks that broke loose then, in order
  int n_released = 0;
  bool far_break = false;  // with the pad moving: the last step's swing broke a far block
};

// The laws and force terms the cluster kernel is compiled for: the event-driving laws of the
// shipped scenes, with neighbour springs. Elsewhere run_cluster returns false and the
// general path, which gives the same events, takes the steps: without neighbour springs
// (k_c = 0) every event is one block, which the lone-slip replay takes; a tabulated law
// pays for its own look-ups; the block damper is the 1DOF model's single block, which never
// forms a cluster. Each compiled combination costs every scheme 16 shapes x pad x located.
template <class Law, class Terms>
inline constexpr bool kClusterKernel = (Law::drives_events && Terms::neighbours && !Terms::damper &&
                                        !std::is_same_v<Law, law::Table>);

// The arrays a scheme's cluster step works on: entries 0 and K + 1 are the stuck ends.
template <int K>
using ClusterArray = std::array<double, K + 2>;

// Runs the loop described above with the Method's step on ClusterArray<K> positions and
// velocities, interior entries only, the stick flags and directions of sliding frozen for
// the step. Returns false, having done nothing, where kClusterKernel is false.
template <class Method, bool Pad, int K>
bool run_cluster_sized(const ChainForces& forces, ClusterRelaxation& r) {
  static_assert(K >= 1 && K <= kMaxCluster);
  return forces.with_switches([&]<class Law, class Terms>(const Law& law_in) {
    // The block damper is the 1DOF model's, a single block free at both ends, which
    // run_cluster turns away before it gets here: no kernel is compiled for it.
    if constexpr (!kClusterKernel<Law, Terms>) {
      return false;
    } else {
      const Law law = law_in;  // a local, which the stores cannot change
      using Array = ClusterArray<K>;
      const Friction& fr = forces.friction();
      const ModelParams& p = forces.params();
      const double damper = p.c_u / p.m_u, kp = p.k_p;
      const bool velocity_dependent = bkq::velocity_dependent(p, Pad);
      ChainState& st = *r.state;
      double* w_all = st.w.data();
      const int lo = r.lo;
      // The entries: the stuck ends 0 and K + 1 and the blocks between them.
      constexpr int first = 0, last = K + 1;
      const double dt = r.dt, half_dt_m = r.half_dt_m, half_dt_cp = r.half_dt_cp;
      const double far_max = r.far_max, far_min = r.far_min;
      const SubstrateState sub = r.sub;
      // The anchor less the pad's position: the substrate, or the whole anchor when held.
      const double base = Pad ? sub.s : r.anchor;
      // Everything the loop carries lives in locals (written back once at the end), so the
      // stores into the state cannot force reloads; the sums are formed in the same order.
      Array w{}, y{}, mobile{}, dir{};
      for (int i = first; i <= last; ++i) {
        w[i] = w_all[lo + i];
        y[i] = st.wd[lo + i];
        mobile[i] = st.mobile[lo + i];
        dir[i] = st.dir[lo + i];
      }
      PadStageState pad{};
      if constexpr (Pad) pad = {st.x, st.xd, st.sum_w};
      double t = st.t, dissipated = *r.dissipated, max_speed = r.max_speed;
      std::int64_t steps = 0, sliding_block_steps = 0;
      int sliding = 0, n_released = 0;
      bool far_break = false;
      // Each block's friction magnitude |phi(y)| at its current velocity: the power at the
      // end of one step needs it, and the first stage of the next step and the power at
      // its start need it again (the same value, so it is divided out once).
      const double magnitude_at_rest = law.magnitude(0.0);
      Array magnitude{};
      for (int i = first; i <= last; ++i) magnitude[i] = law.magnitude(y[i]);
      // A lone block slides throughout the run (it ends at the step where it sticks), and
      // 1 * acc is acc: the product is left out of its critical path.
      auto flagged = [&](int i, double acc) { return K == 1 ? acc : mobile[i] * acc; };
      auto force = [&](const Array& x, int i, double anchor) {
        return forces.interior_force<Terms>(x[i - 1], x[i], x[i + 1], anchor);
      };
      auto acceleration = [&](const Array& x, const Array& v, double anchor, Array& a) {
        for (int i = 1; i <= K; ++i)
          a[i] = flagged(i, forces.acceleration<Law, Terms, false>(law, force(x, i, anchor), v[i],
                                                                   dir[i], sub));
      };
      for (bool done = false; !done;) {
        const Array y0 = y, magnitude0 = magnitude;
        const double xd_old = pad.xd;
        const double anchor0 = Pad ? base + pad.x : base;
        Array a;  // the first stage's accelerations, at the start of the step
        for (int i = 1; i <= K; ++i)
          a[i] = flagged(i, forces.acceleration_given<Law, Terms, false>(
                                force(w, i, anchor0), magnitude[i], y[i], dir[i], sub));
        {
          ClusterLayout<typename Method::Round, decltype(acceleration), Array, Pad> layout(
              forces, base, acceleration, w, y, a, pad, velocity_dependent);
          Method::advance(layout, dt);
        }
        for (int i = 1; i <= K; ++i) w_all[lo + i] = w[i];  // the spring forces below read them
        t += dt;
        ++steps;

        // The crossing rule's work (dissipated_power's sum, in the same order).
        dissipated += half_dt_m * transition::range_power(last - first + 1, [&](int m) {
                        const int i = first + m;
                        magnitude[i] = law.magnitude(y[i]);
                        return transition::crossing_power<Law::backslip>(
                            mobile[i], magnitude0[i], y0[i], magnitude[i], y[i], dir[i], damper);
                      });

        // The stick rule (model/stick.hpp), block by block.
        const double anchor = Pad ? base + pad.x : base;
        sliding = 0;
        n_released = 0;
        for (int i = first; i <= last; ++i) {
          const int j = lo + i;
          const bool was_sliding = mobile[i] != 0.0;
          const stick::Outcome o = transition::settle(fr, mobile[i], dir[i], y0[i], y[i], [&] {
            return forces.spring_force(w_all, j, anchor);
          });
          y[i] = o.y;
          mobile[i] = o.mobile;
          dir[i] = o.dir;
          if (o.slides) {
            if (o.y == 0.0) magnitude[i] = magnitude_at_rest;  // clst91 after a crossing
            ++sliding;
            raise_max_speed(max_speed, std::abs(o.y));
          } else if (o.breaks) {
            ++sliding;
            r.released[n_released++] = j;
          } else if (was_sliding) {
            magnitude[i] = magnitude_at_rest;  // it stuck
          }
        }
        if constexpr (Pad) dissipated += half_dt_cp * (xd_old * xd_old + pad.xd * pad.xd);
        sliding_block_steps += sliding;
        // The far blocks' test (the event engine's, over its force tree), with the anchor
        // formed as the engine forms it.
        if constexpr (Pad)
          far_break = transition::far_failure(fr, kp, far_max, far_min, anchor) != 0;
        done = sliding == 0 || n_released > 0 || far_break || !std::isfinite(max_speed) ||
               steps >= r.max_steps;
      }
      for (int i = first; i <= last; ++i) {
        st.wd[lo + i] = y[i];
        st.mobile[lo + i] = mobile[i];
        st.dir[lo + i] = dir[i];
      }
      if constexpr (Pad) {
        st.x = pad.x;
        st.xd = pad.xd;
        st.sum_w = pad.sum_w;
        r.far_break = far_break;
      }
      st.t = t;
      *r.dissipated = dissipated;
      r.max_speed = max_speed;
      r.steps = steps;
      r.sliding_block_steps = sliding_block_steps;
      r.sliding = sliding;
      r.n_released = n_released;
      return true;
    }
  });
}

// Calls run_cluster_sized with K = r.k.
template <class Method, bool Pad>
bool run_cluster(const ChainForces& forces, ClusterRelaxation& r) {
  return [&]<int... Ks>(std::integer_sequence<int, Ks...>) {
    bool ran = false;
    ((r.k == Ks + 1 && (ran = run_cluster_sized<Method, Pad, Ks + 1>(forces, r), true)) || ...);
    return ran;
  }
  (std::make_integer_sequence<int, kMaxCluster>());
}

}  // namespace bkq
