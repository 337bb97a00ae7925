// The accuracy indicators; see accuracy_check.hpp.
#include "app/observers/accuracy_check.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "integrate/stepper.hpp"
#include "io/checkpoint.hpp"
#include "io/json.hpp"

namespace bkq {

namespace {
constexpr const char* kAccuracyStateName = "accuracy";

// A value with four significant digits, or all of them where four would print it equal to
// the threshold it is compared with.
std::string shown(double value, double limit) {
  char a[32], b[32];
  std::snprintf(a, sizeof a, "%.4g", value);
  std::snprintf(b, sizeof b, "%.4g", limit);
  return std::string(a) == b ? format_real(value) : a;
}
}  // namespace

AccuracyCheck::AccuracyCheck(const Settings& settings, const Stepper& stepper)
    : events_mode_(settings.drive.mode == DriveMode::Events),
      error_mode_(settings.run.accuracy_error),
      // A scheme with error control chooses its own steps; every other scheme steps at dt.
      fixed_step_(!stepper.traits().error_control),
      dt_(settings.integrator.dt),
      omega_dt_(settings.model.max_angular_frequency() * settings.integrator.dt),
      dt_over_limit_(settings.integrator.dt / stepper.time_step_limit(settings.model).dt),
      max_steps_(settings.run.max_steps_per_event),
      // The adaptive scheme is written for chains of nearest-neighbour springs.
      adaptive_allowed_(
          !(settings.model.lattice() || settings.model.long_range() || settings.model.viscous())) {}

void AccuracyCheck::on_event(const EventRecord& e) {
  if (!events_mode_) return;  // slip episodes carry no energy balance
  const double r = std::abs(e.energy_residual);
  if (!(r <= residual_max_) && residual_max_ == residual_max_) residual_max_ = r;  // NaN stays
  residual_sum_ += r;
  ++residual_n_;
}

void AccuracyCheck::on_resume(const Checkpoint& c) {
  // A checkpoint from before the indicators has none: they restart.
  find_state(c, kAccuracyStateName, residual_max_, residual_sum_, residual_n_, steps_max_);
}

void AccuracyCheck::on_checkpoint(Checkpoint& c) {
  put_state(c, kAccuracyStateName, residual_max_, residual_sum_, residual_n_, steps_max_);
}

std::vector<AccuracyCheck::Finding> AccuracyCheck::findings() const {
  std::vector<Finding> f;
  // Each finding reads "<indicator> = <value> is above <limit><why and what to do>".
  const auto above = [&f](const char* indicator, double value, double limit,
                          const std::string& rest) {
    f.push_back({indicator, std::string(indicator) + " = " + shown(value, limit) + " is above " +
                                format_real(limit) + rest});
  };
  const std::string reduce_dt = adaptive_allowed_
                                    ? ": reduce integrator.dt (or use integrator.scheme = adaptive)"
                                    : ": reduce integrator.dt";
  if (events_mode_ && !(residual_max_ <= kEnergyResidualLimit))
    above("energy_residual_max", residual_max_, kEnergyResidualLimit,
          " (the largest relative energy-balance error of an event)" + reduce_dt);
  if (!events_mode_ && !(std::abs(run_residual_) <= kEnergyResidualLimit))
    above("energy_residual", run_residual_, kEnergyResidualLimit,
          " in magnitude (the relative energy-balance error of the whole run)" + reduce_dt);
  if (fixed_step_ && omega_dt_ > kOmegaDtLimit)
    above("omega_dt", omega_dt_, kOmegaDtLimit,
          " (the fastest mode's angular frequency times integrator.dt; fewer than 2 pi steps per "
          "period): reduce integrator.dt to at most " +
              shown(dt_ * kOmegaDtLimit / omega_dt_, 0));
  const double share = static_cast<double>(steps_max_) / static_cast<double>(max_steps_);
  if (events_mode_ && share > kEventStepsShareLimit)
    above("event_steps_share", share, kEventStepsShareLimit,
          " (the longest event's relaxation steps over run.max_steps_per_event = " +
              std::to_string(max_steps_) +
              "): check integrator.dt and the scene, or raise run.max_steps_per_event");
  return f;
}

void AccuracyCheck::add_to_summary(Json& summary) const {
  Json a = Json::object();
  a.set("omega_dt", omega_dt_);
  a.set("omega_dt_limit", fixed_step_ ? kOmegaDtLimit : HUGE_VAL);
  a.set("dt_over_stability_limit", dt_over_limit_);
  if (events_mode_) {
    a.set("energy_residual_max", residual_max_);
    a.set("energy_residual_mean", residual_n_ > 0 ? residual_sum_ / residual_n_ : 0.0);
    a.set("energy_residual_limit", kEnergyResidualLimit);
    a.set("event_steps_max", steps_max_);
    a.set("event_steps_limit", kEventStepsShareLimit * static_cast<double>(max_steps_));
  } else {
    a.set("energy_residual", run_residual_);
    a.set("energy_residual_limit", kEnergyResidualLimit);
  }
  std::vector<std::string> names;
  for (const Finding& f : findings()) names.push_back(f.indicator);
  a.set("warnings", Json::strings(names));
  summary.set("accuracy", std::move(a));
}

void AccuracyCheck::verdict() const {
  const std::vector<Finding> found = findings();
  if (found.empty()) return;
  if (error_mode_) {
    std::string msg = "accuracy: ";
    for (std::size_t k = 0; k < found.size(); ++k) msg += (k ? "; " : "") + found[k].text;
    throw Error(msg + " (run.accuracy = error; the outputs are kept)");
  }
  for (const Finding& f : found)
    std::fprintf(stderr, "bkquake: warning: accuracy: %s (run.accuracy = error makes this fatal)\n",
                 f.text.c_str());
}

}  // namespace bkq
