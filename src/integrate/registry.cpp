// integrator.scheme keyword -> stepper type (one line per scheme in kSchemes), and the
// time-step stability check.
#include <cstdio>

#include "core/error.hpp"
#include "core/format.hpp"
#include "integrate/adaptive.hpp"
#include "integrate/rk2.hpp"
#include "integrate/rk4.hpp"
#include "integrate/stepper.hpp"
#include "integrate/theta.hpp"
#include "integrate/verlet.hpp"

namespace bkq {

namespace {

// One line per scheme: its keyword and how to make it.
struct Entry {
  const char* keyword;
  std::unique_ptr<Stepper> (*make)(int n, double tolerance);
};
template <class S>
std::unique_ptr<Stepper> make(int n, double) {
  return std::make_unique<S>(n);
}
const Entry kSchemes[] = {
    {"rk2", &make<Rk2>},
    {"rk4", &make<Rk4>},
    {"verlet", &make<Verlet>},
    {"theta", &make<Theta>},
    {"adaptive",
     [](int n, double tolerance) -> std::unique_ptr<Stepper> {
       return std::make_unique<Adaptive>(n, tolerance);
     }},
};

}  // namespace

const std::vector<std::string>& stepper_keywords() {
  static const std::vector<std::string> k = [] {
    std::vector<std::string> v;
    for (const Entry& e : kSchemes) v.emplace_back(e.keyword);
    return v;
  }();
  return k;
}

std::unique_ptr<Stepper> make_stepper(const std::string& scheme, int n, double tolerance) {
  for (const Entry& e : kSchemes)
    if (scheme == e.keyword) return e.make(n, tolerance);
  std::string valid;
  for (const auto& k : stepper_keywords()) valid += (valid.empty() ? "" : "|") + k;
  throw Error("integrator.scheme: '" + scheme + "' is not available; expected one of " + valid);
}

Stepper::TimeStepLimit Stepper::time_step_limit(const ModelParams& p) const {
  char why[300];
  if (p.rayleigh_alpha != 0 || p.rayleigh_beta != 0) {
    const double c = damped_stability_constant();
    std::snprintf(why, sizeof why,
                  "with Rayleigh damping the fastest rate max(omega, alpha_M + beta_K omega^2 + "
                  "dampers) of blocks and pad is %.6g, %s accepts rate*dt <= %g",
                  p.max_angular_frequency(), std::string(name()).c_str(), c);
    return {c / p.max_angular_frequency(), why};
  }
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
    // Shortest round-trip text: a dt just above the limit never reads as equal to it.
    throw Error("integrator.dt: " + format_real(dt) + " is above the stability limit " +
                format_real(limit.dt) + " of " + std::string(stepper.name()) + " for this scene (" +
                limit.why + ")");
  }
}

}  // namespace bkq
