// The event-located adaptive reference stepper (integrator.scheme = adaptive): Dormand–
// Prince 5(4) with error control (atol = rtol = integrator.tolerance) and every stick–slip
// transition located on the dense output and polished with real steps, so accuracy does
// not drop to first order at transitions. Order 5 in smooth phases. Stability: the
// step-size control keeps every step stable (integrator.dt is only the macro step).
// Stick rule: Located. The scheme, the error control, the event location and its limits
// are set out in docs/explanation/integrators.md, "The adaptive reference".
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "integrate/stepper.hpp"

namespace bkq {

class Adaptive final : public Stepper, public InStepTransitions, public CarriedState {
 public:
  // tolerance: the local error tolerance, in (0, 1); throws bkq::Error otherwise.
  Adaptive(int n_blocks, double tolerance);

  // Transitions located on its own dense output, its step size under error control.
  static constexpr SchemeTraits kTraits{.stick_rule = StickRule::Located, .error_control = true};
  std::string_view name() const override { return "adaptive"; }
  std::unique_ptr<Stepper> fresh(int n_blocks) const override;
  const SchemeTraits& traits() const override { return kTraits; }
  int order() const override { return 5; }
  double stability_constant() const override { return HUGE_VAL; }
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override;
  // Its parts: what it saw inside the last step, and what it carries (the next step size,
  // where the last call ended and the last located re-stick).
  const InStepTransitions* in_step() const override { return this; }
  CarriedState* carried() override { return this; }
  std::vector<double> save() const override;
  void restore(std::span<const double> s) override;

  double tolerance() const { return tol_; }
  // Run with a fixed internal step h and no error control (transitions still located;
  // for convergence studies in h). h = 0 returns to adaptive steps.
  void set_fixed_step(double h);
  double fixed_step() const { return fixed_h_; }

  // Counters since construction (or reset_counters).
  std::int64_t accepted_steps() const { return accepted_; }
  std::int64_t rejected_steps() const { return rejected_; }
  std::int64_t located_transitions() const { return transitions_; }
  // Real steps taken to polish located transitions (not counted as accepted steps).
  std::int64_t polishing_steps() const { return polishing_; }
  void reset_counters() { accepted_ = rejected_ = transitions_ = polishing_ = 0; }
  // Time of the most recent located re-stick (NaN before the first): the end of a slip,
  // where the driver only sees the macro step's end.
  double last_stick_time() const { return last_stick_time_; }
  double stick_time() const override { return last_stick_time_; }
  // Blocks released inside the last step(), each once (at its first release), in order:
  // a block may have slipped and stuck again before the driver looks at the flags.
  std::span<const Release> releases() const override { return releases_; }

 private:
  // Stage S (0-based, 1..6; stage 0 is first_stage) from the stages before it: positions
  // into ws_, velocities into vel_[S], accelerations into acc_[S] (and the pad's).
  template <int S>
  void stage(const ChainForces& forces, const Substrate& sub, const ChainState& st, double h,
             Ranges ranges);
  // Accelerations of the blocks in the ranges into a; returns the pad's (0 when held).
  double accelerations(const ChainForces& forces, const SubstrateState& sub, const double* w,
                       const double* wd, const ChainState& st, double x, double xd, double sum_w,
                       Ranges ranges, double* a) const;
  // Stage 1 (w', a) at the current state: the start of a new segment.
  void first_stage(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                   Ranges ranges);
  // Stages 1..6 from the current state over h; y1 lands in ws_, vel_[6], x1_, xd1_, sum1_.
  void attempt(const ChainForces& forces, const Substrate& sub, const ChainState& st, double h,
               Ranges ranges);
  // Takes the attempted step: st becomes y1 at t1 and its last stage the next one's first.
  void commit(ChainState& st, double t1, bool pad, Ranges ranges);
  double error_norm(const ChainState& st, double s0, double h, bool pad, Ranges ranges) const;
  double initial_step(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                      double dt, Ranges ranges);

  // Event functions. `fired_at_end` collects the blocks whose event fired over the step
  // just attempted; `fired_at(j, theta)` evaluates block j's on the dense output.
  bool fired_at_end(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                    double t1, Ranges ranges);
  bool fired_at(const ChainForces& forces, const Substrate& sub, const ChainState& st, int j,
                double t0, double h, double theta);
  // Earliest crossing among the fired blocks, as a fraction of the step; `who` is its block.
  double locate(const ChainForces& forces, const Substrate& sub, const ChainState& st, double h,
                int& who);
  // Block j's event function at the end t1 of the step just attempted, signed to be positive
  // before its transition (dir_j w'_j sliding; threshold - |f_j| stuck, threshold - f_j
  // without backslip), its time derivative and the size of its rounding errors.
  struct EventValue {
    double g, rate, noise;
  };
  EventValue event_at_end(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                          int j, double t1);
  // From the dense output's crossing theta h of block `who`, Newton's method on real steps
  // from st.t; returns the final step length, whose attempt is left in the stage arrays.
  double polish(const ChainForces& forces, const Substrate& sub, const ChainState& st, double h,
                double theta, int who, Ranges ranges);
  // Applies the transitions at the current state: `who`'s, and any other fired there.
  void transit(const ChainForces& forces, const Substrate& sub, ChainState& st, int who,
               Ranges ranges);
  bool in_ranges(int j) const { return mark_[j] == stamp_; }
  double dense_w(const ChainState& st, int j, double h, double theta) const;
  double dense_wd(const ChainState& st, int j, double h, double theta) const;
  double dense_x(const ChainState& st, double h, double theta) const;

  double tol_;
  double fixed_h_ = 0;
  double h_ = 0;                    // next step size (0: guess one)
  double t_resume_ = std::nan("");  // where the previous call ended
  double last_stick_time_ = std::nan("");
  std::int64_t accepted_ = 0, rejected_ = 0, transitions_ = 0, polishing_ = 0;

  int n_;
  std::vector<double> ws_;                  // stage positions (and the halo of the ranges)
  std::array<std::vector<double>, 7> vel_;  // stage velocities (the derivative of w)
  std::array<std::vector<double>, 7> acc_;  // stage accelerations (the derivative of w')
  std::array<double, 7> pad_vel_{}, pad_acc_{};
  double x1_ = 0, xd1_ = 0, sum1_ = 0;        // the pad and sum_w at the end of the attempt
  std::vector<double> wq_;                    // positions or velocities around one block
  std::vector<int> fired_;                    // blocks whose event fired over the step
  std::vector<std::uint64_t> mark_;           // mark_[j] == stamp_: j is in this call's ranges
  std::vector<std::uint64_t> released_mark_;  // released_mark_[j] == stamp_: j is in releases_
  std::uint64_t stamp_ = 0;
  std::vector<Release> releases_;
};

}  // namespace bkq
