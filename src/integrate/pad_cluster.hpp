// The cluster path (integrate/cluster.hpp) with the pad moving: a few blocks sliding
// between two stuck ones, held in registers, and the pad advanced alongside them as one
// more element of the scheme's stages, exactly as ChainLayout advances it (the anchor at
// each stage is the substrate plus the pad's stage position; the pad's acceleration reads
// the stage's sum of block positions, formed from the cluster's terms in block order).
// After each step it does what the event engine's general path does, in the same order:
// the blocks' dissipated power, the stick rule at the new anchor, the pad damper's work,
// and the test whether the pad's swing broke a far stuck block (the force tree's extremes,
// constant while the cluster runs); it returns after the first step at which any of
// these ends the cluster's run (cluster.hpp's conditions, or a far block breaking).
// The stuck end blocks add exactly zero to every sum, so they are left out. The events
// are the general path's bit for bit (tests/regression/test_pad_paths.cpp).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "integrate/cluster.hpp"
#include "integrate/layouts.hpp"
#include "integrate/scheme.hpp"

namespace bkq {

struct PadClusterRelaxation : ClusterRelaxation {
  // Set by the caller besides ClusterRelaxation's fields (whose `anchor` is not read: the
  // pad's position is in the state): the force tree's largest and smallest anchor-free
  // force g over the uncovered stuck blocks, and the pad damper's trapezoidal weight.
  double far_max = -HUGE_VAL, far_min = HUGE_VAL;
  double half_dt_cp = 0;
  // What happened besides: the last step's pad swing broke a far block.
  bool far_break = false;
};

// The pad's state while a cluster runs (written back at the end).
struct PadStageState {
  double x, xd, sum_w;
};

// The interior entries of a cluster and the pad, for a Method's advance() (as
// ClusterLayout, plus the pad element and its sums, as ChainLayout forms them).
template <class Round, class Acceleration, class Array>
class PadClusterLayout {
 public:
  static constexpr int K = static_cast<int>(std::tuple_size_v<Array>) - 2;

  PadClusterLayout(const ChainForces& forces, double s, const Acceleration& acceleration, Array& w,
                   Array& v, Array& a, PadStageState& pad)
      : forces_(forces),
        s_(s),
        acceleration_(acceleration),
        w_(w),
        v_(v),
        a_(a),
        x_(w),
        y_(v),
        cw_(w),
        cv_(w),
        u_(v),
        pad_(pad) {}

  bool velocity_dependent() const { return bkq::velocity_dependent(forces_.params(), true); }

  template <class Point, class Update, class Sum>
  void stage(Point p, double time_offset, Update&& update, const Sum& sum) {
    stage(p, time_offset, update, sum, no_sum);
  }
  template <class Point, class Update, class Sum, class Earlier>
  void stage(Point, double, Update&& update, const Sum& sum, const Earlier& earlier) {
    constexpr bool state_positions = Point::positions == Buf::W;
    constexpr bool at_state = state_positions && Point::velocities == Buf::V;
    constexpr bool joint = !std::is_same_v<Earlier, NoSum>;
    constexpr bool summed = !std::is_same_v<Sum, NoSum>;
    const double x_at = state_positions ? pad_.x : x_pad_;
    const double xd_at = pick<Point::velocities>(pad_.xd, xd_, xu_);
    if (!at_state || evaluated_)
      acceleration_(state_positions ? w_ : x_, pick<Point::velocities>(v_, y_, u_), s_ + x_at, a_);
    evaluated_ = true;
    auto pad_acceleration = [&] {
      return forces_.pad_acceleration(x_at, xd_at, state_positions ? pad_.sum_w : sum_, s_);
    };
    double ax = joint ? 0.0 : pad_acceleration();
    auto element = [&](int i) {
      return StageElement<typename Round::BlockRound>{w_[i], v_[i],  x_[i],  y_[i], x_[i],
                                                      y_[i], cw_[i], cv_[i], u_[i]};
    };
    double total = 0, earlier_total = 0;
    // ChainLayout's order: `earlier`'s terms before the update, `sum`'s after it.
    if constexpr (joint) {
      for (int i = 1; i <= K; ++i) earlier_total += earlier.term(element(i));
    }
    for (int i = 1; i <= K; ++i) {
      auto e = element(i);
      update(e, a_[i]);
    }
    if constexpr (summed) {
      for (int i = 1; i <= K; ++i) total += sum.term(element(i));
    }
    if constexpr (joint) {
      sum_ = pad_.sum_w + earlier.scale * earlier_total;
      ax = pad_acceleration();
    }
    StageElement<typename Round::PadRound> e{pad_.x, pad_.xd, x_pad_, xd_, x_pad_,
                                             xd_,    cx_,     cxd_,   xu_};
    update(e, ax);
    if constexpr (summed) {
      if (sum.into_state)
        pad_.sum_w += sum.scale * total;
      else
        sum_ = pad_.sum_w + sum.scale * total;
    }
  }
  void finish(double) {}

 private:
  template <Buf B, class T>
  static T& pick(T& v, T& y, T& u) {
    if constexpr (B == Buf::V)
      return v;
    else if constexpr (B == Buf::Y)
      return y;
    else
      return u;
  }

