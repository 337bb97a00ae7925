// Classical fourth-order Runge–Kutta. Order 4 in smooth phases; four force evaluations
// per step. Stability: its region crosses the imaginary axis at |omega dt| = 2 sqrt(2);
// we accept omega_max dt <= 2.8. With Rayleigh damping a mode of damping ratio 1/2 is
// stable only up to max(omega, c) dt = 2.62 (the least over all ratios; the real axis
// ends at 2.785): we accept 2.6 there. Stick rule: Crossing (see stepper.hpp).
//
// The blocks' stage updates w + c v are fused multiply-adds (one rounding): in the event
// engine's one-block case the stages are a chain of dependent operations whose length
// sets the speed. The pad keeps two roundings. Its stages allow fusing (explicit_scheme.hpp).
#pragma once

#include "integrate/explicit_scheme.hpp"

namespace bkq {

struct Rk4Method {
  static constexpr const char* name = "rk4";
  static constexpr int order = 4;
  static constexpr double stability_constant = 2.8;
  static constexpr double damped_stability_constant = 2.6;
  static constexpr bool fusable = true;
  using Round = Rounding<Fused, Plain>;

  template <class Layout>
  static void advance(Layout& l, double h) {
    const double h2 = 0.5 * h, h6 = h / 6.0;
    // cw, cv gather the stage velocities and accelerations with weights 1, 2, 2, 1.
    auto first = [h2](auto& e, double a) {
      e.cw = e.v;
      e.cv = a;
      e.xo = e.axpy(h2, e.v, e.w);
      e.yo = e.axpy(h2, a, e.v);
    };
    auto middle = [](double c) {
      return [c](auto& e, double a) {
        e.cw += 2.0 * e.y;
        e.cv += 2.0 * a;
        e.xo = e.axpy(c, e.y, e.w);
        e.yo = e.axpy(c, a, e.v);
      };
    };
    auto last = [h6](auto& e, double a) {
      e.w += h6 * (e.cw + e.y);
      e.v = e.axpy(h6, e.cv + a, e.v);
    };
    // The pad's sums go in pairs into the second and fourth passes (a sum in block order is
    // a chain of dependent additions; two side by side cost the time of one): each stage
    // point's sum is taken in the pass that evaluates at that point, before the update,
    // beside the sum of the point that pass makes, after it.
    const auto moved = [](const auto& e) { return e.xo - e.w; };
    l.stage(at_state, 0.0, first, no_sum);
    l.stage(at_stage, h2, middle(h2), sum_to_stage(1.0, moved),
            sum_to_stage(h2, [](const auto& e) { return e.v; }));
    l.stage(at_stage, h2, middle(h), no_sum);
    l.stage(at_stage, h, last, sum_to_state(1.0, [h6](const auto& e) { return h6 * (e.cw + e.y); }),
            sum_to_stage(1.0, [](const auto& e) { return e.x - e.w; }));
    l.finish(h);
  }
};

extern template class ExplicitScheme<Rk4Method>;
extern template bool relax_cluster<Rk4Method>(const ChainForces&, ClusterRelaxation&);
using Rk4 = ExplicitScheme<Rk4Method>;

}  // namespace bkq
