// When a run writes a checkpoint: every run.checkpoint_events events (counted over the
// whole run, transient included; a continuous run counts its slip episodes) or
// run.checkpoint_seconds of wall time, whichever comes first. The first checkpoint by
// time comes early, kFirstCheckpointSeconds after the start (or the period, if shorter),
// so a SIGKILL early in a long run loses at most that much. The run writes it (with every
// observer's state); this observer only asks. Attached when either interval is set.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>

#include "app/observers/observer.hpp"

namespace bkq {

// Wall seconds from a session's start to its first checkpoint (when checkpoints by time
// are on): after that the period run.checkpoint_seconds applies.
inline constexpr double kFirstCheckpointSeconds = 30;

class CheckpointTimer : public RunObserver {
 public:
  // Seconds on a monotonic clock (a test passes its own).
  using Seconds = std::function<double()>;
  static double steady_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }

  CheckpointTimer(std::function<void()> write, std::int64_t every_events, double every_seconds,
                  Seconds now = steady_seconds)
      : write_(std::move(write)),
        every_events_(every_events),
        every_seconds_(every_seconds),
        now_(std::move(now)) {}

  void on_start() override {
    last_ = now_();
    first_ = true;
  }
  void on_advance(const Advance& a) override {
    // A continuous run advances every time step, mostly without a new episode.
    const bool by_count =
        every_events_ > 0 && a.events != last_events_ && a.events % every_events_ == 0;
    last_events_ = a.events;
    // The clock is read every kClockStride advances only (a continuous time step can be
    // shorter than reading it).
    bool by_time = false;
    if (every_seconds_ > 0 && ++calls_ % kClockStride == 0) {
      const double period = first_ && kFirstCheckpointSeconds < every_seconds_
                                ? kFirstCheckpointSeconds
                                : every_seconds_;
      by_time = now_() - last_ >= period;
    }
    if (by_count || by_time) write_();
  }
  // Any checkpoint (also one written on a signal or a failure) restarts the clock.
  void on_checkpoint(Checkpoint&) override {
    last_ = now_();
    first_ = false;
  }

  static constexpr std::int64_t kClockStride = 16;

 private:
  std::function<void()> write_;
  std::int64_t every_events_;
  double every_seconds_;
  Seconds now_;
  std::int64_t last_events_ = -1, calls_ = 0;
  double last_ = 0;
  bool first_ = true;
};

}  // namespace bkq
