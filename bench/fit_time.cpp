// The end-of-run fit on its own (goal 5 of the performance issue): reads a run folder's
// histogram.csv and times the fit `bkquake run` does at its end (fit_histogram with the
// default options, automatic window) over REPEAT repetitions, in CPU time. Prints the
// seconds per fit and the fitted window and b, so a fit that was optimised away would show;
// bench/output_share.sh divides the time by a whole run's.
//   build/fit_time RUN_DIR [REPEAT=20]
#include <time.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "io/histogram_csv.hpp"
#include "stats/gutenberg_richter.hpp"

namespace {

double cpu_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 2 || argc > 3) {
      std::fprintf(stderr, "usage: fit_time RUN_DIR [REPEAT]\n");
      return 2;
    }
    const std::filesystem::path dir = argv[1];
    const int repeat = argc > 2 ? std::stoi(argv[2]) : 20;
    const bkq::MagnitudeHistogram h = bkq::read_histogram_csv(dir / "histogram.csv", 0, 0);
    bkq::GrFit fit;
    const double t0 = cpu_seconds();
    for (int i = 0; i < repeat; ++i) fit = bkq::fit_histogram(h, std::nullopt, std::nullopt);
    const double per_fit = (cpu_seconds() - t0) / repeat;
    std::printf(
        "fit_time: %.6f s per fit (%d fits, %lld events, window [%.2f, %.2f), b_mle %.17g)\n",
        per_fit, repeat, static_cast<long long>(h.events()), fit.mu_min, fit.mu_max, fit.b_mle);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fit_time: %s\n", e.what());
    return 2;
  }
}
