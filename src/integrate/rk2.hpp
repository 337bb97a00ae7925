// Explicit midpoint rule (Ferre 2018 eq. 3.6), the thesis's baseline scheme.
//   y* = y + dt/2 f(y),  y_{n+1} = y + dt f(y*)
// Order 2 in smooth phases; two force evaluations per step. Stability: not A-stable on
// the imaginary axis: an undamped mode of frequency omega grows by
// sqrt(1 + (omega dt)^4/4) per step, i.e. by about exp(pi (omega dt)^3/4) per period. We
// accept omega_max dt <= 0.5, where the fastest undamped mode grows by about 10% per
// period (friction and dampers remove far more than that in every run we ship).
// Stick rule: Crossing (see stepper.hpp).
#pragma once

#include "integrate/explicit_scheme.hpp"

namespace bkq {

struct Rk2Method {
  static constexpr const char* name = "rk2";
  static constexpr int order = 2;
  static constexpr double stability_constant = 0.5;
  static constexpr bool fusable = false;
  using Round = Rounding<Plain, Plain>;

  template <class Layout>
  static void advance(Layout& l, double h) {
    const double h2 = 0.5 * h;
    // The pad's sum at the midpoint is taken in the second stage's pass, beside the sum
    // that stage adds (two chains of additions side by side cost the time of one).
    l.stage(
        at_state, 0.0,
        [h2](auto& e, double a) {
          e.xo = e.axpy(h2, e.v, e.w);
          e.yo = e.axpy(h2, a, e.v);
        },
        no_sum);
    l.stage(
        at_stage, h2,
        [h](auto& e, double a) {
          e.w = e.axpy(h, e.y, e.w);
          e.v = e.axpy(h, a, e.v);
        },
        sum_to_state(h, [](const auto& e) { return e.y; }),
        sum_to_stage(h2, [](const auto& e) { return e.v; }));
    l.finish(h);
  }
};

extern template class ExplicitScheme<Rk2Method>;
extern template bool relax_cluster<Rk2Method>(const ChainForces&, ClusterRelaxation&);
using Rk2 = ExplicitScheme<Rk2Method>;

}  // namespace bkq
