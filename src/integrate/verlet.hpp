// Velocity Verlet (kick–drift–kick). For position-dependent forces it is the symplectic
// second-order scheme: two force evaluations per step here (the acceleration at the
// start is recomputed rather than cached, since stick transitions change it). Friction
// and dampers depend on velocity, so when the scene has any the closing kick is taken
// with the trapezoidal rule on a predicted end velocity (one more evaluation), which keeps
// the scheme second order. Stability: omega_max dt < 2 for undamped modes; we accept
// omega_max dt <= 2. Stick rule: Crossing (see stepper.hpp).
#pragma once

#include "integrate/stepper.hpp"

namespace bkq {

class Verlet final : public ExplicitStepper {
 public:
  explicit Verlet(int n) : ExplicitStepper(n) {}
  std::string_view name() const override { return "verlet"; }
  int order() const override { return 2; }
  double stability_constant() const override { return 2.0; }
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override;
  bool relax_cluster(const ChainForces& forces, ClusterRelaxation& r) const override;
};

}  // namespace bkq
