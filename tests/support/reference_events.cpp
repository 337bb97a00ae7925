// The straightforward event engine (see reference_events.hpp).
#include "support/reference_events.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "engine/contacts.hpp"
#include "model/substrate.hpp"

namespace bkq {

ReferenceEventEngine::ReferenceEventEngine(const ChainForces& forces, Stepper& stepper, double dt,
                                           const ChainState& state)
    : forces_(forces), stepper_(stepper), dt_(dt) {
  if (forces.params().pad_moves())
    throw Error("reference event engine: model.kind = bkp is not supported (the pad must be held)");
  if (stepper.stick_rule() != StickRule::Crossing)
    throw Error("reference event engine: integrator.scheme = " + std::string(stepper.name()) +
                " resolves transitions itself; only rk2, rk4 and verlet are supported");
  w_before_.assign(forces.n(), 0.0);
  wd_old_.assign(forces.n(), 0.0);
  slipped_.assign(forces.n(), 0);
  set_state(state);
}

void ReferenceEventEngine::set_state(const ChainState& state) {
  st_ = state;
  std::fill(st_.mobile.begin(), st_.mobile.end(), 0.0);
  std::fill(st_.wd.begin(), st_.wd.end(), 0.0);
  st_.x = st_.xd = 0;
}

EventRecord ReferenceEventEngine::next_event() {
  const int n = forces_.n();
  const ModelParams& p = forces_.params();
  const double thr = forces_.friction().threshold;
  const double* w = st_.w.data();

  // Load: scan for the largest force (the first of equals) and move the substrate until
  // it reaches the threshold, as EventEngine's loader does from its force tree.
  int trigger = 0;
  double g_max = forces_.local_force(w, 0);
  for (int j = 1; j < n; ++j) {
    const double g = forces_.local_force(w, j);
    if (g > g_max) g_max = g, trigger = j;
  }
  st_.s += std::max(0.0, (thr - (g_max + p.k_p * st_.s)) / p.loading_rate());

  EventRecord e;
  e.event = ++events_;
  e.load = st_.s;
  e.trigger = trigger;
  std::copy(st_.w.begin(), st_.w.end(), w_before_.begin());
  std::fill(slipped_.begin(), slipped_.end(), 0);
  st_.t = 0;
  st_.mobile[trigger] = 1.0;
  st_.dir[trigger] = std::copysign(1.0, forces_.spring_force(w, trigger, st_.s));
  slipped_[trigger] = 1;

  // Relax: every block, every step, until all are stuck.
  const Substrate frozen = Substrate::frozen(st_.s);
  const Range all[1] = {Range{0, n}};
  std::int64_t event_steps = 0;
  double max_speed = 0;
  for (int sliding = 1; sliding > 0;) {
    std::copy(st_.wd.begin(), st_.wd.end(), wd_old_.begin());
    stepper_.step(forces_, frozen, st_, dt_, all);
    const ContactScan scan = settle_contacts(forces_, st_, wd_old_.data(), st_.s, all, true,
                                             [&](int j) { slipped_[j] = 1; });
    sliding = scan.sliding;
    raise_max_speed(max_speed, scan.max_speed);
    sliding_block_steps += scan.sliding;
    if (!std::isfinite(max_speed))
      throw Error("reference event engine: non-finite velocity in event " +
                  std::to_string(e.event));
    if (++event_steps > max_steps_per_event)
      throw Error("reference event engine: event " + std::to_string(e.event) +
                  " did not end within " + std::to_string(max_steps_per_event) + " steps");
  }
  steps += event_steps;
  block_steps += event_steps * n;

  e.first_block = n;
  e.last_block = -1;
  std::vector<int> sites;
  for (int j = 0; j < n; ++j) {
    if (!slipped_[j]) continue;
    ++e.blocks;
    e.moment += st_.w[j] - w_before_[j];
    e.first_block = std::min(e.first_block, j);
    e.last_block = j;
    if (forces_.lattice()) sites.push_back(j);
  }
  if (forces_.lattice()) place_on_lattice(e, e.trigger, sites, forces_.nx());
  e.magnitude = e.moment > 0 ? std::log(e.moment) : std::nan("");
  e.duration = st_.t;
  e.max_speed = max_speed;
  return e;
}

}  // namespace bkq
