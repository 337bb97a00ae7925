// The event-driven rate-and-state engine: between events every block follows its closed form
// (model/rsf_nucleation.hpp) under the loader's stressing rate k V_pl; the next block to reach
// the hand-over speed V_h is the top of an indexed heap of those times, and an event changes
// only the entries of the blocks it touched. At that time the whole grid is handed to the
// cycle integrator (engine/rsf_cycle.hpp: the scene's dynamics, quasi-dynamic or inertial,
// the full aging law), which runs until the seismic detector (engine/rsf_events.hpp) has
// closed its events and every block is below V_h again and where its closed form holds (a
// velocity-weakening block is also handed over when V theta/D_c nears 1, where neither the
// locked nor the nucleation form does, and kept until it is well below or above 1; a
// velocity-strengthening one goes back near steady state or locked); each block then goes back to
// its closed form from the integrator's slip rate and state, both kept as they are (the elastic
// stress is the law's at those values, as the closed form's quasi-static balance has it), except
// that a velocity-strengthening block above steady state enters its steady-state phase at
// constant friction (rsf::onto_steady_state: its stress kept, theta at D_c/V).
//
// Blocks alone (with the active-block integration, RsfLoader::integrate_alone): a velocity-
// weakening block that neither nucleates (V theta/D_c >= kOmegaOut) nor is locked and slow
// (V theta/D_c < kOmegaBack below kSlowLocked V_pl) is integrated on its own below v_alone
// (engine/rsf_alone.hpp: its full aging law under the loader's stressing rate, k_eff unloading
// it, its neighbours' creep in quanta as in the closed forms), with a forecast of its steps
// from its last set() instead of a closed form; it is due at v_alone and its clocks are the
// forecast's (the quantum, the closed forms' domains entered at a step's end, the forecast's
// horizon). A locked block reaching kOmegaIn or kSlowLocked V_pl goes over to it (a change of
// phase, not due). Without it such blocks join the integrator near steady state (the whole
// grid's rule), where the active-block integration carries them at its events' step sizes.
//
// Between events the neighbours' creep reaches a block in quanta: each block's closed-form
// slip is passed on as stress steps to its neighbours whenever it reaches rsf.creep_quantum
// (RsfLoader::sync), and every block is synced when an event starts.
//
// Approximations (stated in docs/explanation/rate-and-state.md):
//   - between events a block is loaded by the plate and by its neighbours' creep in quanta of
//     slip q (the stress arrives late by up to one quantum's worth, k_c q); the locked
//     phase's slip is left out; a block's own creep unloads it through
//     k_eff = k + its coupling springs' sum, in H = b/D_c - k_eff/sigma;
//   - the closed forms' phases (healing while V theta/D_c < 1, then nucleation with
//     V theta/D_c >> 1, or steady state for a > b) and their quasi-static balance
//     (eta V << a sigma below V_h).
#pragma once

#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "engine/event_record.hpp"
#include "engine/rsf_active.hpp"
#include "engine/rsf_alone.hpp"
#include "engine/rsf_cycle.hpp"
#include "model/rsf_nucleation.hpp"

namespace bkq {

// A binary min-heap of one time per index 0..n-1, ordered by time and then by index (so the
// order never depends on the history of updates); set() moves one entry, O(log n).
class IndexedMinHeap {
 public:
  explicit IndexedMinHeap(int n = 0);
  void set(int i, double time);
  int top() const { return heap_[0]; }
  double top_time() const { return time_[heap_[0]]; }
  double time(int i) const { return time_[i]; }
  int size() const { return static_cast<int>(heap_.size()); }
  // Every parent before its children (what the tests check).
  bool valid() const;