  const ChainForces& forces_;
  double s_;
  const Acceleration& acceleration_;
  Array &w_, &v_, &a_;
  Array x_, y_, cw_, cv_, u_;
  PadStageState& pad_;
  double x_pad_ = 0, xd_ = 0, cx_ = 0, cxd_ = 0, xu_ = 0, sum_ = 0;
  bool evaluated_ = false;
};

// run_cluster_sized's loop with the pad (see the top of this file).
template <class Method, int K, bool FreeLeft, bool FreeRight>
bool run_pad_cluster_sized(const ChainForces& forces, PadClusterRelaxation& r) {
  static_assert(K >= 1 && K <= kMaxCluster);
  return forces.with_switches([&]<class Law, class Terms>(const Law& law_in) {
    if constexpr (!Law::drives_events) {
      return false;
    } else {
      const Law law = law_in;
      using Array = ClusterArray<K>;
      const Friction& fr = forces.friction();
      const ModelParams& p = forces.params();
      const double damper = p.c_u / p.m_u, kp = p.k_p;
      ChainState& st = *r.state;
      double* w_all = st.w.data();
      const int lo = r.lo;
      constexpr int first = FreeLeft ? 1 : 0, last = FreeRight ? K : K + 1;
      const double dt = r.dt, half_dt_m = r.half_dt_m, half_dt_cp = r.half_dt_cp;
      const double far_max = r.far_max, far_min = r.far_min;
      const SubstrateState sub = r.sub;
      const double s = sub.s;
      Array w{}, y{}, mobile{}, dir{};
      for (int i = first; i <= last; ++i) {
        w[i] = w_all[lo + i];
        y[i] = st.wd[lo + i];
        mobile[i] = st.mobile[lo + i];
        dir[i] = st.dir[lo + i];
      }
      PadStageState pad{st.x, st.xd, st.sum_w};
      double t = st.t, dissipated = *r.dissipated, max_speed = r.max_speed;
      std::int64_t steps = 0, sliding_block_steps = 0;
      int sliding = 0, n_released = 0;
      bool far_break = false;
      const double magnitude_at_rest = law.magnitude(0.0);
      Array magnitude{};
      for (int i = first; i <= last; ++i) magnitude[i] = law.magnitude(y[i]);
      auto flagged = [&](int i, double acc) { return K == 1 ? acc : mobile[i] * acc; };
      auto force = [&](const Array& x, int i, double anchor) {
        if constexpr (FreeLeft) {
          if (i == 1) return forces.interior_force<Terms>(x[1], x[1], x[2], anchor);
        }
        if constexpr (FreeRight) {
          if (i == K) return forces.interior_force<Terms>(x[K], x[K], x[K - 1], anchor);
        }
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
        const double anchor0 = s + pad.x;
        Array a;
        for (int i = 1; i <= K; ++i)
          a[i] = flagged(i, forces.acceleration_given<Law, Terms, false>(
                                force(w, i, anchor0), magnitude[i], y[i], dir[i], sub));
        {
          PadClusterLayout<typename Method::Round, decltype(acceleration), Array> layout(
              forces, s, acceleration, w, y, a, pad);
          Method::advance(layout, dt);
        }
        t += dt;
        ++steps;
        for (int i = 1; i <= K; ++i) w_all[lo + i] = w[i];

        RangePowerSum power;
        for (int i = first; i <= last; ++i) {
          magnitude[i] = law.magnitude(y[i]);
          power.add(i - first,
                    mobile[i] * step_power_given<Law::backslip>(magnitude0[i], y0[i], magnitude[i],
                                                                y[i], dir[i], damper));
        }
        dissipated += half_dt_m * power.total();

        const double anchor = s + pad.x;
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
            if (o.y == 0.0) magnitude[i] = magnitude_at_rest;
            ++sliding;
            raise_max_speed(max_speed, std::abs(o.y));
          } else if (o.breaks) {
            ++sliding;
            r.released[n_released++] = j;
          } else if (was_sliding) {
            magnitude[i] = magnitude_at_rest;
          }
        }
        dissipated += half_dt_cp * (xd_old * xd_old + pad.xd * pad.xd);
        sliding_block_steps += sliding;
        // query_tree_failures' test, with the anchor formed as anchor() forms it.
        far_break = far_max + kp * anchor > fr.threshold ||
                    (fr.backslip && far_min + kp * anchor < -fr.threshold);
        done = sliding == 0 || n_released > 0 || far_break || !std::isfinite(max_speed) ||
               steps >= r.max_steps;
      }
      for (int i = first; i <= last; ++i) {
        st.wd[lo + i] = y[i];
        st.mobile[lo + i] = mobile[i];
        st.dir[lo + i] = dir[i];
      }
      st.x = pad.x;
      st.xd = pad.xd;
      st.sum_w = pad.sum_w;
      st.t = t;
      *r.dissipated = dissipated;
      r.max_speed = max_speed;
      r.steps = steps;
      r.sliding_block_steps = sliding_block_steps;
      r.sliding = sliding;
      r.n_released = n_released;
      r.far_break = far_break;
      return true;
    }
  });
}

// run_cluster's dispatch on the cluster's size and free ends, for run_pad_cluster_sized.
template <class Method>
bool run_pad_cluster(const ChainForces& forces, PadClusterRelaxation& r) {
  auto sized = [&]<bool FreeLeft, bool FreeRight, int Max>() {
    return [&]<int... Ks>(std::integer_sequence<int, Ks...>) {
      bool ran = false;
      ((r.k == Ks + 1 &&
        (ran = run_pad_cluster_sized<Method, Ks + 1, FreeLeft, FreeRight>(forces, r), true)) ||
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
