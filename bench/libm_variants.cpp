// The C library's run-time choice of libm variants, measured: glibc picks an implementation
// of log, exp, pow, sin and cos by processor when the program starts (on x86-64 an FMA
// variant where the processor has FMA and AVX2, else the SSE2 one). bkquake calls these in
// its magnitudes (log), the lone-slip oscillator (exp, sin, cos) and the adaptive step
// control (pow). This program evaluates each function on the same 4e6 arguments and writes
// the results; run it twice, once with glibc told to ignore FMA and AVX2 (the variant a
// processor without them gets), and compare:
//
//   build/libm_variants a.bin
//   GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA build/libm_variants b.bin
//   build/libm_variants --compare a.bin b.bin
//
// The comparison prints, per function, how many results differ and by how many units in
// the last place at most (docs/explanation/reliability.md, "Across machines").
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace {

constexpr int kFunctions = 7;
constexpr const char* kNames[kFunctions] = {"log", "exp", "pow", "sin", "cos", "expm1", "log1p"};
constexpr std::int64_t kArguments = 4'000'000;

// xorshift64: the same arguments in every run, whatever the C library.
std::uint64_t next(std::uint64_t& s) {
  s ^= s << 13;
  s ^= s >> 7;
  s ^= s << 17;
  return s;
}

int write_results(const char* path) {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(kArguments) * kFunctions);
  std::uint64_t s = 88172645463325252ull;
  for (std::int64_t i = 0; i < kArguments; ++i) {
    const double u = static_cast<double>(next(s) >> 11) * 0x1p-53;  // [0, 1)
    const double wide = std::ldexp(u + 0.5, static_cast<int>(s % 60) - 30);
    const double arg = (u - 0.5) * 1400.0;  // exp's whole range
    out.insert(out.end(), {std::log(wide), std::exp(arg), std::pow(wide, 3 * u), std::sin(arg),
                           std::cos(arg), std::expm1(u - 0.5), std::log1p(u)});
  }
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(out.data()),
          static_cast<std::streamsize>(out.size() * sizeof(double)));
  if (!f) {
    std::fprintf(stderr, "libm_variants: cannot write %s\n", path);
    return 2;
  }
  return 0;
}

std::vector<std::int64_t> read_bits(const char* path) {
  std::ifstream f(path, std::ios::binary);
  std::vector<std::int64_t> v(static_cast<std::size_t>(kArguments) * kFunctions);
  f.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * 8));
  if (!f) v.clear();
  return v;
}

int compare(const char* a_path, const char* b_path) {
  const auto a = read_bits(a_path), b = read_bits(b_path);
  if (a.empty() || b.empty()) {
    std::fprintf(stderr, "libm_variants: cannot read %s and %s as results of this program\n",
                 a_path, b_path);
    return 2;
  }
  std::printf("%-6s %12s %10s %8s\n", "func", "differ", "share", "max ulp");
  for (int k = 0; k < kFunctions; ++k) {
    std::int64_t differ = 0, max_ulp = 0;
    for (std::int64_t i = 0; i < kArguments; ++i) {
      const std::size_t at = static_cast<std::size_t>(i * kFunctions + k);
      if (a[at] == b[at]) continue;
      ++differ;
      const std::int64_t d = a[at] > b[at] ? a[at] - b[at] : b[at] - a[at];
      if (d > max_ulp) max_ulp = d;
    }
    std::printf("%-6s %12lld %10.2e %8lld\n", kNames[k], static_cast<long long>(differ),
                static_cast<double>(differ) / static_cast<double>(kArguments),
                static_cast<long long>(max_ulp));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--compare") != 0) return write_results(argv[1]);
  if (argc == 4 && std::strcmp(argv[1], "--compare") == 0) return compare(argv[2], argv[3]);
  std::fprintf(stderr,
               "usage: libm_variants OUT.bin | libm_variants --compare A.bin B.bin "
               "(see the comment at the top of bench/libm_variants.cpp)\n");
  return 2;
}
