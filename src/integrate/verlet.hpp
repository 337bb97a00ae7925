// Velocity Verlet (kick–drift–kick). For position-dependent forces it is the symplectic
// second-order scheme: two force evaluations per step here (the acceleration at the
// start is recomputed rather than cached, since stick transitions change it). Friction
// and dampers depend on velocity, so when the scene has any the closing kick is taken
// with the trapezoidal rule on a predicted end velocity (one more evaluation), which keeps
// the scheme second order. Stability: omega_max dt < 2 for undamped modes; we accept
// omega_max dt <= 2. Stick rule: Crossing (see stepper.hpp).
#pragma once

#include "integrate/explicit_scheme.hpp"

namespace bkq {

struct VerletMethod {
  static constexpr const char* name = "verlet";
  static constexpr int order = 2;
  static constexpr double stability_constant = 2.0;
  static constexpr bool fusable = false;  // the first stage moves the positions it reads
  using Round = Rounding<Plain, Plain>;

  template <class Layout>
  static void advance(Layout& l, double h) {
    const double h2 = 0.5 * h;
    // Kick and drift: y = v + h/2 a (the half-step velocity), w += h y.
    l.stage(
        at_state, 0.0,
        [h, h2](auto& e, double a) {
          e.yo = e.axpy(h2, a, e.v);
          e.w = e.axpy(h, e.yo, e.w);
        },
        sum_to_state(1.0, [h](const auto& e) { return h * e.y; }));
    // Closing kick v = y + h/2 a, with a at a predicted end velocity u when it matters.
    auto kick = [h2](auto& e, double a) { e.v = e.axpy(h2, a, e.y); };
    if (l.velocity_dependent()) {
      l.stage(
          at_state_positions, h, [h2](auto& e, double a) { e.u = e.axpy(h2, a, e.y); }, no_sum);
      l.stage(at_state_positions_spare, h, kick, no_sum);
    } else {
      l.stage(at_state_positions, h, kick, no_sum);
    }
    l.finish(h);
  }
};

extern template class ExplicitScheme<VerletMethod>;
extern template bool relax_cluster<VerletMethod>(const ChainForces&, ClusterRelaxation&);
using Verlet = ExplicitScheme<VerletMethod>;

}  // namespace bkq
