// Explicit midpoint rule (thesis eq. 3.6), the thesis's baseline scheme.
//   y* = y + dt/2 f(y),  y_{n+1} = y + dt f(y*)
// Order 2 in smooth phases; two force evaluations per step. Stability: not A-stable on
// the imaginary axis — an undamped mode of frequency omega grows by
// sqrt(1 + (omega dt)^4/4) per step, i.e. by about exp(pi (omega dt)^3/4) per period. We
// accept omega_max dt <= 0.5, where the fastest undamped mode grows by about 10% per period
// (friction and dampers remove far more than that in every run we ship).
// Stick rule: Crossing (see stepper.hpp).
#pragma once

#include "integrate/stepper.hpp"

namespace bkq {

class Rk2 final : public ExplicitStepper {
 public:
  explicit Rk2(int n) : ExplicitStepper(n) {}
  std::string_view name() const override { return "rk2"; }
  int order() const override { return 2; }
  double stability_constant() const override { return 0.5; }
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override;
  bool relax_cluster(const ChainForces& forces, ClusterRelaxation& r) const override;
};

}  // namespace bkq
