// Classical fourth-order Runge–Kutta. Order 4 in smooth phases; four force evaluations
// per step. Stability: its region crosses the imaginary axis at |omega dt| = 2 sqrt(2);
// we accept omega_max dt <= 2.8. Stick rule: Crossing (see stepper.hpp).
#pragma once

#include "integrate/stepper.hpp"

namespace bkq {

class Rk4 final : public ExplicitStepper {
 public:
  explicit Rk4(int n) : ExplicitStepper(n) {}
  std::string_view name() const override { return "rk4"; }
  int order() const override { return 4; }
  double stability_constant() const override { return 2.8; }
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt, Ranges ranges) override;
  bool relax_single_block(const ChainForces& forces, SingleBlockRelaxation& r) const override;
};

}  // namespace bkq
