// CPU time of the calling thread, in seconds: what the side-by-side benchmarks compare, so
// that another process on the shared machine slows neither side's figure.
#pragma once

#include <time.h>

namespace bkq::bench {

inline double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace bkq::bench
