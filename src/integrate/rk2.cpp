// Explicit midpoint rule; see rk2.hpp.
#include "integrate/rk2.hpp"

namespace bkq {

void Rk2::step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt, Ranges ranges) {
  const bool pad = forces.params().pad_moves();
  const double h = dt, h2 = 0.5 * dt;
  double* __restrict w = st.w.data();
  double* __restrict wd = st.wd.data();
  double* __restrict ws = ws_.data();
  double* __restrict wds = wds_.data();
  double* __restrict a = a_.data();

  const double ax1 =
      evaluate(forces, sub.at(st.t), w, wd, st, st.x, st.xd, st.sum_w, ranges, a);
  double dsum = 0;
  for (const Range& r : ranges) {
    for (int j = r.lo; j < r.hi; ++j) {
      ws[j] = w[j] + h2 * wd[j];
      wds[j] = wd[j] + h2 * a[j];
    }
    if (pad)
      for (int j = r.lo; j < r.hi; ++j) dsum += wd[j];
  }
  const double xm = st.x + h2 * st.xd, xdm = st.xd + h2 * ax1;
  const double ax2 = evaluate(forces, sub.at(st.t + h2), ws, wds, st, xm, xdm,
                              st.sum_w + h2 * dsum, ranges, a);
  dsum = 0;
  for (const Range& r : ranges) {
    for (int j = r.lo; j < r.hi; ++j) {
      w[j] += h * wds[j];
      wd[j] += h * a[j];
    }
    if (pad)
      for (int j = r.lo; j < r.hi; ++j) dsum += wds[j];
  }
  if (pad) {
    st.x += h * xdm;
    st.xd += h * ax2;
    st.sum_w += h * dsum;
  }
  st.t += dt;
}

}  // namespace bkq
