// integrator.scheme keyword -> stepper type and traits (one line per scheme in schemes()),
// and the time-step stability check.
#include <cstdio>
#include <string_view>

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

// One line per scheme: its keyword, its traits (the class's own, declared there once) and
// how to make it.
struct Entry {
  std::string keyword;
  SchemeTraits traits;
  StepperMaker make;
  bool shipped = true;
};
template <class S>
std::unique_ptr<Stepper> make(int n, double) {
  return std::make_unique<S>(n);
}
std::vector<Entry>& schemes() {
  static std::vector<Entry> s = {
      {"rk2", Rk2::kTraits, &make<Rk2>},
      {"rk4", Rk4::kTraits, &make<Rk4>},
      {"verlet", Verlet::kTraits, &make<Verlet>},
      {"theta", Theta::kTraits, &make<Theta>},
      {"adaptive", Adaptive::kTraits,
       [](int n, double tolerance) -> std::unique_ptr<Stepper> {
         return std::make_unique<Adaptive>(n, tolerance);
       }},
  };
  return s;
}
// The keywords, in registry order (kept beside the entries: callers hold a reference).
std::vector<std::string>& keywords() {
  static std::vector<std::string> k = [] {
    std::vector<std::string> v;
    for (const Entry& e : schemes()) v.push_back(e.keyword);
    return v;
  }();
  return k;
}

}  // namespace

const std::vector<std::string>& stepper_keywords() {
  return keywords();
}

const SchemeTraits* scheme_traits(std::string_view keyword) {
  for (const Entry& e : schemes())
    if (e.keyword == keyword) return &e.traits;
  return nullptr;
}

std::vector<std::string> shipped_scheme_keywords() {
  std::vector<std::string> k;
  for (const Entry& e : schemes())
    if (e.shipped) k.push_back(e.keyword);
  return k;
}

std::unique_ptr<Stepper> make_stepper(const std::string& scheme, int n, double tolerance) {
  for (const Entry& e : schemes())
    if (scheme == e.keyword) return e.make(n, tolerance);
  std::string valid;
  for (const auto& k : stepper_keywords()) valid += (valid.empty() ? "" : "|") + k;
  throw Error("integrator.scheme: '" + scheme + "' is not available; expected one of " + valid);
}

void register_scheme(const std::string& keyword, const SchemeTraits& traits, StepperMaker make) {
  if (scheme_traits(keyword) != nullptr)
    throw Error("integrator.scheme: '" + keyword + "' is registered already");
  // The keyword list first: made on first use from the entries, it would hold this one twice.
  std::vector<std::string>& k = keywords();
  schemes().push_back(Entry{keyword, traits, make, false});
  k.push_back(keyword);
}

void unregister_scheme(const std::string& keyword) {
  auto& s = schemes();
  for (auto it = s.begin(); it != s.end(); ++it)
    if (it->keyword == keyword && !it->shipped) {
      s.erase(it);
      std::erase(keywords(), keyword);
      return;
    }
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
