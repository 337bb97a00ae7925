// Classical fourth-order Runge–Kutta. Order 4 in smooth phases; four force evaluations
// per step. Stability: its region crosses the imaginary axis at |omega dt| = 2 sqrt(2);
// we accept omega_max dt <= 2.8. Stick rule: Crossing (see stepper.hpp).
#pragma once

#include <vector>

#include "integrate/stepper.hpp"

namespace bkq {

class Rk4 final : public ExplicitStepper {
 public:
  explicit Rk4(int n) : ExplicitStepper(n) {}
  std::string_view name() const override { return "rk4"; }
  int order() const override { return 4; }
  double stability_constant() const override { return 2.8; }
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override;
  // One pass per stage over each range: forces, accelerations and stage sums together,
  // with the stage positions and velocities double-buffered.
  void step_held(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                 Ranges ranges) override;
  bool relax_cluster(const ChainForces& forces, ClusterRelaxation& r) const override;

 private:
  std::vector<double> ws2_ = std::vector<double>(ws_.size()),
                      wds2_ = std::vector<double>(ws_.size());
};

}  // namespace bkq
