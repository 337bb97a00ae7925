// Classical RK4 on (w, w', x, x'); see rk4.hpp. The stage sums of positions and
// velocities are accumulated in acc_w_/acc_v_ so each stage is one pass over the ranges.
// The blocks' stage updates w + c v are written as std::fma: one rounding, and in the
// event engine's one-block case the stages are a chain of dependent operations whose
// length sets the speed. Every form of the step (step, step_held, the cluster form) uses
// the same operations, so they agree bit for bit.
#include "integrate/rk4.hpp"

#include <cmath>

#include "integrate/cluster.hpp"

namespace bkq {

void Rk4::step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
               Ranges ranges) {
  const bool pad = forces.params().pad_moves();
  const double h = dt, h2 = 0.5 * dt;
  double* __restrict w = st.w.data();
  double* __restrict wd = st.wd.data();
  double* __restrict ws = ws_.data();
  double* __restrict wds = wds_.data();
  double* __restrict a = a_.data();
  double* __restrict cw = acc_w_.data();
  double* __restrict cv = acc_v_.data();

  // Stage 1 at (w, w').
  double ax = evaluate(forces, sub.at(st.t), w, wd, st, st.x, st.xd, st.sum_w, ranges, a);
  double dsum = 0;
  for (const Range& r : ranges) {
    for (int j = r.lo; j < r.hi; ++j) {
      cw[j] = wd[j];
      cv[j] = a[j];
      ws[j] = std::fma(h2, wd[j], w[j]);
      wds[j] = std::fma(h2, a[j], wd[j]);
    }
    if (pad)
      for (int j = r.lo; j < r.hi; ++j) dsum += wd[j];
  }
  double cx = st.xd, cxd = ax;
  double xs = st.x + h2 * st.xd, xds = st.xd + h2 * ax, sum_s = st.sum_w + h2 * dsum;

  // Stages 2 and 3 at the midpoint; their weights are 2.
  for (int stage = 2; stage <= 3; ++stage) {
    const double c = stage == 2 ? h2 : h;
    ax = evaluate(forces, sub.at(st.t + h2), ws, wds, st, xs, xds, sum_s, ranges, a);
    dsum = 0;
    for (const Range& r : ranges) {
      for (int j = r.lo; j < r.hi; ++j) {
        cw[j] += 2.0 * wds[j];
        cv[j] += 2.0 * a[j];
        ws[j] = std::fma(c, wds[j], w[j]);
        wds[j] = std::fma(c, a[j], wd[j]);
      }
      if (pad)
        for (int j = r.lo; j < r.hi; ++j) dsum += ws[j] - w[j];
    }
    cx += 2.0 * xds;
    cxd += 2.0 * ax;
    xs = st.x + c * xds;
    xds = st.xd + c * ax;
    sum_s = st.sum_w + dsum;
  }

  // Stage 4 at the end of the step.
  ax = evaluate(forces, sub.at(st.t + h), ws, wds, st, xs, xds, sum_s, ranges, a);
  const double h6 = h / 6.0;
  dsum = 0;
  for (const Range& r : ranges) {
    for (int j = r.lo; j < r.hi; ++j) {
      const double dw = h6 * (cw[j] + wds[j]);
      w[j] += dw;
      wd[j] = std::fma(h6, cv[j] + a[j], wd[j]);
    }
    if (pad)
      for (int j = r.lo; j < r.hi; ++j) dsum += h6 * (cw[j] + wds[j]);
  }
  if (pad) {
    st.x += h6 * (cx + xds);
    st.xd += h6 * (cxd + ax);
    st.sum_w += dsum;
  }
  st.t += dt;
}

