// Explicit midpoint rule; see rk2.hpp.
#include "integrate/rk2.hpp"

#include "integrate/cluster.hpp"

namespace bkq {

void Rk2::step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
               Ranges ranges) {
  const bool pad = forces.params().pad_moves();
  const double h = dt, h2 = 0.5 * dt;
  double* __restrict w = st.w.data();
  double* __restrict wd = st.wd.data();
  double* __restrict ws = ws_.data();
  double* __restrict wds = wds_.data();
  double* __restrict a = a_.data();

  const double ax1 = evaluate(forces, sub.at(st.t), w, wd, st, st.x, st.xd, st.sum_w, ranges, a);
  for (const Range& r : ranges) {
    for (int j = r.lo; j < r.hi; ++j) {
      ws[j] = w[j] + h2 * wd[j];
      wds[j] = wd[j] + h2 * a[j];
    }
  }
  const double xm = st.x + h2 * st.xd, xdm = st.xd + h2 * ax1;
  const SubstrateState sub_m = sub.at(st.t + h2);
  forces.block_accelerations(ws, wds, st.mobile.data(), st.dir.data(), sub_m.s + (pad ? xm : 0.0),
                             sub_m, ranges, a);
  // The pad needs the sums of the block velocities at both stages (for its acceleration at
  // the midpoint and for sum_w). Each sum, taken in block order, is a chain of dependent
  // additions whose speed is set by the latency of one addition; two chains side by side
  // in one loop cost the time of one. Hence both are taken here, after the stage-2 forces
  // (which do not depend on them), and the pad's stage-2 acceleration after that.
  double dsum0 = 0, dsum = 0;
  for (const Range& r : ranges) {
    if (pad)
      for (int j = r.lo; j < r.hi; ++j) {
        dsum0 += wd[j];
        dsum += wds[j];
      }
    for (int j = r.lo; j < r.hi; ++j) {
      w[j] += h * wds[j];
      wd[j] += h * a[j];
    }
  }
  if (pad) {
    const double ax2 = forces.pad_acceleration(xm, xdm, st.sum_w + h2 * dsum0, sub_m.s);
    st.x += h * xdm;
    st.xd += h * ax2;
    st.sum_w += h * dsum;
  }
  st.t += dt;
}

bool Rk2::relax_cluster(const ChainForces& forces, ClusterRelaxation& r) const {
  // step() for the cluster's interior blocks, operation for operation.
  return run_cluster(forces, r, [](const auto& acceleration, auto& w, auto& wd, auto& a, double h) {
    constexpr int k = static_cast<int>(std::tuple_size_v<std::remove_reference_t<decltype(w)>>) - 2;
    const double h2 = 0.5 * h;
    auto ws = w, wds = wd;
    for (int i = 1; i <= k; ++i) {
      ws[i] = w[i] + h2 * wd[i];
      wds[i] = wd[i] + h2 * a[i];
    }
    acceleration(ws, wds, a);
    for (int i = 1; i <= k; ++i) {
      w[i] += h * wds[i];
      wd[i] += h * a[i];
    }
  });
}

}  // namespace bkq
