// The start of every event, integrated once and replayed.
//
// An event starts when the loader has put one block exactly at the static threshold F0,
// at rest, with every other block stuck (the pad held: BK and 1DOF models). Until one of
// its neighbours breaks loose, that block slides alone, and in coordinates relative to
// where it started its equation is the same in every event:
//     m_u d'' = F0 - K d - m_u phi(d') [- c_u d'],     d(0) = d'(0) = 0,
// where K is its stiffness (k_p + 2 k_c inside the chain, k_p + k_c at a free end, k_p
// without neighbour springs; on a lattice k_p plus the springs to the site's partners, and a
// partner's force changes by its spring times d): nothing in it depends on where the chain is.
// So the engine
// integrates it once per stiffness, with the scene's own stepper, step and stick rule
// (Crossing), through the general code path (step, dissipated_power, settle_contacts),
// and records every step until the block sticks. An event then takes its start from the
// record: a neighbour at spring force f_n breaks at the first step n with
// f_n + k_c d_n > F0 (or < -F0 where backslip is allowed); if none does before the
// block sticks, the event was a lone slip and is finished; otherwise the engine puts the
// block at the recorded state of step n and integrates on from there.
//
// The recorded trajectory is the stepper's own, in relative coordinates; the direct
// integration computes the same steps from absolute positions, which in a long run are
// large (|w| ~ the substrate's displacement), so the two differ by rounding only. Where
// that rounding could change a decision (a neighbour's force within a bound on it of the
// threshold, the start force not at the threshold within it, or a crossing of the table
// too narrow for it), the engine integrates the event directly instead. The bound is ten
// times the worst case of the rounding a direct integration of that many steps at those
// positions can accumulate, every rounding adding up (lone_slip_tolerance). The bound
// grows with the positions, so a long run's replays thin out as its load grows
// (docs/explanation/event-engine.md, "How it works", gives the measured share).
//
// What the replay changes is rounding only, but rounding is all that separates two
// integrations of a chaotic chain: a long run with the replay on and off from the same
// seed gives catalogues that agree event for event at first and drift apart later (as
// they would under any change of the arithmetic's order, such as shifting the origin).
// tests/regression/test_lone_slip.cpp runs events both ways from the same states, at
// small and at large loads.
//
// With located transitions (integrator.transitions = located) the record is integrated by
// the located stepper (integrate/located.hpp): the block's stick is located inside its
// last step, and the record keeps that instant (stick_time). A neighbour's failure is then
// located inside the step where it happens, which the record does not do: the engine
// replays the record up to the step before it and takes that step on its general path.
// The decisions the record takes are the located stepper's (the sign of the velocity at
// the end of each attempted step, friction holding the force at the stick), and their
// margins are measured on them.
//
// The slide ends at the block's first turning point: there its spring force is
// F0 - K d with K d at most twice F0 - phi (the kinetic friction), so friction holds it
// and it sticks. So d never decreases (d_min stays 0); the record keeps the running
// extremes all the same, so that the neighbours' tests do not rest on that argument.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "model/parameters.hpp"

namespace bkq {

class Stepper;

struct LoneSlip {
  // The state at the end of step n (steps[n - 1]), after the stick rule.
  struct Step {
    double d = 0;      // displacement from the start
    double v = 0;      // velocity (0 once stuck)
    double dir = 1;    // direction of sliding
    double t = 0;      // time since the start (dt added n times, as the engine adds it)
    double work = 0;   // work against friction and the block damper since the start
    double d_max = 0;  // extremes of d over steps 1..n
    double d_min = 0;
    double max_speed = 0;            // largest |v| of a sliding block over steps 1..n
    int sliding = 1;                 // 1 while it slides, 0 at the last step
    std::int64_t sliding_steps = 0;  // `sliding` summed over steps 1..n
  };
  double stiffness = 0;
  std::vector<Step> steps;  // the block sticks at the end of the last one
  // Located transitions: the instant of the stick, inside the last step (time since the
  // start); NaN at the step.
  double stick_time = std::nan("");
  // How far the table's own decisions are from going the other way: the smallest
  // |velocity| at the end of a step (the crossing test looks at its sign), and the smallest
  // distance of the spring force from the threshold where a crossing was tested.
  double velocity_margin = 0;
  double force_margin = 0;
  bool usable = false;
  std::string why_not;  // when not usable
};

// Integrates the lone block of stiffness `stiffness` with the model's friction, mass and
// damper, by a fresh copy of `scheme`'s stepper (Stepper::fresh; a located wrapper's scheme
// unwrapped) at step dt, until it sticks (unusable if it has not after max_steps
// steps, or if it never leaves the start); `located`: with located transitions.
LoneSlip integrate_lone_slip(const ModelParams& p, double stiffness, const Stepper& scheme,
                             double dt, std::int64_t max_steps, bool located = false);

// Bounds on the differences of rounding size between the table and a direct integration
// of `steps` steps at step dt with positions of size `position_scale` (see above).
struct LoneSlipTolerance {
  double force = 0;
  double velocity = 0;
};
LoneSlipTolerance lone_slip_tolerance(const ModelParams& p, double position_scale, double dt,
                                      std::int64_t steps);
// The same for a block whose springs to its partners sum to at most `coupled` (2 k_c in a
// chain, which the form above takes; on a lattice twice the stencil's springs).
LoneSlipTolerance lone_slip_tolerance(const ModelParams& p, double position_scale, double dt,
                                      std::int64_t steps, double coupled);

}  // namespace bkq
