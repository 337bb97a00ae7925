// An event of the event-driven rate-and-state engine (engine/rsf_loader.hpp) integrated on its
// active blocks only: the cost of a step scales with the blocks that move, not with N.
//
// Active blocks are integrated as the cycle integrator integrates the whole grid (Dormand-
// Prince 5(4) over (slip, ln V, ln theta), the full aging law, the scene's dynamics, the same
// error control); every other block stays with its closed form in the loader. Slip is counted
// from the integration's start in one coordinate per block, held while the block is not active.
//   - An inactive neighbour's slip is held at its value (its spring pulls an active block back
//     with -k_ji V_j, an extra unloading stiffness). Its closed-form creep meanwhile reaches the
//     active block through the loader's quanta, summed while the block is active and passed on
//     as one stress step when it leaves (RsfLoader::hold/release): late by at most the block's
//     active time, k_ji times the neighbour's creep in it (below V_h).
//   - Activation: after every accepted step each inactive neighbour i of an active block gets
//     the stress the active blocks' slip has put on it since its last update, sum k_ij
//     (delta_j - passed_ij), as the direct effect on its closed form, V_i exp(dtau/(a sigma))
//     at constant theta; where that reaches V_h, the stress is passed to it (a stress step), its
//     unsynced creep is settled and it joins the integration from its closed-form state. A
//     block whose own closed form reaches V_h or a creep quantum meanwhile is taken in time
//     order: the steps are clipped at the loader's next time.
//   - Hand-back: a block that passes the engine's hand-back test (at least one step after it
//     joined) goes back to its closed form from its slip rate and state, its position moves by
//     its slip since it joined, the stress summed for it is passed on, and the stress its slip
//     puts on its inactive neighbours (k_ij delta_j less what they have had) is passed to them.
// The integration ends when no block is active and no event is open (or at t_end, where every
// active block goes back). The seismic detector reads the active slots (RsfStepSpan).
// Inertial dynamics: each block's tau0 is set when it joins so that its stress balances its
// friction there (sigma f + eta V), as the cycle integrator does at its start; this is not
// checked against the whole grid, and the engine integrates inertial scenes on the whole grid.
// A velocity-strengthening block whose nucleation form has let theta fall far below steady
// state (V theta/D_c < 1/e) joins at the steady state of its stress (a ln V + b ln theta kept).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "engine/dormand_prince.hpp"
#include "engine/event_record.hpp"
#include "engine/rsf_cycle.hpp"
#include "engine/rsf_events.hpp"

namespace bkq {

class RsfLoader;

class RsfActiveIntegration {
 public:
  RsfActiveIntegration(const RsfModel& m, double tolerance, double v_threshold);

  // What the engine's hand-back test reads, by block: the cycle integrator's accessors for
  // the active blocks (y() and dy() in its layout, slip at j, ln V at n + j, ln theta at 2n + j).
  struct Column {
    const RsfActiveIntegration* a;
    int comp0;  // 0: y, 3: dy
    double operator[](int i) const { return a->value(i, comp0); }
  };
  int n() const { return m_.n(); }
  const RsfModel& model() const { return m_; }
  double t() const { return dp_.t; }
  double slip(int j) const { return dp_.y[3 * slot_[j]]; }
  double ln_v(int j) const { return dp_.y[3 * slot_[j] + 1]; }
  double ln_theta(int j) const { return dp_.y[3 * slot_[j] + 2]; }
  Column y() const { return {this, 0}; }
  Column dy() const { return {this, 3}; }
  double friction_stress(int j) const;
  bool in_event() const { return detector_.in_event(); }

  using HandBack = std::function<bool(const RsfActiveIntegration&, int)>;
  // One integration from block `first` reaching V_h at t0 (absolute times) until no block is
  // active and no event is open, or t_end; the loader keeps the other blocks and gets every
  // block back. Returns the end time; the events are in events(), their times from t0.
  double run(RsfLoader& loader, int first, double t0, double t_end, const HandBack& handed_back);
  const std::vector<EventRecord>& events() const { return events_; }

  std::int64_t accepted() const { return dp_.accepted; }   // steps, all integrations
  std::int64_t slot_steps() const { return slot_steps_; }  // sum of active blocks per step
  std::int64_t activations() const { return activations_; }
  std::int64_t syncs() const { return syncs_; }    // quanta passed on during integrations
  std::int64_t resets() const { return resets_; }  // barriers started at steady state

 private:
  double value(int i, int comp0) const;
  void activate(RsfLoader& loader, int j, double t_abs, double dtau);
  void release(RsfLoader& loader, int j, double t_abs);
  void rebuild();  // the slots' neighbour lists, and the FSAL derivative
  void rhs(double t, const double* y, double* dy);
  double step(double t_max);
  // The stress the active blocks' slip has put on inactive block i since it last had it.
  double owed(int i) const;
  RsfStepSpan span() const;

  RsfModel m_;
  double tol_;
  RsfNeighbours nb_;
  RsfEventDetector detector_;
  // Per block (N): slot or -1, slip coordinate (held while inactive), slip when it joined,
  // the step it joined at, and a stamp for visiting neighbours once.
  std::vector<int> slot_, joined_step_, stamp_;
  std::vector<double> held_, slip_at_join_;
  std::vector<double> passed_;  // per spring e of block i's row: slip of index[e] i has had
  std::vector<int> touched_;    // blocks that joined in this integration
  int stamp_now_ = 0;
  // Per slot: the block, tau0, the state (3 a slot, in dp_ with the stages, the time and the
  // step size).
  std::vector<int> id_;
  std::vector<double> tau0_, v_;
  dopri::Adaptive<> dp_;
  // Per slot, its springs: the neighbour's slot (-1: held) and block, and k.
  std::vector<int> cstart_, cslot_, cblock_;
  std::vector<double> ck_;
  std::int64_t steps_in_run_ = 0;
  std::int64_t slot_steps_ = 0, activations_ = 0, syncs_ = 0, resets_ = 0;
  std::vector<EventRecord> events_;
};

}  // namespace bkq
