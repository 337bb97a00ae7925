// Progress line; see progress.hpp.
#include "app/observers/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace bkq {

Progress::Progress(std::string what, double total)
    : tty_(isatty(STDERR_FILENO) != 0), what_(std::move(what)), total_(total) {
  start_ = last_ = std::chrono::steady_clock::now();
}

void Progress::report(double done, bool final) {
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (!final && since < (tty_ ? 0.25 : 10.0)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? done / elapsed : 0;
  const double eta = rate > 0 ? (total_ - done) / rate : 0;
  std::fprintf(stderr, "%s%s %.0f/%.0f (%.1f%%), %.4g/s, elapsed %.0f s, ETA %.0f s%s",
               tty_ ? "\r" : "", what_.c_str(), done, total_,
               total_ > 0 ? 100.0 * done / total_ : 100.0, rate, elapsed, final ? 0.0 : eta,
               tty_ && !final ? "   " : "\n");
  std::fflush(stderr);
}

void Progress::finish(double done) {
  if (tty_ || std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() > 10)
    report(done, true);
}

}  // namespace bkq
