// The accuracy indicators every run measures, as an observer: the largest |energy balance
// residual| of a recorded event (event runs; EventRecord::energy_residual) or the energy
// balance of the whole run (continuous runs; engine/continuous.hpp), the fastest
// linear mode's omega_max * dt (fixed-step schemes; also the theta-method, which is stable
// far beyond the point where it resolves the motion) with dt over the scheme's stability
// limit, and the most relaxation steps an event took over run.max_steps_per_event (event
// runs; an event reaching the cap fails the run). They go into summary.json ("accuracy");
// after the outputs are written, each one above its threshold gives one warning line on
// stderr, or with run.accuracy = error a bkq::Error (exit 2, outputs kept). The
// thresholds are in docs/explanation/accuracy.md, "Accuracy indicators of every run".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/observers/observer.hpp"
#include "integrate/stepper.hpp"
#include "io/settings.hpp"

namespace bkq {

inline constexpr double kEnergyResidualLimit = 0.05;  // of an event, or of a continuous run
inline constexpr double kOmegaDtLimit = 1.0;          // omega_max * dt, fixed-step schemes
inline constexpr double kEventStepsShareLimit = 0.5;  // of run.max_steps_per_event

class AccuracyCheck : public RunObserver {
 public:
  AccuracyCheck(const Settings& settings, const Stepper& stepper);
  void on_resume(const Checkpoint& c) override;
  void on_event(const EventRecord& e) override;
  void on_checkpoint(Checkpoint& c) override;
  void add_to_summary(Json& summary) const override;
  // The relaxation steps an event took (event runs, transient events included).
  void note_event_steps(std::int64_t steps) {
    if (steps > steps_max_) steps_max_ = steps;
  }
  // Continuous runs: the energy balance of the whole run (ContinuousDriver), set before
  // the run ends.
  void set_run_energy_residual(double r) { run_residual_ = r; }
  // Once the outputs are written: a warning line on stderr per indicator above its
  // threshold, or, with run.accuracy = error, throws bkq::Error naming them.
  void verdict() const;

 private:
  struct Finding {
    std::string indicator, text;
  };
  std::vector<Finding> findings() const;

  bool events_mode_, error_mode_, fixed_step_;
  double dt_, omega_dt_, dt_over_limit_;
  std::int64_t max_steps_;
  bool adaptive_allowed_;  // may the advice name the adaptive scheme
  double residual_max_ = 0, residual_sum_ = 0;
  std::int64_t residual_n_ = 0, steps_max_ = 0;
  double run_residual_ = 0;
};

}  // namespace bkq
