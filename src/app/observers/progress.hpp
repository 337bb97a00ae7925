// The progress line of long runs, as an observer: on a terminal a status line on stderr
// refreshed a few times a second (done, rate, ETA); otherwise one line about every 10 s.
// Attached unless the run is quiet.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "app/observers/observer.hpp"

namespace bkq {

// One status line for `total` units of work.
class Progress {
 public:
  Progress(std::string what, double total);
  // Cheap to call often: it looks at the clock only every few calls.
  void update(double done) {
    if ((++calls_ & 255) != 0) return;
    report(done, false);
  }
  void finish(double done);

 private:
  void report(double done, bool final);

  bool tty_;
  std::string what_;
  double total_;
  std::uint64_t calls_ = 0;
  std::chrono::steady_clock::time_point start_, last_;
};

// A Progress line per phase of the run.
class ProgressLine : public RunObserver {
 public:
  void on_phase(const Phase& p) override {
    start_ = p.start;
    line_.emplace(p.what, p.total - p.start);
  }
  void on_advance(const Advance& a) override { line_->update(a.done - start_); }
  void on_phase_end(const Advance& a) override {
    line_->finish(a.done - start_);
    line_.reset();
  }

 private:
  std::optional<Progress> line_;
  double start_ = 0;
};

}  // namespace bkq