 private:
  bool before(int a, int b) const { return time_[a] < time_[b] || (time_[a] == time_[b] && a < b); }
  void place(int slot, int i) {
    heap_[slot] = i;
    pos_[i] = slot;
  }
  void up(int slot);
  void down(int slot);
  std::vector<int> heap_, pos_;
  std::vector<double> time_;
};

// Every block's closed form, its time to the hand-over speed and its creep quanta. A block's
// closed-form slip since its last sync is its unsynced slip; a sync moves the block's position
// by it and gives each coupled neighbour i the stress step k_ji times the slip passed on
// (rsf::stress_step: V_i times exp(dtau/(a sigma)) at theta kept, or along steady state; its clocks
// recomputed). The block's own unloading k_eff is inside its H, so only neighbours change. The
// quanta are centred: a block that has passed on exactly its slip (lead 0) is synced when its
// unsynced slip reaches q/2 and passes on q, half a quantum ahead; after that each sync comes at q
// and passes on q. The stress its neighbours see then lies within k q/2 of the continuous one, on
// both sides (error O(q^2) on average, not O(q)), and a settling sync (each event's start) passes
// on the slip less the lead, so that the stress passed on equals the slip. Each block's heap entry
// is the earlier of its two times (V_h, or its next quantum).
class RsfLoader {
 public:
  // creep_quantum: q [m], > 0; +inf: the creep is never passed on (left out, as in RSQSim).
  RsfLoader(const RsfModel& m, double v_handover, double creep_quantum);
  int n() const { return static_cast<int>(slider_.size()); }
  const rsf::Slider& slider(int j) const { return slider_[j]; }
  // Block j's state at time t, not before its last set().
  rsf::SliderState state_at(int j, double t) const;
  // Block j is in state x at time t with nothing unsynced: its closed form restarts there.
  void set(int j, double t, rsf::SliderState x);
  // The same with `unsynced` metres of slip not yet synced and a lead (a checkpoint's).
  void set(int j, double t, rsf::SliderState x, double unsynced, double lead);
  // A shear-stress step dtau on block j at time t (its unsynced slip kept).
  void stress_step(int j, double t, double dtau);
  // A sudden step (an integrated event's slip passed on): the direct effect only, V times
  // exp(dtau/(a sigma)) at theta kept, in every phase; a barrier it takes away from steady state
  // is then due to the integrator, which evolves its theta.
  void sudden_stress_step(int j, double t, double dtau);
  // Block j's closed-form slip since its last sync, at time t.
  double unsynced(int j, double t) const;
  // Moves block j's position by its unsynced slip at time t and passes a slip on to its
  // neighbours as stress steps: the quantum's (centred), or, settling, the slip less the lead.
  // Returns the slip passed on.
  double sync(int j, double t, bool settle = false);
  // The slip block j has passed on beyond its position (0 or q/2).
  double lead(int j) const { return lead_[j]; }
  // Moves block j's position by an integrated slip (an event's).
  void move(int j, double slip) { position_[j] += slip; }
  double position(int j) const { return position_[j]; }
  void set_position(int j, double x) { position_[j] = x; }  // a checkpoint's
  // The next block to reach V_h or its quantum, or to change phase, and when; whether it is
  // the quantum; whether it is a change of phase (the caller then calls rephase()).
  int next_block() const { return heap_.top(); }
  double next_time() const { return heap_.top_time(); }
  double time_of(int j) const { return heap_.time(j); }  // block j's entry
  bool next_is_quantum() const { return clock_[heap_.top()] == kQuantum; }
  bool next_is_phase() const { return clock_[heap_.top()] == kPhase; }
  // The next block's form restarts at its time: a locked block nearing steady state is taken
  // alone, a block taken alone goes back to a closed form (or its forecast goes on).
  void rephase();

  // Velocity-weakening blocks that nucleate on their own are integrated alone near steady
  // sliding (engine/rsf_alone.hpp: V theta/D_c from kOmegaBack to kOmegaOut) below
  // v_alone, where they are due (instead of joining the integrator there at V_h); tolerance:
  // the integrator's. Off until called (they are due near steady state, as the whole grid
  // needs them).
  void integrate_alone(double v_alone, double tolerance);
  bool alone(int j) const { return in_alone_[j] != 0; }  // being integrated alone now
  double v_alone() const { return v_alone_; }            // 0: off
  double alone_tolerance() const { return alone_.tolerance(); }
  double ln_v_alone() const {  // -inf: off
    return v_alone_ > 0 ? alone_limits_.ln_v_target : -std::numeric_limits<double>::infinity();
  }
  // A block's forecasts alone start with the step size the last one proposed at its end (0:
  // none, the forecast's own first step). The first step block j's current forecast tried is part
  // of a snapshot: set before the block's set(), its forecast takes the same steps again.
  double alone_first_step(int j) const { return h_first_[j]; }
  void set_alone_first_step(int j, double h) { h_hint_[j] = h; }
  long long alone_steps() const { return alone_.steps(); }
  void set_alone_steps(long long n) { alone_.set_steps(n); }  // a checkpoint's
  double ln_v_handover() const { return ln_vh_; }
  double creep_quantum() const { return quantum_; }
  // Block j's steady sliding is unstable on its own springs: near V theta/D_c = 1 it is left to
  // the integrator.
  bool nucleates_alone(int j) const { return nucleates_alone_[j] != 0; }
  // Where block j's closed form starts (its last set()).
  double t_ref(int j) const { return t_ref_[j]; }
  const rsf::SliderState& x_ref(int j) const { return x_ref_[j]; }

  // Block j is with the active-block integrator (engine/rsf_active.hpp): its heap entry is
  // parked at +inf, and the stress steps its neighbours' syncs would give it are summed
  // instead; release() ends that and returns the sum (the caller set()s the block, then
  // passes the sum on as a stress step).
  void hold(int j);
  double release(int j);
  // The stress summed for held block j so far, and the sum restarted (the block stays held).
  double take_held_stress(int j);
  bool held(int j) const { return !held_.empty() && held_[j] != 0; }