namespace {

// The blocks held_stage() advances and what it reads: everything is a restrict parameter,
// so the compiler knows the stores cannot change the model and vectorises the loop.
struct HeldStage {
  const double* mobile;
  const double* dir;
  double anchor;
  SubstrateState frozen;
};

// One RK4 stage over the inner blocks [lo, hi) of a range with stuck ends, fused: the
// kernel's acceleration at stage positions x and velocities v, then (first stage) the
// stage sums cw, cv start, or (middle stages) they gain 2 x the stage, and the next
// stage's positions and velocities w + c v, w' + c a go to x_out, v_out.
template <FrictionLaw Law, bool Neighbours, bool Damper, bool First>
void held_stage(const ChainForces& forces, const HeldStage& in, int lo, int hi,
                const double* __restrict w, const double* __restrict wd, const double* __restrict x,
                const double* __restrict v, double c, double* __restrict cw, double* __restrict cv,
                double* __restrict x_out, double* __restrict v_out) {
  const double* __restrict mobile = in.mobile;
  const double* __restrict dir = in.dir;
  const double anchor = in.anchor;
  const SubstrateState frozen = in.frozen;
  for (int j = lo; j < hi; ++j) {
    const double a =
        mobile[j] * forces.acceleration<Law, Damper, false>(
                        forces.interior_force<Neighbours>(x[j - 1], x[j], x[j + 1], anchor), v[j],
                        dir[j], frozen);
    if constexpr (First) {
      cw[j] = v[j];
      cv[j] = a;
    } else {
      cw[j] += 2.0 * v[j];
      cv[j] += 2.0 * a;
    }
    x_out[j] = std::fma(c, v[j], w[j]);
    v_out[j] = std::fma(c, a, wd[j]);
  }
}

// The last stage: w += h/6 (cw + v), w' += h/6 (cv + a).
template <FrictionLaw Law, bool Neighbours, bool Damper>
void held_last_stage(const ChainForces& forces, const HeldStage& in, int lo, int hi,
                     double* __restrict w, double* __restrict wd, const double* __restrict x,
                     const double* __restrict v, double h6, const double* __restrict cw,
                     const double* __restrict cv) {
  const double* __restrict mobile = in.mobile;
  const double* __restrict dir = in.dir;
  const double anchor = in.anchor;
  const SubstrateState frozen = in.frozen;
  for (int j = lo; j < hi; ++j) {
    const double a =
        mobile[j] * forces.acceleration<Law, Damper, false>(
                        forces.interior_force<Neighbours>(x[j - 1], x[j], x[j + 1], anchor), v[j],
                        dir[j], frozen);
    const double dw = h6 * (cw[j] + v[j]);
    w[j] += dw;
    wd[j] = std::fma(h6, cv[j] + a, wd[j]);
  }
}

}  // namespace

void Rk4::step_held(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                    Ranges ranges) {
  // The stage positions and velocities alternate between (ws_, wds_) and (ws2_, wds2_).
  const SubstrateState frozen = sub.at(st.t);
  const HeldStage in{st.mobile.data(), st.dir.data(), frozen.s + 0.0 /* as evaluate() forms it */,
                     frozen};
  const double h = dt, h2 = 0.5 * dt, h6 = h / 6.0;
  double* w = st.w.data();
  double* wd = st.wd.data();
  double *xa = ws_.data(), *va = wds_.data(), *xb = ws2_.data(), *vb = wds2_.data();
  double *cw = acc_w_.data(), *cv = acc_v_.data();
  forces.with_switches([&]<FrictionLaw Law, bool Neighbours, bool Damper>() {
    for (const Range& r : ranges) {
      const int lo = r.lo + 1,
                hi = r.hi - 1;  // the end blocks are stuck: their stage positions are w
      xa[r.lo] = xb[r.lo] = w[r.lo];
      xa[hi] = xb[hi] = w[hi];
      held_stage<Law, Neighbours, Damper, true>(forces, in, lo, hi, w, wd, w, wd, h2, cw, cv, xa,
                                                va);
      held_stage<Law, Neighbours, Damper, false>(forces, in, lo, hi, w, wd, xa, va, h2, cw, cv, xb,
                                                 vb);
      held_stage<Law, Neighbours, Damper, false>(forces, in, lo, hi, w, wd, xb, vb, h, cw, cv, xa,
                                                 va);
      held_last_stage<Law, Neighbours, Damper>(forces, in, lo, hi, w, wd, xa, va, h6, cw, cv);
    }
  });
  st.t += dt;
}

bool Rk4::relax_cluster(const ChainForces& forces, ClusterRelaxation& r) const {
  // step_held() for the cluster's interior blocks, operation for operation (cw, cv are
  // the stage sums; the ends' stage positions are their positions).
  return run_cluster(forces, r, [](const auto& acceleration, auto& w, auto& wd, auto& a, double h) {
    constexpr int k = static_cast<int>(std::tuple_size_v<std::remove_reference_t<decltype(w)>>) - 2;
    const double h2 = 0.5 * h, h6 = h / 6.0;
    auto cw = w, cv = w, ws = w, wds = wd;
    for (int i = 1; i <= k; ++i) {
      cw[i] = wd[i];
      cv[i] = a[i];
      ws[i] = std::fma(h2, wd[i], w[i]);
      wds[i] = std::fma(h2, a[i], wd[i]);
    }
    for (int stage = 2; stage <= 3; ++stage) {
      const double c = stage == 2 ? h2 : h;
      acceleration(ws, wds, a);
      for (int i = 1; i <= k; ++i) {
        cw[i] += 2.0 * wds[i];
        cv[i] += 2.0 * a[i];
        ws[i] = std::fma(c, wds[i], w[i]);
        wds[i] = std::fma(c, a[i], wd[i]);
      }
    }
    acceleration(ws, wds, a);
    for (int i = 1; i <= k; ++i) {
      const double dw = h6 * (cw[i] + wds[i]);
      w[i] += dw;
      wd[i] = std::fma(h6, cv[i] + a[i], wd[i]);
    }
  });
}

}  // namespace bkq
