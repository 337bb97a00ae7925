// The bkquake program: dispatches on the first word to a command of the table (commands.hpp) and
// turns errors into one line on stderr and an exit status: bad input (bkq::Error) exits 2,
// anything else is a bug and exits 1.
#include <unistd.h>

#include <csignal>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "app/sweep_comm.hpp"
#include "bkquake_version.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/terminal_text.hpp"
#include "io/catalog_h5.hpp"

namespace {

// The optional parts this build has, as --version prints them: what the configure found
// (CMakeLists.txt: BKQUAKE_HAVE_PYTHON is set on this file alone).
std::string optional_parts() {
  auto part = [](const char* name, bool in) { return std::string(name) + (in ? " yes" : " no"); };
  return "optional parts: " + part("HDF5 catalogues", bkq::hdf5_available()) + ", " +
         part("MPI sweeps", bkq::mpi_available()) + ", " +
         part("Python module", BKQUAKE_HAVE_PYTHON != 0);
}

// The platform and compiler this binary was built for and with, as the configure saw them
// (CMakeLists.txt sets BKQUAKE_TARGET on this file alone).
#ifndef BKQUAKE_TARGET
#define BKQUAKE_TARGET "unknown"
#endif

#if defined(__x86_64__) && defined(__AVX2__) && defined(__FMA__)
// A binary built for x86-64-v3 (or native) on a CPU without AVX2 or FMA would die with
// SIGILL somewhere in the first event; this runs before main and any static initialiser of
// this file, compiled for the plain x86-64 instruction set, and says why instead.
// A native build on an AVX-512 machine is checked for AVX-512F as well.
__attribute__((constructor(101), target("arch=x86-64"))) void require_build_cpu() {
  __builtin_cpu_init();
  bool ok = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#if defined(__AVX512F__)
  ok = ok && __builtin_cpu_supports("avx512f");
  static const char needs[] = "AVX2, FMA and AVX-512F";
#else
  static const char needs[] = "AVX2 and FMA";
#endif
  if (ok) return;
  const auto say = [](const char* s) {
    std::size_t len = 0;
    while (s[len]) ++len;
    [[maybe_unused]] const ssize_t n = ::write(2, s, len);
  };
  constexpr bool native = std::string_view(bkq::kBuildArch) == "native";
  say("bkquake: error: this bkquake was built for ");
  say(native ? "the CPU of the machine that built it" : bkq::kBuildArch);
  say(native ? ", with " : " CPUs, with ");
  say(needs);
  say(", which this CPU lacks; rebuild it here (the default build targets x86-64-v3)\n");
  ::_exit(bkq::kExitBadInput);
}
#endif

}  // namespace

int main(int argc, char** argv) {
  // A file size limit (ulimit -f) would end the process by SIGXFSZ mid-write, with no word
  // and its lock left behind; ignored, the write fails with EFBIG and ends the run as a full
  // disk does: one line naming the file, the lock released, a resumable folder.
  std::signal(SIGXFSZ, SIG_IGN);
  const std::vector<std::string> all(argv + 1, argv + argc);
  try {
    if (all.empty()) {
      std::cerr << bkq::usage_text();
      return bkq::kExitBadInput;
    }
    const std::string& command = all.front();
    const std::vector<std::string> args(all.begin() + 1, all.end());
    if (command == "--help" || command == "-h" || command == "help") {
      std::cout << bkq::usage_text();
      return 0;
    }
    if (command == "--version") {
      std::cout << "bkquake " << bkq::kVersion << " (git " << bkq::kGitRevision << ", built for "
                << bkq::kBuildArch << ")\n"
                << optional_parts() << "\n"
                << "target: " << BKQUAKE_TARGET << "\n";
      return 0;
    }
    if (const bkq::Command* c = bkq::find_command(command)) return bkq::run_command(*c, args);
    throw bkq::Error("unknown command '" + command + "'; the commands are " + bkq::command_names() +
                     "; try 'bkquake --help'");
  } catch (const bkq::Error& e) {
    // One line of printable text, whatever file content or value the message quotes.
    std::cerr << "bkquake: error: " << bkq::printable_text(e.what()) << "\n";
    return bkq::kExitBadInput;
  } catch (const std::bad_alloc&) {
    // Out of memory (a memory limit, a request too large for the machine): what was written
    // is kept, as for any refusal; the lock is released by unwinding.
    std::cerr << "bkquake: error: out of memory (the machine or its limit on this process "
                 "cannot hold what was asked for; ask for less)\n";
    return bkq::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "bkquake: internal error: " << bkq::printable_text(e.what()) << "\n";
    return 1;
  }
}
