// integrator.scheme keyword -> stepper type, and the time-step stability check.
#include <cstdio>

#include "core/error.hpp"
#include "integrate/adaptive.hpp"
#include "integrate/rk2.hpp"
#include "integrate/rk4.hpp"
#include "integrate/stepper.hpp"
#include "integrate/theta.hpp"
#include "integrate/verlet.hpp"

namespace bkq {

void ExplicitStepper::resize(int n) {
  for (auto* v : {&ws_, &wds_, &a_, &acc_w_, &acc_v_}) v->assign(n, 0.0);
}

const std::vector<std::string>& stepper_keywords() {
  static const std::vector<std::string> k{"rk2", "rk4", "verlet", "theta", "adaptive"};
  return k;
}

std::unique_ptr<Stepper> make_stepper(const std::string& scheme, int n, double tolerance) {
  if (scheme == "rk2") return std::make_unique<Rk2>(n);
  if (scheme == "rk4") return std::make_unique<Rk4>(n);
  if (scheme == "verlet") return std::make_unique<Verlet>(n);
  if (scheme == "theta") return std::make_unique<Theta>(n);
  if (scheme == "adaptive") return std::make_unique<Adaptive>(n, tolerance);
  std::string valid;
  for (const auto& k : stepper_keywords()) valid += (valid.empty() ? "" : "|") + k;
  throw Error("integrator.scheme: '" + scheme + "' is not available; expected one of " + valid);
}

Stepper::TimeStepLimit Stepper::time_step_limit(const ModelParams& p) const {
  char why[200];
  std::snprintf(why, sizeof why, "omega_max = %.6g, %s accepts omega_max*dt <= %g",
                p.max_angular_frequency(), std::string(name()).c_str(), stability_constant());
  return {stability_constant() / p.max_angular_frequency(), why};
}

double stability_limit(const Stepper& stepper, const ModelParams& p) {
  return stepper.time_step_limit(p).dt;
}

void check_time_step(const Stepper& stepper, const ModelParams& p, double dt) {
  const Stepper::TimeStepLimit limit = stepper.time_step_limit(p);
  if (dt > limit.dt) {
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "integrator.dt: %g is above the stability limit %.6g of %s for this scene (%s)",
                  dt, limit.dt, std::string(stepper.name()).c_str(), limit.why.c_str());
    throw Error(msg);
  }
}

}  // namespace bkq
