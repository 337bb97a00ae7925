// Wall-clock seconds for the run loops: since a time point, and a run's total over the
// sessions a resume joins (the seconds before it, kept in the checkpoint, plus this
// session's).
#pragma once

#include <chrono>

namespace bkq {

using WallClock = std::chrono::steady_clock;

inline double seconds_since(WallClock::time_point t0) {
  return std::chrono::duration<double>(WallClock::now() - t0).count();
}

// Starts with the session (the loop that holds it is built).
class RunWall {
 public:
  // The wall seconds of the sessions before this one (0 on a fresh run).
  void set_before(double seconds) { before_ = seconds; }
  double total() const { return before_ + seconds_since(session_t0_); }

 private:
  WallClock::time_point session_t0_ = WallClock::now();
  double before_ = 0;
};

}  // namespace bkq
