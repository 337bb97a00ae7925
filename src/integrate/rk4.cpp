// Classical RK4 on (w, w', x, x'); see rk4.hpp. The stage sums of positions and
// velocities are accumulated in acc_w_/acc_v_ so each stage is one pass over the ranges.
#include "integrate/rk4.hpp"

#include "integrate/single_block.hpp"

namespace bkq {

void Rk4::step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt, Ranges ranges) {
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
      ws[j] = w[j] + h2 * wd[j];
      wds[j] = wd[j] + h2 * a[j];
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
        ws[j] = w[j] + c * wds[j];
        wds[j] = wd[j] + c * a[j];
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
      wd[j] += h6 * (cv[j] + a[j]);
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

void Rk4::step_held(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt, Ranges ranges) {
  forces.with_switches([&]<FrictionLaw Law, bool Neighbours, bool Damper>() {
    const SubstrateState frozen = sub.at(st.t);
    const double anchor = frozen.s + 0.0;  // as evaluate() forms it with the pad held
    const double h = dt, h2 = 0.5 * dt, h6 = h / 6.0;
    double* __restrict w = st.w.data();
    double* __restrict wd = st.wd.data();
    const double* __restrict mobile = st.mobile.data();
    const double* __restrict dir = st.dir.data();
    double* __restrict ws_a = ws_.data();
    double* __restrict wds_a = wds_.data();
    double* __restrict ws_b = ws2_.data();
    double* __restrict wds_b = wds2_.data();
    double* __restrict cw = acc_w_.data();
    double* __restrict cv = acc_v_.data();
    // The kernel's acceleration of block j at stage positions x and velocities v.
    auto acceleration = [&](const double* __restrict x, const double* __restrict v, int j) {
      return mobile[j] * forces.acceleration<Law, Damper, false>(
                             forces.interior_force<Neighbours>(x[j - 1], x[j], x[j + 1], anchor), v[j], dir[j],
                             frozen);
    };
    for (const Range& r : ranges) {
      const int lo = r.lo + 1, hi = r.hi - 1;  // the end blocks are stuck: their stage positions are w
      ws_a[r.lo] = ws_b[r.lo] = w[r.lo];
      ws_a[hi] = ws_b[hi] = w[hi];
      for (int j = lo; j < hi; ++j) {
        const double a = acceleration(w, wd, j);
        cw[j] = wd[j];
        cv[j] = a;
        ws_a[j] = w[j] + h2 * wd[j];
        wds_a[j] = wd[j] + h2 * a;
      }
      for (int j = lo; j < hi; ++j) {
        const double a = acceleration(ws_a, wds_a, j);
        cw[j] += 2.0 * wds_a[j];
        cv[j] += 2.0 * a;
        ws_b[j] = w[j] + h2 * wds_a[j];
        wds_b[j] = wd[j] + h2 * a;
      }
      for (int j = lo; j < hi; ++j) {
        const double a = acceleration(ws_b, wds_b, j);
        cw[j] += 2.0 * wds_b[j];
        cv[j] += 2.0 * a;
        ws_a[j] = w[j] + h * wds_b[j];
        wds_a[j] = wd[j] + h * a;
      }
      for (int j = lo; j < hi; ++j) {
        const double a = acceleration(ws_a, wds_a, j);
        const double dw = h6 * (cw[j] + wds_a[j]);
        w[j] += dw;
        wd[j] += h6 * (cv[j] + a);
      }
    }
  });
  st.t += dt;
}

bool Rk4::relax_single_block(const ChainForces& forces, SingleBlockRelaxation& r) const {
  // step() for one block, operation for operation (cw, cv are its stage sums).
  run_single_block(forces, r, [](const auto& acceleration, double& w, double& wd, double h) {
    const double h2 = 0.5 * h, h6 = h / 6.0;
    double a = acceleration(w, wd);
    double cw = wd, cv = a, ws = w + h2 * wd, wds = wd + h2 * a;
    for (int stage = 2; stage <= 3; ++stage) {
      const double c = stage == 2 ? h2 : h;
      a = acceleration(ws, wds);
      cw += 2.0 * wds;
      cv += 2.0 * a;
      ws = w + c * wds;
      wds = wd + c * a;
    }
    a = acceleration(ws, wds);
    const double dw = h6 * (cw + wds);
    w += dw;
    wd += h6 * (cv + a);
  });
  return true;
}

}  // namespace bkq
