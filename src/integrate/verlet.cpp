// Velocity Verlet with a velocity-corrected closing kick; see verlet.hpp.
#include "integrate/verlet.hpp"

#include "integrate/cluster.hpp"

namespace bkq {

void Verlet::step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                  Ranges ranges) {
  const ModelParams& p = forces.params();
  const bool pad = p.pad_moves();
  const bool velocity_dependent = p.law != FrictionLaw::None || p.c_u != 0 || (pad && p.c_p != 0);
  const double h = dt, h2 = 0.5 * dt;
  double* __restrict w = st.w.data();
  double* __restrict wd = st.wd.data();
  double* __restrict wh = wds_.data();    // half-step velocity
  double* __restrict wp = acc_v_.data();  // predicted end velocity
  double* __restrict a = a_.data();

  // Kick and drift: w(t+h) = w + h (w' + h/2 a).
  const double ax0 = evaluate(forces, sub.at(st.t), w, wd, st, st.x, st.xd, st.sum_w, ranges, a);
  double dsum = 0;
  for (const Range& r : ranges) {
    for (int j = r.lo; j < r.hi; ++j) {
      wh[j] = wd[j] + h2 * a[j];
      w[j] += h * wh[j];
    }
    if (pad)
      for (int j = r.lo; j < r.hi; ++j) dsum += h * wh[j];
  }
  const double xh = st.xd + h2 * ax0;
  if (pad) {
    st.x += h * xh;
    st.sum_w += dsum;
  }
  const SubstrateState end = sub.at(st.t + h);

  // Closing kick.
  double ax1 = evaluate(forces, end, w, wh, st, st.x, xh, st.sum_w, ranges, a);
  double xp = xh + h2 * ax1;
  if (velocity_dependent) {
    for (const Range& r : ranges)
      for (int j = r.lo; j < r.hi; ++j) wp[j] = wh[j] + h2 * a[j];
    ax1 = evaluate(forces, end, w, wp, st, st.x, xp, st.sum_w, ranges, a);
  }
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) wd[j] = wh[j] + h2 * a[j];
  if (pad) st.xd = xh + h2 * ax1;
  st.t += dt;
}

bool Verlet::relax_cluster(const ChainForces& forces, ClusterRelaxation& r) const {
  // step() for the cluster's interior blocks, operation for operation (the engine never
  // holds a moving pad here, and event-driven friction always depends on velocity, but
  // keep the test).
  const ModelParams& p = forces.params();
  const bool velocity_dependent = p.law != FrictionLaw::None || p.c_u != 0;
  return run_cluster(
      forces, r,
      [velocity_dependent](const auto& acceleration, auto& w, auto& wd, auto& a, double h) {
        constexpr int k =
            static_cast<int>(std::tuple_size_v<std::remove_reference_t<decltype(w)>>) - 2;
        const double h2 = 0.5 * h;
        auto wh = wd, wp = wd;
        for (int i = 1; i <= k; ++i) {
          wh[i] = wd[i] + h2 * a[i];
          w[i] += h * wh[i];
        }
        acceleration(w, wh, a);
        if (velocity_dependent) {
          for (int i = 1; i <= k; ++i) wp[i] = wh[i] + h2 * a[i];
          acceleration(w, wp, a);
        }
        for (int i = 1; i <= k; ++i) wd[i] = wh[i] + h2 * a[i];
      });
}

}  // namespace bkq
