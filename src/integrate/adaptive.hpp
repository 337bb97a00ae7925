// The event-located adaptive reference stepper (integrator.scheme = adaptive): Dormand–
// Prince 5(4) with error control, and every stick–slip transition inside a step located
// on the dense output, so that accuracy does not collapse to first order at transitions
// the way it does for the fixed-step schemes under the Crossing rule (stepper.hpp).
//
// Scheme. The explicit Runge–Kutta pair of Dormand & Prince (1980), seven stages with
// FSAL (the last stage is the derivative at the new point, reused as the next step's
// first), on y = (w, w', x, x') for the blocks in the ranges and the pad when it moves.
// The 5th-order solution is propagated; the embedded 4th-order one gives the local error
// estimate. Dense output is Shampine's 4th-order continuous extension (Hairer, Nørsett &
// Wanner, Solving ODEs I, §II.6; DOPRI5's CONTD5), evaluated per component on demand.
//   Order 5 in smooth phases (global error ~ tolerance).
//   Stability: the step-size control keeps every step inside DOPRI5's stability region
//   (|h lambda| up to ~3.3), so stability_constant() is HUGE_VAL: the scene's dt is only
//   the macro step after which the driver looks at the state.
//
// Error control. Max norm over the advanced components of err_i / (tol (1 + |y_i|)) with
// |y_i| the larger of the step's two ends (mixed absolute/relative, atol = rtol = tol).
// Positions enter as w - s0, measured from the substrate's position s0 at the start of the
// step, so the relative part does not grow with the loading (w = u + s). Step-size
// controller: h_new = h min(10, max(0.2, 0.9 err^(-1/5))), no growth right after a
// rejection; a step shortened to land on the macro step's end does not shrink the next.
// The first step of a new problem (the stepper's first call, or a call whose time does
// not continue the previous one, as at each event of the event engine) is guessed by
// Hairer's HINIT. A step size below 16 eps max(|t|, dt) throws bkq::Error.
//
// Stick rule: Located. Within a step the stick flags (st.mobile) and sliding directions
// (st.dir) are frozen between transitions. Event functions, checked at the ends of every
// accepted step for the blocks in the ranges:
//   sliding block j:  g_j = dir_j w'_j, a transition once g_j <= 0 (it stopped or turned);
//   stuck block j:    friction().breaks(f_j), f_j = spring_force(w, j, s + x) (the static
//                     threshold, and -threshold for laws with backslip).
// If any fired, the earliest crossing is found in two stages:
//   bracketing: each fired block's crossing is bisected on the dense output (cheap: per
//     block) to 1e-13 (|t| + h), and the earliest, t*, taken. The dense output is only 4th
//     order and not error-controlled: with h omega ~ 0.1 it puts a stick ~1e-6 late or early;
//   polishing: Newton's method on that block's event function with real steps. A DP5 step
//     from the step's start t0 to any t <= t0 + h ends on the 5th-order solution, its error
//     no larger than the accepted step's. Starting at t*, each iterate is such a step, the
//     event function's rate there (dir_j w''_j sliding, the spring force's rate stuck) gives
//     the next t, kept inside the bracket [t0, t0 + h] that the real steps narrow (else
//     bisected), until the correction is below 1e-13 (|t| + h), the event function is at
//     its rounding level (for a stuck block, the rounding of spring forces summed from
//     positions w = u + s of the size of the loading), or the corrections stop shrinking.
//     Two or three real steps per transition (polishing_steps(); ~2.5 on the default scene).
// The state is set to the last real step's end and every block whose event function has
// fired there makes its transition:
//   sliding -> stuck (mobile 0, w' = 0) if friction().holds(f); otherwise w' = 0 and it
//              keeps sliding the way its spring pulls (dir = sign f): back the way it came
//              (dir flips) for laws with backslip, forwards (dir = +1) for clst91;
//   stuck -> sliding (mobile 1, w' = 0, dir = sign f).
// Integration then restarts from that instant (the right-hand side jumps there). The
// located instant is thus as accurate as the integration itself, whatever the step size:
// its error is the trajectory's global error divided by the event function's rate of
// change, plus rounding. At tolerance 1e-10 a single block decelerating at 0.01 sticks
// within 1e-13 of the exact time in macro steps of 0.01 (2e-9 in one call for the whole
// slip: the velocity's global error over the larger steps), and the first event of a
// 2-block chain (k_c = 100) has the same moment and duration to 1e-13 in macro steps of
// 1e-3 and 1e-4; in macro steps of 1e-2 they differ by the global error of steps that
// long, 1e-9 and 3e-9 (tests/numeric/test_adaptive.cpp). A second block whose event
// fires within the dense output's error of the located one makes its transition at the
// polished instant too. The direction of a sliding block with non-zero velocity is taken
// from its velocity at the start of step(), as settle_contacts keeps it. Frictionless
// scenes (law none) have no transitions and locate nothing.
//
// Limitation: only blocks in the ranges are watched. A stuck block just outside them is
// held fixed for the whole macro step and its threshold is checked by the driver only
// after the macro step (the engine covers a sliding block's neighbours, so such a block
// is one that a transition inside the step has newly exposed).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "integrate/stepper.hpp"

namespace bkq {

class Adaptive final : public Stepper {
 public:
  // tolerance: the local error tolerance, in (0, 1); throws bkq::Error otherwise.
  Adaptive(int n_blocks, double tolerance);

  std::string_view name() const override { return "adaptive"; }
  int order() const override { return 5; }
  double stability_constant() const override { return HUGE_VAL; }
  StickRule stick_rule() const override { return StickRule::Located; }
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override;

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
  double located_stick_time() const override { return last_stick_time_; }
  // Blocks released inside the last step(), each once (at its first release), in order:
  // a block may have slipped and stuck again before the driver looks at the flags.
  std::span<const Release> releases() const { return releases_; }
  std::span<const Release> releases_in_step() const override { return releases_; }

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
