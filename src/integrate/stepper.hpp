// The interface every time stepper implements, and the registry that maps the scene
// keyword (integrator.scheme) to a stepper. A stepper advances the blocks in the given
// ranges and the pad (when it moves) by one step with the stick flags frozen; what
// happens at stick and slip transitions is its `stick_rule()`:
//   Crossing   within a step the stick flags and each sliding block's direction of
//              sliding are frozen (friction keeps opposing the motion the block had at the
//              start of the step, so a block decelerating through zero really crosses it).
//              The driver applies the rule after the step: a sliding block whose velocity
//              relative to the substrate changed sign (or is exactly 0) during the step is
//              stuck with zero velocity if friction can hold its spring force; otherwise it
//              keeps sliding the other way (backslip) or, for clst91, stays at zero
//              velocity. A stuck
//              block breaks loose at the start of the next step once its spring force
//              exceeds the threshold. The transition is thus resolved to within one step:
//              across transitions every fixed-step scheme is first order.
//   Projection the stepper itself projects friction onto its admissible set (theta-method).
//   Located    the stepper locates each transition on its dense output (adaptive).
#pragma once

#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "integrate/scheme_traits.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"

namespace bkq {

// A block that broke loose inside a step, with its position then.
struct StepRelease {
  int block;
  double w;
};

// What a stepper that resolves transitions inside its step (Projection, Located) saw in its
// last step(), which the driver cannot see from the flags after it: the blocks that broke
// loose (each once, with its position then; a block may have stuck again before the step
// ended), the time of the most recent located re-stick (NaN when none was located: the
// driver then takes the end of the step) and, with traits().located_on_fixed_steps, the
// work done against friction and the block dampers, summed piece by piece between located
// transitions.
class InStepTransitions {
 public:
  virtual std::span<const StepRelease> releases() const = 0;
  virtual double stick_time() const = 0;
  virtual double work() const { return 0.0; }

 protected:
  ~InStepTransitions() = default;
};

// What a stepper carries from one step() to the next besides the chain state (the adaptive
// scheme's next step size, the theta-method's reused factorisation), as plain numbers: a
// continuous run keeps it in its checkpoint and restores it into a fresh stepper of the
// same scheme and size, which then continues bit for bit. restore throws bkq::Error on data
// of another shape.
class CarriedState {
 public:
  virtual std::vector<double> save() const = 0;
  virtual void restore(std::span<const double> saved) = 0;

 protected:
  ~CarriedState() = default;
};

// The step itself, its accuracy and stability, and the parts above where a scheme has them
// (in_step(), carried(): null where it has none). What else a scheme can do is in its
// traits: the cluster form (traits().cluster_kernel) and the stencil form
// (traits().stencil_kernel) are functions of the scheme declared there.
class Stepper {
 public:
  using Release = StepRelease;
  virtual ~Stepper() = default;
  virtual std::string_view name() const = 0;
  // What this stepper supports (integrate/scheme_traits.hpp), declared once by its scheme.
  virtual const SchemeTraits& traits() const = 0;
  StickRule stick_rule() const { return traits().stick_rule; }
  // Global order of accuracy in smooth phases (no transition inside the step).
  virtual int order() const = 0;
  // Largest omega*dt accepted for an undamped linear mode of angular frequency omega
  // (HUGE_VAL for unconditionally stable schemes).
  virtual double stability_constant() const = 0;
  // The same bound on rate*dt for scenes with Rayleigh damping, where a mode's eigenvalues
  // are the roots of l^2 + c l + omega^2 (c = alpha_M + beta_K omega^2) and rate is
  // max(omega, c): the scheme's bound over every damping ratio c/(2 omega).
  virtual double damped_stability_constant() const { return stability_constant(); }
  // Largest dt this stepper accepts on this model, and why (for the error message). By
  // default the linear stability limit stability_constant / omega_max; a stepper with a
  // further bound (theta: a unique sliding speed under weakening friction) overrides it.
  struct TimeStepLimit {
    double dt;
    std::string why;
  };
  virtual TimeStepLimit time_step_limit(const ModelParams& p) const;
  virtual void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                    Ranges ranges) = 0;
  // step() in the event engine's common situation: the substrate frozen and the two end
  // blocks of every range stuck (so every block advanced is interior and the ranges
  // interact only through the pad, when it moves). A stepper may fuse its stages there
  // (traits().fused_kernels); it must give the same result as step() bit for bit. By
  // default it is step().
  virtual void step_held(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                         Ranges ranges) {
    step(forces, sub, st, dt, ranges);
  }
  // A new stepper of the same scheme and settings for a chain of n_blocks blocks, carrying
  // nothing from this one's steps: the lone-slip record (engine/lone_slip.hpp) integrates
  // its one block with it, whatever the scheme and whether the registry knows it.
  virtual std::unique_ptr<Stepper> fresh(int n_blocks) const = 0;
  // The scheme that takes the steps: this one, or the one a wrapper (located transitions)
  // wraps.
  virtual const Stepper& scheme() const { return *this; }

  // The parts, null where the stepper has none.
  virtual const InStepTransitions* in_step() const { return nullptr; }
  virtual CarriedState* carried() { return nullptr; }

  // What the driver reads of them: nothing released, no located stick (NaN), no work
  // reported and nothing carried where the stepper has no such part.
  std::span<const Release> releases_in_step() const {
    const InStepTransitions* t = in_step();
    return t ? t->releases() : std::span<const Release>{};
  }
  double located_stick_time() const {
    const InStepTransitions* t = in_step();
    return t ? t->stick_time() : std::nan("");
  }
  double step_work() const {
    const InStepTransitions* t = in_step();
    return t ? t->work() : 0.0;
  }
  std::vector<double> carried_state() {
    const CarriedState* c = carried();
    return c ? c->save() : std::vector<double>{};
  }
  void restore_carried_state(std::span<const double> saved) {
    if (CarriedState* c = carried()) c->restore(saved);
  }
};

// Keyword -> stepper; an unknown keyword throws bkq::Error listing the valid ones.
// `tolerance` is the local error tolerance of the adaptive scheme (integrator.tolerance).
std::unique_ptr<Stepper> make_stepper(const std::string& scheme, int n_blocks,
                                      double tolerance = 1e-8);
const std::vector<std::string>& stepper_keywords();

// A scheme the program does not ship (a test's): its keyword, its traits (which its
// stepper's traits() must return) and how to make it. bkq::Error when the keyword is
// taken. unregister_scheme removes one registered so; the shipped ones stay.
using StepperMaker = std::unique_ptr<Stepper> (*)(int n_blocks, double tolerance);
void register_scheme(const std::string& keyword, const SchemeTraits& traits, StepperMaker make);
void unregister_scheme(const std::string& keyword);

// Largest stable dt for this stepper on this model: stability_constant / omega_max.
double stability_limit(const Stepper& stepper, const ModelParams& p);
// Throws bkq::Error ("integrator.dt: ... above the stability limit ...") when dt is too big.
void check_time_step(const Stepper& stepper, const ModelParams& p, double dt);

}  // namespace bkq
