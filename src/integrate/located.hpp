// Located transitions for the explicit Crossing schemes (integrator.transitions = located):
// the scheme's own step (rk2, rk4 or verlet), with every stick and every failure inside a
// step located on the step's dense output and the step cut there.
//
// Method. A step of length h is taken with the stick flags frozen, as the Crossing rule
// does. If at its end a sliding block's velocity has reached zero against its direction of
// sliding (dir w' <= 0) or a stuck block's spring force has passed the threshold, the
// instant of the earliest such transition is located on the cubic Hermite interpolant of
// the step (positions from w, w' at both ends; velocities from w', w'' at both ends, the
// accelerations at the ends evaluated with the frozen flags), bracketed to 1e-13 of the
// step (Illinois regula falsi, bisecting where a step does not halve the bracket). The step is then
// taken again, by the same scheme, from its start to that instant. A failure's instant, and a
// stick's after which nothing of the ranges slides (the event's end, whose duration it is), is
// then polished by at most three Newton steps on such real steps (the attempted step ran past
// the transition, where friction has a kink at zero velocity, which limits the interpolant
// there; the real steps end before it). Any other stick keeps the interpolant's instant: the
// block's velocity is zero there, so the instant's error enters the state only quadratically,
// while a failure's instant carries over one to one into the rest of the event (the released
// block's slip starts then). There the located block (and every other block whose transition has
// happened by then) changes state by the stick rule below, and the rest of the step proceeds the
// same way. The work against friction and the block dampers is summed piece by piece (work()).
// This is a whole-cluster cut: every block of the ranges is stepped to the transition instant. A
// per-block cut (only the blocks a transition concerns stepped to it) is not possible within one
// explicit step, whose stages couple each block to its neighbours at the intermediate times: a
// block stepped alone to the instant would see its neighbours at the step's end, which is first
// order again.
//
// Order. Between transitions the scheme's own (order p; rk2 2, rk4 4, verlet 2). The
// cubic Hermite interpolant is exact to O(h^4) locally and passes through the scheme's
// values, and the polish brings the instant to the accuracy of the scheme's state, so a
// polished transition time is located to O(h^p): a failure time's error enters
// the slip linearly, a stick time's only quadratically (the velocity is zero there), so an
// unpolished stick, O(h^2) at worst, costs O(h^4) in the state. The
// event therefore keeps the scheme's order (Hairer, Nørsett & Wanner 1993, Solving ODEs I,
// §II.6 on dense output; Shampine 1986, Appl. Math. Comput., on event location).
//
// Stability limit: the scheme's (a cut step is shorter than dt, never longer).
//
// Stick rule at a located instant (Located): a sliding block whose velocity reached zero
// sticks, with zero velocity, where friction holds its spring force; otherwise it slides
// on the way its spring pulls (backslip laws: back the way it came; clst91: forwards, since
// f > threshold > 0). A stuck block whose force reached the threshold breaks loose with
// zero velocity, sliding the way its spring pulls. These are the rules of model/stick.hpp
// applied at the located instant instead of at the end of the step.
//
// A block released inside a step moves for the rest of it: its neighbours join the step's
// ranges as stuck blocks (the scheme's stages read their positions), and the caller learns
// of the release from releases() (InStepTransitions).
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "integrate/stepper.hpp"

namespace bkq {

class LocatedTransitions final : public Stepper, public InStepTransitions, public CarriedState {
 public:
  // `scheme` must be a Crossing scheme (rk2, rk4, verlet); bkq::Error otherwise.
  LocatedTransitions(std::unique_ptr<Stepper> scheme, int n_blocks);

  std::string_view name() const override { return scheme_->name(); }
  std::unique_ptr<Stepper> fresh(int n_blocks) const override {
    return std::make_unique<LocatedTransitions>(scheme_->fresh(n_blocks), n_blocks);
  }
  const Stepper& scheme() const override { return *scheme_; }
  const SchemeTraits& traits() const override { return traits_; }
  int order() const override { return scheme_->order(); }
  double stability_constant() const override { return scheme_->stability_constant(); }
  double damped_stability_constant() const override { return scheme_->damped_stability_constant(); }
  TimeStepLimit time_step_limit(const ModelParams& p) const override {
    return scheme_->time_step_limit(p);
  }
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override;

  // Its parts: what it saw inside the last step, and the last located re-stick carried.
  const InStepTransitions* in_step() const override { return this; }
  CarriedState* carried() override { return this; }
  std::span<const Release> releases() const override { return releases_; }
  double stick_time() const override { return last_stick_time_; }
  // The work done against friction and the block dampers over the last step(): the
  // trapezoidal rule on each piece between two located transitions, with the flags of that
  // piece (the event engine's ledger; over the whole step the rule would straddle them).
  double work() const override { return work_; }
  std::vector<double> save() const override { return {last_stick_time_}; }
  void restore(std::span<const double> s) override;

