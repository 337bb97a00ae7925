// The events since the last mainshock, for the statistics that look back from a mainshock
// (foreshocks, the Mogi picture, b before mainshocks). A ring buffer of at most `capacity`
// events: memory stays flat however long the catalogue; when a quiet stretch between two
// mainshocks holds more events, the window starts at the oldest one kept (window_start()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "stats/seismicity/quake.hpp"

namespace bkq::seis {

struct PastEvent {
  double t;
  double mu;
  int trigger;
  int trigger_row;
  bool operator==(const PastEvent&) const = default;
};

class Lookback {
 public:
  static constexpr std::size_t kDefaultCapacity = 1'000'000;
  explicit Lookback(std::size_t capacity = kDefaultCapacity) : cap_(capacity) {}

  // After the statistics have seen q: a mainshock empties the buffer and starts a window.
  void add(const Quake& q) {
    if (!started_) {
      start_ = q.t;
      started_ = true;
    }
    if (q.mainshock) {
      buf_.clear();
      head_ = 0;
      start_ = q.t;
      return;
    }
    if (buf_.size() < cap_) {
      buf_.push_back({q.t, q.mu, q.trigger, q.trigger_row});
      return;
    }
    start_ = buf_[head_].t;  // the oldest is dropped: the window now starts there
    buf_[head_] = {q.t, q.mu, q.trigger, q.trigger_row};
    head_ = (head_ + 1) % cap_;
  }
  // The window's start: the last mainshock, the first event, or the oldest event dropped.
  double window_start() const { return start_; }
  bool started() const { return started_; }
  std::size_t size() const { return buf_.size(); }
  template <class F>
  void for_each(F&& f) const {
    for (std::size_t i = 0; i < buf_.size(); ++i) f(buf_[(head_ + i) % buf_.size()]);
  }

 private:
  std::size_t cap_;
  std::vector<PastEvent> buf_;
  std::size_t head_ = 0;
  double start_ = 0;
  bool started_ = false;
};

}  // namespace bkq::seis
