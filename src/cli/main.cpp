// The bkquake program: dispatches on the first word to a subcommand (commands.hpp) and
// turns errors into one line on stderr and an exit status: bad input (bkq::Error) exits 2,
// anything else is a bug and exits 1.
#include <unistd.h>

#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "bkquake_version.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/format.hpp"

namespace {

const char* kUsage =
    R"(bkquake: earthquake statistics for Burridge-Knopoff spring-block chains and the BK-Pad model

Usage:
  bkquake run [SCENE] [--set section.key=value]... [--out DIR] [--resume] [--force]
  bkquake run --dump-defaults      print a commented scene with every key at its default
  bkquake fit CATALOG.csv [--mu-min A] [--mu-max B] [--bin-width W] [--blocks N] [--json OUT]
  bkquake merge RUN_DIR... --out DIR [--force]
  bkquake accuracy [SCENE] [--set section.key=value]... [--out DIR]
  bkquake spectrum RUN_DIR [--signal S] [--segment K | --from T0 --to T1] [--out FILE]
  bkquake special-speed [SCENE] [--set section.key=value]...
  bkquake special-law BK_RUN_DIR... > law.csv
  bkquake sweep SWEEP.ini [--set section.key=value]... --out DIR [--resume]
  bkquake friction-study [--out DIR] [--seeds N] [--jobs J] [--segment T]
  bkquake stability [SCENE] [--set section.key=value]... [--sweep KEY=FROM:TO:COUNT] [--out DIR] [--force]
  bkquake --help | --version

Commands:
  run     simulate a scene (event-driven or continuously driven) and write
          scene.ini, catalog.csv, histogram.csv, summary.json (+ timeseries.csv)
  fit     fit the Gutenberg-Richter law R = A exp(-b mu) to an event catalogue
  merge   merge the histograms of runs of the same scene and fit the result
  accuracy  work-precision study: error against time per event for every scheme and dt
  spectrum  amplitude spectrum of a continuous run's signal, peaks beside the natural
            frequencies (thesis §4.3)
  special-speed  t_death and v_special = F0/(k_p t_death) of thesis eq. 4.8
  special-law    the friction a held pad feels in BK runs, as a table (thesis Fig. 4.8)
  sweep   run every point of a sweep file (also under mpirun) and write sweep.csv
  friction-study the four configurations of thesis Fig. 4.6 over the speed grid
  stability  steady sliding and the complex eigenvalues of its linearisation (stability.csv)

Examples:
  bkquake run                                    the Carlson-Langer reference, event-driven
  bkquake run data/scenes/thesis.ini --out runs/thesis
  bkquake run data/scenes/carlson-langer.ini --set friction.alpha=1 --set run.events=20000

Each command takes --help. Every scene key, its default, range and meaning:
'bkquake run --dump-defaults' and README.md (section Scenes).
)";

#if defined(__x86_64__) && defined(__AVX2__) && defined(__FMA__)
// A binary built for x86-64-v3 (or native) on a CPU without AVX2 or FMA would die with
// SIGILL somewhere in the first event; this runs before main and any static initialiser of
// this file, compiled for the plain x86-64 instruction set, and says why instead.
__attribute__((constructor(101), target("arch=x86-64"))) void require_build_cpu() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return;
  static const char msg[] =
      "bkquake: error: this bkquake was built for CPUs with AVX2 and FMA (x86-64-v3), which this "
      "CPU lacks; rebuild it here with -DBKQUAKE_ARCH=x86-64-v2\n";
  [[maybe_unused]] const ssize_t n = ::write(2, msg, sizeof msg - 1);
  ::_exit(bkq::kExitBadInput);
}
#endif

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> all(argv + 1, argv + argc);
  try {
    if (all.empty()) {
      std::cerr << kUsage;
      return bkq::kExitBadInput;
    }
    const std::string& command = all.front();
    const std::vector<std::string> args(all.begin() + 1, all.end());
    if (command == "--help" || command == "-h" || command == "help") {
      std::cout << kUsage;
      return 0;
    }
    if (command == "--version") {
      std::cout << "bkquake " << bkq::kVersion << " (git " << bkq::kGitRevision << ")\n";
      return 0;
    }
    if (command == "run") return bkq::cmd_run(args);
    if (command == "fit") return bkq::cmd_fit(args);
    if (command == "merge") return bkq::cmd_merge(args);
    if (command == "accuracy") return bkq::cmd_accuracy(args);
    if (command == "spectrum") return bkq::cmd_spectrum(args);
    if (command == "special-speed") return bkq::cmd_special_speed(args);
    if (command == "special-law") return bkq::cmd_special_law(args);
    if (command == "sweep") return bkq::cmd_sweep(args);
    if (command == "friction-study") return bkq::cmd_friction_study(args);
    if (command == "stability") return bkq::cmd_stability(args);
    if (command == "readme-tables") return bkq::cmd_readme_tables(args);
    throw bkq::Error("unknown command '" + command + "'; try 'bkquake --help'");
  } catch (const bkq::Error& e) {
    // One line of printable text, whatever file content or value the message quotes.
    std::cerr << "bkquake: error: " << bkq::escape_unprintable(e.what()) << "\n";
    return bkq::kExitBadInput;
  } catch (const std::bad_alloc&) {
    // Out of memory (a memory limit, a request too large for the machine): what was written
    // is kept, as for any refusal; the lock is released by unwinding.
    std::cerr << "bkquake: error: out of memory (the machine or its limit on this process "
                 "cannot hold what was asked for; ask for less)\n";
    return bkq::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "bkquake: internal error: " << bkq::escape_unprintable(e.what()) << "\n";
    return 1;
  }
}
