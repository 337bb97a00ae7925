// The event engine's commonest cases, a few blocks sliding between two neighbours that
// hold (most events of the shipped scenes), advanced by a scheme's scalar form instead of
// its range loops.
//
// A cluster is one covered range [lo, lo + K + 2) whose two end blocks are stuck: K
// interior blocks, some sliding, some stuck, and nothing else in the chain moving (the
// pad is held; the caller checks). With K a compile-time constant the whole cluster
// lives in registers. A Crossing stepper (rk2, rk4, verlet) supplies its step for the
// cluster as a function of fixed-size arrays; run_cluster() runs it step after step and
// after each one does what the engine's general path does: it adds the dissipated power
// to the energy balance (dissipated_power's sum, in the same order), and applies the
// Crossing rule and the release test to every block of the range in block order
// (settle_contacts' rule, engine/contacts.hpp). It returns after the first step at whose
// end every block is stuck, a block broke loose, a speed is not finite, or the step
// budget ran out: the caller then does its usual end-of-step bookkeeping, and the general
// path takes over if the event goes on in another shape.
//
// Every operation is the one the general path performs, in the same order (the stuck
// ends' stage positions equal their positions), so the events are the same bit for bit;
// tests/regression/test_cluster.cpp runs both paths and compares the catalogs.
//
// At a free chain end the range has no stuck block on that side: its first (or last)
// block is then the chain's end block, in any state, and the cluster's entry 0 (or
// K + 1) is a phantom. The interior force with the phantom's position equal to the end
// block's, passed as the left neighbour and the block's one real neighbour as the right,
// is the end block's spring force bit for bit: k_c ((w - 2w) + w_n) is k_c (w_n - w)
// exactly, and k_p (anchor - w) + that is spring_force's k_c (0 + (w_n - w)) -
// k_p (w - anchor) exactly.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "model/chain.hpp"
#include "model/stick.hpp"