  // Counters since construction: transitions located inside a step (each one cut), and
  // scheme steps taken (the attempted steps that found a transition included).
  std::int64_t located_transitions() const { return located_; }
  std::int64_t scheme_steps() const { return scheme_steps_; }

  // A study's view of each step cut at a located instant inside it (a transition at a
  // step's very end cuts nothing): the block whose transition cut it and the step's ranges,
  // the flags those of the step. Tests and benchmarks count with it what the cuts step
  // (tests/support/located_cuts.hpp); null (the default) watches nothing.
  class CutWatcher {
   public:
    virtual void cut(const ChainForces& forces, const ChainState& st, int who, Ranges ranges) = 0;

   protected:
    ~CutWatcher() = default;
  };
  void watch_cuts(CutWatcher* watcher) { watcher_ = watcher; }

 private:
  // Saves (restore: puts back) the start of the step: the blocks of the ranges, the pad.
  void save_start(const ChainState& st, Ranges ranges);
  void restore_start(ChainState& st, Ranges ranges) const;
  // Blocks whose transition has happened by the end of the attempted step (in fired_).
  bool fired_at_end(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                    Ranges ranges);
  // Block j's event function at t0 + theta h on the dense output: for a sliding block its
  // velocity along its direction, for a stuck one the threshold less its spring force (its
  // magnitude with backslip); the transition has happened where fired() says so.
  double event_value(const ChainForces& forces, const Substrate& sub, const ChainState& st, int j,
                     double theta);
  static bool fired(const ChainState& st, int j, double g) {
    return st.mobile[j] != 0.0 ? g <= 0.0 : g < 0.0;
  }
  // The earliest located transition among fired_, as a fraction of the step; `who` its block.
  double locate(const ChainForces& forces, const Substrate& sub, const ChainState& st, int& who);
  // The transitions at the current instant: `who`'s, and every other that has happened.
  void transit(const ChainForces& forces, const Substrate& sub, ChainState& st, int who,
               Ranges ranges);
  bool in_ranges(int j) const { return mark_[j] == stamp_; }
  // Adds block k to this step's ranges (own_), and sets the dense output's held blocks;
  // false if it was in them already.
  bool include(int k, const ChainState& st);
  void halo(const ChainState& st);
  // Block j's event function over its time derivative at the current state (the Newton
  // correction of the located instant, on a real step).
  double newton_ratio(const ChainForces& forces, const Substrate& sub, const ChainState& st, int j);
  // The work of one piece of length tau: from the velocities v0_ at its start to st's.
  double sub_step_work(const ChainForces& forces, const ChainState& st, Ranges ranges,
                       double tau) const;
  // Whether the instant of `who`'s transition (st at its estimate) is polished: a failure's
  // always, a stick's when every other sliding block of the ranges has stopped by then too
  // (the event may end there, and its duration is the instant). See the header comment.
  static bool instant_matters(const ChainState& st, int who, Ranges ranges);
  double dense_w(int j, double theta) const;
  double dense_wd(int j, double theta) const;

  std::unique_ptr<Stepper> scheme_;
  SchemeTraits traits_;  // the scheme's, located (located_traits)
  int n_;
  // The attempted step: its start (w0_, v0_, a0_, pad), end (w1_, v1_, a1_, pad) and length.
  std::vector<double> w0_, v0_, a0_, w1_, v1_, a1_, wq_;
  double x0_ = 0, xd0_ = 0, sum0_ = 0, x1_ = 0, xd1_ = 0, t0_ = 0, h_ = 0;
  std::vector<int> fired_;
  // The ranges of the step: the caller's, grown by the neighbours of the blocks that break
  // loose inside it.
  std::vector<Range> own_;
  std::vector<std::uint64_t> mark_, released_mark_;
  std::uint64_t stamp_ = 0;
  std::vector<Release> releases_;
  double last_stick_time_ = std::nan("");
  double work_ = 0;
  std::int64_t located_ = 0, scheme_steps_ = 0;
  CutWatcher* watcher_ = nullptr;
};

// The stepper of `scheme` with located transitions (the wrapper above); bkq::Error naming
// integrator.transitions when the scheme resolves its transitions itself.
std::unique_ptr<Stepper> with_located_transitions(std::unique_ptr<Stepper> scheme, int n_blocks);

}  // namespace bkq
