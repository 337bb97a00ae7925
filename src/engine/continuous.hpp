// Continuous driving (SPEC §3, thesis ch. 4): the substrate moves on its schedule and
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

class ContinuousDriver {
 public:
  ContinuousDriver(const ChainForces& forces, Stepper& stepper, const Substrate& substrate,
                   ChainState state, double dt);

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

 private:
  void start_episode(int trigger);

  const ChainForces& forces_;
  Stepper& stepper_;
  Substrate substrate_;
  ChainState st_;
  double dt_;
  Range all_;
  std::vector<double> wd_old_;
  int sliding_ = 0;

  // Episode bookkeeping: w at the episode start for each block, which blocks slid.
  bool in_episode_ = false;
  std::vector<double> w_start_;
  std::vector<unsigned char> slid_;
  EventRecord episode_;
  double episode_t0_ = 0, episode_x0_ = 0;
  std::int64_t episodes_ = 0;
  std::optional<EventRecord> finished_;
};

}  // namespace bkq
