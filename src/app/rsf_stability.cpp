// The dense stability report of per-block rate-and-state laws; see rsf_stability.hpp.
#include "app/rsf_stability.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/stability_csv.hpp"
#include "stats/rsf_stability.hpp"

namespace bkq {

RsfStabilityReport rsf_dense_stability(const Settings& settings) {
  const RsfModel& m = settings.rsf.chain;
  const int n = m.n();
  if (n > kRsfDenseLimit)
    throw Error("stability: per-block rate-and-state laws (rsf.blocks or rsf.pattern) on " +
                std::to_string(n) + " blocks: their linearisation is a dense eigenproblem of " +
                std::to_string(m.dynamics == RsfDynamics::Inertial ? 3 * n : 2 * n) +
                " unknowns, O(N^3), written for at most " + std::to_string(kRsfDenseLimit) +
                " blocks; allowed: model.blocks x model.rows <= " + std::to_string(kRsfDenseLimit) +
                ", or one law for every block");
  const std::vector<std::complex<double>> roots = rsf_dense_eigenvalues(m);
  RsfStabilityReport r;
  r.modes_csv = header_of(stability_schema()) + "\n";
  int listed = 0, unstable = 0;
  double top_growth = -HUGE_VAL, top_freq = 0;
  for (const std::complex<double>& s : roots) {
    if (s.imag() < 0) continue;  // a complex pair once
    const double freq = s.imag() / (2 * std::numbers::pi);
    unstable += s.real() > 0 ? 1 : 0;
    if (s.real() > top_growth) top_growth = s.real(), top_freq = freq;
    r.modes_csv += format_real(m.v_pl) + ",dense " + std::to_string(listed++) + "," +
                   format_real(s.real()) + "," + format_real(s.imag()) + "," + format_real(freq) +
                   "," + (s.real() > 0 ? "1" : "0") + "\n";
  }
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const rsf::Law& law : m.law) {
    const double k = rsf::critical_stiffness(law.params(), m.sigma);
    lo = std::min(lo, k);
    hi = std::max(hi, k);
  }
  const std::string nan = format_real(std::nan(""));
  r.summary_csv =
      "v_pl,k,k_c,k_crit_quasi_static,k_crit_radiation_damping,k_crit,frequency_at_k_crit,"
      "modes,unstable,max_growth,its_frequency\n" +
      format_real(m.v_pl) + "," + format_real(m.k) + "," + format_real(m.k_c) + "," + nan + "," +
      nan + "," + nan + "," + nan + "," + std::to_string(listed) + "," + std::to_string(unstable) +
      "," + format_real(top_growth) + "," + format_real(top_freq) + "\n";
  char line[640];
  std::snprintf(line, sizeof line,
                "rate-and-state steady sliding at V_pl = %g m/s, k = %g Pa/m, per-block laws:\n"
                "  sigma (b - a)/D_c of the blocks from %g to %g Pa/m (each block's own k_crit; "
                "the chain has no single one)\n"
                "  %s linearisation of %d blocks, dense: %d eigenvalues listed (complex pairs "
                "once)\n"
                "  %d unstable; largest growth rate %g 1/s at %g Hz\n",
                m.v_pl, m.k, lo, hi,
                m.dynamics == RsfDynamics::Inertial ? "inertial" : "quasi-dynamic", n, listed,
                unstable, top_growth, top_freq);
  r.text = line;
  return r;
}

}  // namespace bkq
