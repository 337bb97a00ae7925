// When a run writes a checkpoint: every run.checkpoint_events events (counted over the
// whole run, transient included; a continuous run counts its slip episodes) or
// run.checkpoint_seconds of wall time, whichever comes first. The run writes it (with
// every observer's state); this observer only asks. Attached when either interval is set.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>

#include "app/observers/observer.hpp"

namespace bkq {

class CheckpointTimer : public RunObserver {
 public:
  using Clock = std::chrono::steady_clock;
  CheckpointTimer(std::function<void()> write, std::int64_t every_events, double every_seconds)
      : write_(std::move(write)), every_events_(every_events), every_seconds_(every_seconds) {}

  void on_start() override { last_ = Clock::now(); }
  void on_advance(const Advance& a) override {
    // A continuous run advances every time step, mostly without a new episode.
    const bool by_count =
        every_events_ > 0 && a.events != last_events_ && a.events % every_events_ == 0;
    last_events_ = a.events;
    const bool by_time =
        every_seconds_ > 0 &&
        std::chrono::duration<double>(Clock::now() - last_).count() >= every_seconds_;
    if (by_count || by_time) write_();
  }
  // Any checkpoint (also one written on a signal or a failure) restarts the clock.
  void on_checkpoint(Checkpoint&) override { last_ = Clock::now(); }

 private:
  std::function<void()> write_;
  std::int64_t every_events_;
  double every_seconds_;
  std::int64_t last_events_ = -1;
  Clock::time_point last_ = Clock::now();
};

}  // namespace bkq
