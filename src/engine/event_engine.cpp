// The event-driven engine; see event_engine.hpp for the algorithm and the definition of
// the end of an event.
#include "engine/event_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "integrate/transition_rule.hpp"
#include "model/damped_oscillator.hpp"

namespace bkq {

namespace {
// The pad's sum of block positions is re-summed from scratch every this many events.
constexpr int kResumEvery = 1024;
// Stuck blocks covered on each side of a sliding block: those its springs reach (one, or R
// with range coupling); twice that for the adaptive stepper, which locates releases inside
// its step (a block released mid-step reaches as far again). The located wrapper of a
// fixed-step scheme adds the neighbours of a block it releases to its step itself
// (located.hpp).
int margin_for(const ChainForces& forces, const Stepper& stepper) {
  const bool adds_own = stepper.traits().located_on_fixed_steps;
  return (stepper.stick_rule() == StickRule::Located && !adds_own ? 2 : 1) * forces.reach();
}
}  // namespace

namespace {
// Steppers that place transitions inside their step (theta's projection, the adaptive scheme,
// the located wrapper) read and cover only j +- 1: lattices, couplings beyond the nearest
// neighbours and dashpots need a Crossing scheme (the scene refuses the others; this holds for
// every caller).
void check_stepper(const ChainForces& forces, const Stepper& stepper) {
  if (!forces.general_kernel() || stepper.traits().general_kernels) return;
  throw Error("the " + std::string(stepper.name()) +
              " stepper (transitions inside its step) is written for chains of "
              "nearest-neighbour springs without dashpots; this model needs rk2, rk4 or verlet "
              "with transitions at the step");
}
}  // namespace

EventEngine::EventEngine(const ChainForces& forces, Stepper& stepper, double dt, ChainState state)
    : forces_(forces),
      stepper_(stepper),
      dt_(dt),
      st_(std::move(state)),
      pad_(forces.params().pad_moves()),
      active_(forces, margin_for(forces, stepper), pad_),
      ledger_(forces.n()),
      paths_{&replay_, &cluster_, &stencil_, &general_} {
  check_model(forces.params());
  check_stepper(forces, stepper);
  std::fill(st_.mobile.begin(), st_.mobile.end(), 0.0);
  std::fill(st_.wd.begin(), st_.wd.end(), 0.0);
  st_.xd = 0;
  st_.recompute_sum_w();
  if (pad_) st_.x = forces_.pad_equilibrium(st_.sum_w, st_.s);
  active_.rebuild_tree(st_);
}

EventEngine::EventEngine(const ChainForces& forces, Stepper& stepper, double dt,
                         const EngineSnapshot& saved)
    : forces_(forces),
      stepper_(stepper),
      dt_(dt),
      st_(saved.state),
      pad_(forces.params().pad_moves()),
      active_(forces, margin_for(forces, stepper), pad_),
      ledger_(forces.n()),
      paths_{&replay_, &cluster_, &stencil_, &general_} {
  check_model(forces.params());
  check_stepper(forces, stepper);
  if (st_.n() != forces.n())
    throw Error("checkpoint: it holds " + std::to_string(st_.n()) + " blocks, the scene has " +
                std::to_string(forces.n()));
  ledger_.set_counters(saved.counters);
  active_.rebuild_tree(st_);
}

void EventEngine::add_path(std::unique_ptr<RelaxationPath> path) {
  paths_.insert(paths_.end() - 1, path.get());
  added_.push_back(std::move(path));
}

void EventEngine::check_model(const ModelParams& p) {
  check_law_drives_events(p);
  // The relaxation's fast paths (the lone slip's closed form, the held-range and cluster
  // kernels) have no block damping, and with the substrate frozen an event has no sliding
  // state for the damping to be measured from: it is a continuous runs' effect.
  if (p.rayleigh_alpha != 0 || p.rayleigh_beta != 0)
    throw Error("model.rayleigh_alpha = " + format_real(p.rayleigh_alpha) +
                ", model.rayleigh_beta = " + format_real(p.rayleigh_beta) +
                ": Rayleigh block damping applies in continuous runs only (drive.mode = "
                "continuous); event runs need both 0");
}

double EventEngine::worst_stuck_excess() const {
  const double a = anchor(), thr = forces_.friction().threshold;
  double worst = -HUGE_VAL;
  for (int j = 0; j < forces_.n(); ++j) {
    if (st_.mobile[j] != 0.0) continue;
    const double f = forces_.spring_force(st_.w.data(), j, a);
    worst = std::max(worst, (forces_.friction().backslip ? std::abs(f) : f) - thr);
  }
  return worst;
}

void EventEngine::set_sliding(int j) {
  st_.mobile[j] = 1.0;
  st_.wd[j] = 0.0;
  st_.dir[j] = std::copysign(1.0, forces_.holding_force(st_.w.data(), st_.wd.data(), j, anchor()));
  active_.cover(j);
}

void EventEngine::release(int j) {
  ledger_.note_release(j, st_.w[j]);
  set_sliding(j);
}

double EventEngine::load_to_failure(EventRecord& e) {
  // Jump the substrate until the most loaded block sits at the threshold.
  const ModelParams& p = forces_.params();
  if (pad_ && ledger_.counters().events % kResumEvery == 0) st_.recompute_sum_w();
  const int trigger = active_.tree().argmax();
  const double f_max = active_.tree().max() + p.k_p * anchor();
  const double ds = std::max(0.0, (forces_.friction().threshold - f_max) / p.loading_rate());
  st_.s += ds;
  if (pad_) st_.x = forces_.pad_equilibrium(st_.sum_w, st_.s);
  ledger_.open(e);
  e.load = st_.s;
  e.trigger = trigger;
  st_.t = 0;
  ledger_.add_sliding();
  release(trigger);
  return st_.x;
}

void EventEngine::relax_step(Relaxation& rx) {
  PathReport report;
  const double book = ledger_.dissipated();
  rx.steps = ledger_.event_steps();
  for (RelaxationPath* path : paths_)
    if (path->advance(rx, report)) {
      report.path = path->name();
      break;
    }
  report.work = ledger_.dissipated() - book;
  if (observer_) observer_(report);
  ledger_.apply(report, st_, [&](int j) { set_sliding(j); });
  if (pad_) query_tree_failures();
  if (!std::isfinite(report.max_speed)) check_finite();
  ledger_.end_of_step(report.stick_time, st_.t, dt_);
  const std::int64_t steps = ledger_.event_steps();
  if (steps % kShrinkEvery == 0) active_.shrink(st_);
  if (steps > max_steps_per_event) {
    char msg[300];
    std::snprintf(msg, sizeof msg,
                  "event %lld did not end after %lld steps (time %.6g): check integrator.dt "
                  "and the scene (the bound is run.max_steps_per_event)",
                  static_cast<long long>(ledger_.counters().events), static_cast<long long>(steps),
                  st_.t);
    throw Error(msg);
  }
}

EventRecord EventEngine::next_event() {
  EventRecord e;
  const double x0 = load_to_failure(e);
  Relaxation rx{forces_, stepper_, stepper_.traits(),    dt_,
                st_,     active_,  ledger_.dissipated(), pad_};
  rx.trigger = e.trigger;
  rx.max_steps = max_steps_per_event;
  rx.replay = lone_slip_path;
  rx.cluster = cluster_path;
  rx.held_ranges = held_ranges_path;
  rx.stencil = stencil_path;
  for (;;) {
    while (ledger_.sliding() > 0) relax_step(rx);
    if (!pad_ || !pad_phase()) break;
  }
  active_.uncover_all(st_);
  ledger_.close(e, forces_, st_, x0);
  return e;
}

bool EventEngine::query_tree_failures() {
  // Stuck, uncovered blocks feel only the pad's motion; ask the tree who broke (the
  // transition rules' far-block test, which the cluster kernels apply too).
  const double kp = forces_.params().k_p;
  bool any = false;
  for (;;) {
    const int side = transition::far_failure(forces_.friction(), kp, active_.tree().max(),
                                             active_.tree().min(), anchor());
    if (side == 0) break;
    release(side > 0 ? active_.tree().argmax() : active_.tree().argmin());
    ledger_.add_sliding();
    any = true;
  }
  return any;
}

bool EventEngine::pad_phase() {
  // Every block is stuck: m_x xi'' + c_p xi' + K xi = 0 about the rest position.
  active_.uncover_all(st_);
  const ModelParams& p = forces_.params();
  const double thr = forces_.friction().threshold;
  const double K = p.k_p0 + p.n * p.k_p;
  const double x_eq = forces_.pad_equilibrium(st_.sum_w, st_.s);
  const DampedOscillator osc(p.m_x, p.c_p, K, st_.x - x_eq, st_.xd);
  // Block j breaks when x crosses hi (or lo, for laws with backslip).
  const double hi = (thr - active_.tree().max()) / p.k_p - st_.s;
  const double lo =
      forces_.friction().backslip ? (-thr - active_.tree().min()) / p.k_p - st_.s : -HUGE_VAL;
  const double margin = std::min(hi - x_eq, x_eq - lo);
  auto breaks = [&](double t) {
    const double x = x_eq + osc.position(t);
    return x > hi || x < lo;
  };
  const double dt = osc.resolution();
  // The pad's energy about its rest position; what it loses here is the damper's work.
  auto pad_energy = [&](double xi, double v) { return 0.5 * (p.m_x * v * v + K * xi * xi); };
  const double e_start = pad_energy(st_.x - x_eq, st_.xd);
  double t = 0;
  // Walk the closed-form solution until its envelope can no longer reach either level.
  for (std::int64_t i = 0; osc.bound_after(t) >= margin && i < 10'000'000; ++i) {
    if (!breaks(t + dt)) {
      t += dt;
      continue;
    }
    double a = t, b = t + dt;
    for (int k = 0; k < 200 && b - a > 1e-13 * (1.0 + b); ++k) {
      const double m = 0.5 * (a + b);
      (breaks(m) ? b : a) = m;
    }
    st_.x = x_eq + osc.position(b);
    st_.xd = osc.velocity(b);
    st_.t += b;
    ledger_.dissipated() += e_start - pad_energy(osc.position(b), st_.xd);
    // The located block fails now, even if at b its force rounds to the threshold itself.
    release(st_.x > hi ? active_.tree().argmax() : active_.tree().argmin());
    ledger_.add_sliding();
    query_tree_failures();
    return true;
  }
  st_.x = x_eq;
  st_.xd = 0;
  ledger_.dissipated() += e_start;
  return false;
}

void EventEngine::check_finite() const {
  for (const Range& r : active_.ranges())
    for (int j = r.lo; j < r.hi; ++j)
      if (!std::isfinite(st_.w[j]) || !std::isfinite(st_.wd[j])) {
        char msg[300];
        std::snprintf(
            msg, sizeof msg,
            "non-finite state at block %d, time %.9g into event %lld: the integration is unstable "
            "(reduce integrator.dt)",
            j, st_.t, static_cast<long long>(ledger_.counters().events + 1));
        throw Error(msg);
      }
}

}  // namespace bkq
