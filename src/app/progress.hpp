// Progress on long runs: on a terminal a status line on stderr refreshed a few times a
// second (done, rate, ETA); otherwise one line about every 10 s; nothing when quiet.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace bkq {

class Progress {
 public:
  Progress(bool quiet, std::string what, double total);
  // Cheap to call often: it looks at the clock only every few calls.
  void update(double done) {
    if (quiet_ || (++calls_ & 255) != 0) return;
    report(done, false);
  }
  void finish(double done);

 private:
  void report(double done, bool final);

  bool quiet_, tty_;
  std::string what_;
  double total_;
  std::uint64_t calls_ = 0;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace bkq
