// Continuous driving (Ferre 2018 ch. 4): the substrate moves on its schedule and
// every block and the pad are integrated at finite speed. Slip episodes — maximal
// stretches of time with at least one block sliding — form an event catalogue, so runs at
// small speed can be compared with the event-driven engine.
#pragma once

#include <optional>

#include "engine/event_record.hpp"
#include "integrate/stepper.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"

namespace bkq {

// The energy balance of a continuous run: the energy of the chain and pad (springs,
// kinetic in the lab frame) at the start, the work done on them by the substrate and what
// friction and the dampers dissipated, both summed per step by the trapezoidal rule. The
// substrate acts through friction only, whose total force on the chain follows from the
// chain's momentum balance (sum F_f = d/dt sum m u' + k_p sum (u_j - x) + c_u sum u',
// plus the Rayleigh damping's alpha_M m_u sum u' + beta_K k_p sum (u'_j - x')), so only
// the sliding blocks' friction is evaluated; the dissipation includes u'^T C u'. An exact
// integration ends with E - e0 = work - dissipated; residual() is the relative error.
struct EnergyBalance {
  double e0 = 0, work = 0, dissipated = 0;
  // (E_end - e0 - work + dissipated) / dissipated; 0 while nothing was dissipated.
  double residual(double e_end) const {
    return dissipated > 0 ? (e_end - e0 - work + dissipated) / dissipated : 0.0;
  }
};

// What a driver needs to continue exactly where it stopped, between two steps: the chain
// state, the slip episode under way and what the stepper carries from step to step.
struct ContinuousSnapshot {
  ChainState state;
  int sliding = 0;
  bool in_episode = false;
  std::vector<double> w_start;      // w at the start of the episode under way
  std::vector<unsigned char> slid;  // blocks that slid in it
  EventRecord episode;              // its record so far
  double episode_t0 = 0, episode_x0 = 0;
  std::int64_t episodes = 0;    // episodes started
  std::vector<double> stepper;  // Stepper::carried_state()
  EnergyBalance energy;
};

class ContinuousDriver {
 public:
  ContinuousDriver(const ChainForces& forces, Stepper& stepper, const Substrate& substrate,
                   ChainState state, double dt);
  // Continues from a snapshot (restoring the stepper's carried state): the steps that
  // follow are those of the driver that was snapshotted, bit for bit. Throws bkq::Error
  // when the snapshot does not fit the chain.
  ContinuousDriver(const ChainForces& forces, Stepper& stepper, const Substrate& substrate,
                   const ContinuousSnapshot& saved, double dt);
  ContinuousSnapshot snapshot() const;

  // One time step followed by the stick/slip transitions.
  void step();

  const ChainState& state() const { return st_; }
  ChainState& state() { return st_; }
  SubstrateState substrate() const { return substrate_.at(st_.t); }
  int sliding() const { return sliding_; }
  // Sum of the pulling-spring forces on the pad, k_p sum_j (u_j - x) ("pad friction").
  double pad_friction() const;
  // Lab-frame block displacement u_j = w_j - s.
  double displacement(int j) const { return st_.w[j] - substrate().s; }

  // A slip episode that ended during the last step, if any.
  std::optional<EventRecord> finished_episode();

  // The run's energy balance so far and the energy now (springs and lab-frame kinetic).
  const EnergyBalance& energy_balance() const { return energy_; }
  double energy() const;

 private:
  // The terms of the balance at the current state: the friction impulse's parts (lab
  // momentum of the blocks, pulling springs' and block dampers' total force) and the
  // dissipation rate.
  struct Power {
    double momentum = 0, force = 0, dissipation = 0;
  };
  Power power() const;

  void start_episode(int trigger);

  const ChainForces& forces_;
  Stepper& stepper_;
  Substrate substrate_;
  ChainState st_;
  double dt_;
  Range all_;
  std::vector<double> wd_old_;
  int sliding_ = 0;
  // Steppers that locate releases (integrate/located.hpp, adaptive.hpp): blocks released
  // inside a step are taken
  // from the stepper's list (their slip counted from where they broke loose, also when they
  // stuck again before the step ended); see step().
  bool located_releases_ = false;

  // Episode bookkeeping: w at the episode start for each block, which blocks slid.
  bool in_episode_ = false;
  std::vector<double> w_start_;
  std::vector<unsigned char> slid_;
  EventRecord episode_;
  double episode_t0_ = 0, episode_x0_ = 0;
  std::int64_t episodes_ = 0;
  std::optional<EventRecord> finished_;
  EnergyBalance energy_;
  Power power_;  // at the current state
};

}  // namespace bkq