 private:
  void rebase(int j, double t);  // the closed form restarts at t, its slip kept as unsynced
  void schedule(int j);

  std::vector<rsf::Slider> slider_;
  std::vector<char> nucleates_alone_;  // handed over near V theta/D_c = 1
  RsfNeighbours nb_;
  std::vector<double> t_ref_;
  std::vector<rsf::SliderState> x_ref_;
  std::vector<double> unsynced_, position_;  // slip before t_ref not synced; synced slip
  std::vector<double> lead_;                 // slip passed on less the synced slip
  enum Clock : char { kDue, kQuantum, kPhase };
  std::vector<char> clock_;  // what each block's heap time is
  IndexedMinHeap heap_;
  // Blocks integrated alone: the forecast from their last set (its steps), by block.
  double v_alone_ = 0;                     // 0: off
  rsf::AloneSlider::Limits alone_limits_;  // all but the amount (the next quantum's)
  mutable rsf::AloneSlider alone_{1e-8};   // the tolerance: integrate_alone's
  std::vector<std::vector<rsf::AloneSlider::Point>> path_;
  std::vector<char> in_alone_;
  std::vector<double> h_hint_;        // by block: the next forecast's first step
  std::vector<double> h_first_;       // by block: the current forecast's
  double ln_vh_, ln_slow_, quantum_;  // ln_slow_: ln(kSlowLocked V_pl), the locked form's limit
  std::vector<char> held_;            // empty until the first hold()
  std::vector<double> held_stress_;   // stress steps summed for held blocks [Pa]
};

class RsfEventEngine {
 public:
  // Starts at t = 0 with slip rates v and states theta (one value, or one per block).
  // creep_quantum: the loader's q [m] (+inf: no creep passed on between events).
  RsfEventEngine(RsfModel m, double tolerance, double v_threshold, double v_handover,
                 double creep_quantum, const std::vector<double>& v,
                 const std::vector<double>& theta);

  // The next seismic event's record, or none when t_end comes first (then t() = t_end).
  std::optional<EventRecord> next(double t_end);

  double t() const { return t_; }
  std::int64_t events() const { return events_; }
  std::int64_t integrations() const { return integrations_; }  // hand-overs to the integrator
  std::int64_t steps() const { return steps_; }                // their accepted steps
  std::int64_t syncs() const { return syncs_; }                // creep quanta passed on
  const RsfLoader& loader() const { return loader_; }
  const RsfModel& model() const { return m_; }
  // Records of the last integration not yet returned (a checkpoint is taken only at none).
  bool pending() const { return !pending_.empty(); }

  // How an event is integrated: the whole grid (the default), or its active blocks only
  // (engine/rsf_active.hpp), quasi-dynamic scenes only: inertial ones stay with the whole
  // grid (the active-block path's inertial events are not checked). The choice is not part
  // of a snapshot.
  void set_active_blocks(bool on) { active_blocks_ = on; }
  // With active blocks: groups that share no spring integrated apart (RsfActiveIntegration::
  // set_groups). Not part of a snapshot (the scene's).
  void set_groups(bool on) { groups_ = on; }
  bool groups() const { return groups_; }
  // With active blocks: velocity-weakening blocks away from their closed forms are integrated
  // alone below v_alone (RsfLoader::integrate_alone) instead of joining the integration at
  // V_h; 0 until called. tolerance: of their integration (0: the integrator's). Not part of a
  // snapshot (the scene's).
  void set_alone_speed(double v_alone, double tolerance = 0) {
    loader_.integrate_alone(v_alone, tolerance > 0 ? tolerance : tol_);
  }
  double alone_speed() const { return loader_.v_alone(); }
  double alone_tolerance() const { return loader_.alone_tolerance(); }
  bool active_blocks() const { return active_blocks_ && m_.dynamics == RsfDynamics::QuasiDynamic; }
  // Active blocks summed over the integrations' steps (the mean active set is this / steps()
  // over the steps of active-block integrations); 0 for the whole grid.
  std::int64_t active_block_steps() const { return active_block_steps_; }

  // The state between two events, as numbers (a checkpoint's), and back; the records of the
  // last integration not yet returned are part of it (a finished run's final state may fall
  // between them).
  std::vector<double> snapshot() const;
  void restore(const std::vector<double>& s);

 private:
  void integrate_event(double t0, double t_end);
  void integrate_active(int first, double t0, double t_end);

  RsfModel m_;
  double tol_, v_th_;
  RsfLoader loader_;
  double t_ = 0;
  std::int64_t events_ = 0, integrations_ = 0, steps_ = 0, syncs_ = 0;
  std::deque<EventRecord> pending_;
  bool active_blocks_ = false, groups_ = false;
  std::int64_t active_block_steps_ = 0;
  std::unique_ptr<RsfActiveIntegration> active_;
};

}  // namespace bkq