namespace bkq {

// Largest number of blocks a cluster may have between its ends (the code is instantiated
// for each size up to it).
inline constexpr int kMaxCluster = 8;

struct ClusterRelaxation {
  // Set by the caller.
  int lo = 0;               // the range is [lo, lo + k + 2); its end blocks are stuck,
  int k = 1;                // k interior blocks, 1..kMaxCluster, between them,
  bool free_left = false;   // except that entry 0 is a phantom (lo = -1: block 0 is a free end)
  bool free_right = false;  // or entry k + 1 is (block n - 1 is a free end)
  double anchor = 0;        // substrate + pad (the pad is held)
  SubstrateState sub;       // the frozen substrate
  double dt = 0;
  double half_dt_m = 0;        // trapezoidal weight of the dissipated power: dt m_u / 2
  std::int64_t max_steps = 0;  // return after this many steps at most
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
};

// The arrays a scheme's cluster step works on: entries 0 and K + 1 are the stuck ends.
template <int K>
using ClusterArray = std::array<double, K + 2>;

// Runs the loop described above with the scheme's step
//   advance(acceleration, w, y, a, h)
// on ClusterArray<K> positions w and velocities y, interior entries only, where a holds
// the accelerations at (w, y) on entry (scratch after), and acceleration(x, v, a) sets
// a[1..K] to the blocks' accelerations at stage positions x and velocities v (x[0] and
// x[K+1] being the ends' positions), with every block's stick flag and direction of
// sliding frozen for the step. Returns false, having done
// nothing, for the friction laws the event engine refuses (cl89, none).
template <int K, bool FreeLeft, bool FreeRight, class Advance>
bool run_cluster_sized(const ChainForces& forces, ClusterRelaxation& r, Advance&& advance) {
  static_assert(K >= 1 && K <= kMaxCluster);
  return forces.with_switches([&]<class Law, class Terms>(const Law& law_in) {
    if constexpr (!Law::drives_events) {
      return false;
    } else {
      const Law law = law_in;  // a local, which the stores cannot change
      using Array = ClusterArray<K>;
      const Friction& fr = forces.friction();
      const double damper = forces.params().c_u / forces.params().m_u;
      ChainState& st = *r.state;
      double* w_all = st.w.data();
      const int lo = r.lo;
      // The entries that are blocks of the chain (the phantoms are not).
      constexpr int first = FreeLeft ? 1 : 0, last = FreeRight ? K : K + 1;
      const double anchor = r.anchor, dt = r.dt, half_dt_m = r.half_dt_m;
      const SubstrateState sub = r.sub;
      // Everything the loop carries lives in locals (written back once at the end), so the
      // stores into the state cannot force reloads; the sums are formed in the same order.
      Array w{}, y{}, mobile{}, dir{};
      for (int i = first; i <= last; ++i) {
        w[i] = w_all[lo + i];
        y[i] = st.wd[lo + i];
        mobile[i] = st.mobile[lo + i];
        dir[i] = st.dir[lo + i];
      }
      double t = st.t, dissipated = *r.dissipated, max_speed = r.max_speed;
      std::int64_t steps = 0, sliding_block_steps = 0;
      int sliding = 0, n_released = 0;
      // Each block's friction magnitude |phi(y)| at its current velocity: the power at the
      // end of one step needs it, and the first stage of the next step and the power at
      // its start need it again (the same value, so it is divided out once).
      const double magnitude_at_rest = law.magnitude(0.0);
      Array magnitude{};
      for (int i = first; i <= last; ++i) magnitude[i] = law.magnitude(y[i]);
      // A lone block slides throughout the run (it ends at the step where it sticks), and
      // 1 * acc is acc: the product is left out of its critical path.
      auto flagged = [&](int i, double acc) { return K == 1 ? acc : mobile[i] * acc; };
      // The phantom always goes in the left slot: k_c ((w - 2w) + w_n) rounds once, as
      // spring_force's k_c (0 + (w_n - w)) does; in the right slot (w_n - 2w) + w would
      // round twice.
      auto force = [&](const Array& x, int i) {
        if constexpr (FreeLeft) {
          if (i == 1) return forces.interior_force<Terms>(x[1], x[1], x[2], anchor);
        }
        if constexpr (FreeRight) {
          if (i == K) return forces.interior_force<Terms>(x[K], x[K], x[K - 1], anchor);
        }
        return forces.interior_force<Terms>(x[i - 1], x[i], x[i + 1], anchor);
      };
      auto acceleration = [&](const Array& x, const Array& v, Array& a) {
        for (int i = 1; i <= K; ++i)
          a[i] = flagged(
              i, forces.acceleration<Law, Terms, false>(law, force(x, i), v[i], dir[i], sub));
      };
      for (bool done = false; !done;) {
        const Array y0 = y, magnitude0 = magnitude;
        Array a;  // the first stage's accelerations, at the start of the step
        for (int i = 1; i <= K; ++i)
          a[i] = flagged(i, forces.acceleration_given<Law, Terms, false>(force(w, i), magnitude[i],
                                                                         y[i], dir[i], sub));
        advance(acceleration, w, y, a, dt);
        t += dt;
        ++steps;
        for (int i = 1; i <= K; ++i) w_all[lo + i] = w[i];  // the spring forces below read them

        // dissipated_power's sum, in the same order.
        RangePowerSum power;
        for (int i = first; i <= last; ++i) {
          magnitude[i] = law.magnitude(y[i]);
          power.add(i - first,
                    mobile[i] * step_power_given<Law::backslip>(magnitude0[i], y0[i], magnitude[i],
                                                                y[i], dir[i], damper));
        }
        dissipated += half_dt_m * power.total();

        // The stick rule (model/stick.hpp), block by block.
        sliding = 0;
        n_released = 0;
        for (int i = first; i <= last; ++i) {
          const int j = lo + i;
          const bool was_sliding = mobile[i] != 0.0;
          const stick::Outcome o = stick::settle_one(fr, true, mobile[i], dir[i], y0[i], y[i], [&] {
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
        sliding_block_steps += sliding;
        done = sliding == 0 || n_released > 0 || !std::isfinite(max_speed) || steps >= r.max_steps;
      }
      for (int i = first; i <= last; ++i) {
        st.wd[lo + i] = y[i];
        st.mobile[lo + i] = mobile[i];
        st.dir[lo + i] = dir[i];
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

// Free chain ends take this many blocks at most into a cluster (fewer instantiations).
inline constexpr int kMaxClusterAtEnd = 4;

// Calls run_cluster_sized with K = r.k and the free ends as compile-time constants;
// `advance` must accept the ClusterArray of every size. False if there is no such
// instantiation (a cluster at a chain end larger than kMaxClusterAtEnd).
template <class Advance>
bool run_cluster(const ChainForces& forces, ClusterRelaxation& r, Advance&& advance) {
  auto sized = [&]<bool FreeLeft, bool FreeRight, int Max>() {
    return [&]<int... Ks>(std::integer_sequence<int, Ks...>) {
      bool ran = false;
      ((r.k == Ks + 1 &&
        (ran = run_cluster_sized<Ks + 1, FreeLeft, FreeRight>(forces, r, advance), true)) ||
       ...);
      return ran;
    }
    (std::make_integer_sequence<int, Max>());
  };
  if (r.free_left && r.free_right) return false;
  if (r.free_left) return sized.template operator()<true, false, kMaxClusterAtEnd>();
  if (r.free_right) return sized.template operator()<false, true, kMaxClusterAtEnd>();
  return sized.template operator()<false, false, kMaxCluster>();
}

}  // namespace bkq
