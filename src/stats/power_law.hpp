// Power-law fits of an event-size distribution, for any size measure (moment, blocks,
// topplings, area, duration): maximum likelihood for a continuous or a discrete (integer)
// measure, x_min by the Kolmogorov-Smirnov distance, an optional upper cut x_max (the fit
// is normalised on [x_min, x_max]), a goodness-of-fit p-value from synthetic sets, and
// likelihood-ratio comparisons with a lognormal (Vuong 1989) and with a power law with an
// exponential cut-off (nested; Self & Liang 1987 for the boundary), all after Clauset,
// Shalizi & Newman, SIAM Review 51, 661 (2009). The exponent's error is both the Fisher
// one (independent events) and a block bootstrap over the catalogue's order (correlated
// events; gutenberg_richter.hpp's integrated_autocorrelation_time chooses the block).
// docs/explanation/power-law-fits.md describes the methods.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace bkq {

struct PowerLawOptions {
  bool discrete = false;        // the measure is an integer (blocks, topplings, area)
  std::optional<double> x_min;  // given; else the KS scan over the grid below
  std::optional<double> x_max;  // given; else x_max_auto decides
  bool x_max_auto = true;       // below the first gap or rise of ln x (GrFitOptions' tests)
  std::int64_t min_tail = 50;   // fewest events in [x_min, x_max]
  // and at least this share of the values up to x_max: a tail of a few dozen events beyond
  // a cut-off (the finite size of a lattice) looks like a steep power law to the KS scan.
  double min_tail_share = 0.01;
  std::int64_t x_min_grid = 30;  // at most this many x_min candidates, even in ln x
  std::int64_t gof_sets = 100;   // synthetic sets of the goodness-of-fit p-value (0: none)
  std::int64_t boot_resamples = 200;
  double boot_block_factor = 5.0;
  double boot_plateau = 0.9;  // the block length's rule (GrFitOptions)
  std::int64_t boot_min_blocks = 10;
  std::uint64_t seed = 20261128;
  bool compare = true;  // the likelihood-ratio tests
  // Polled between synthetic sets; true stops the fit (FitCancelled).
  std::function<bool()> cancelled;
};

struct PowerLawFit {
  bool ok = false;
  std::string no_fit_reason;
  bool discrete = false;
  std::int64_t n_total = 0;  // finite values > 0 given
  std::int64_t n_tail = 0;   // in [x_min, x_max]
  double x_min = 0;
  double x_max = std::numeric_limits<double>::infinity();  // inf: no upper cut
  std::string x_max_reason;                                // "given", "gap", "rise", "none"
  bool x_min_auto = true;
  std::int64_t x_min_candidates = 0;                                 // the size of the grid scanned
  double alpha = std::numeric_limits<double>::quiet_NaN();           // tau: p(x) ~ x^-alpha
  double alpha_err = std::numeric_limits<double>::quiet_NaN();       // Fisher information
  double alpha_boot_err = std::numeric_limits<double>::quiet_NaN();  // block bootstrap
  std::int64_t boot_block = 0;
  double boot_tau_int = std::numeric_limits<double>::quiet_NaN();
  double ks = std::numeric_limits<double>::quiet_NaN();
  double p = std::numeric_limits<double>::quiet_NaN();  // goodness of fit
  std::int64_t gof_sets = 0;
  // Vuong's test against a lognormal fitted to the same tail: the normalised log-likelihood
  // ratio (> 0 favours the power law) and its two-sided p-value.
  double lognormal_mu = std::numeric_limits<double>::quiet_NaN();
  double lognormal_sigma = std::numeric_limits<double>::quiet_NaN();
  double lognormal_ratio = std::numeric_limits<double>::quiet_NaN();
  double lognormal_p = std::numeric_limits<double>::quiet_NaN();
  // Nested test against x^-alpha e^{-lambda x}: 2 (ln L_cut - ln L_pl) >= 0 and its p-value.
  double cutoff_alpha = std::numeric_limits<double>::quiet_NaN();
  double cutoff_lambda = std::numeric_limits<double>::quiet_NaN();
  double cutoff_ratio = std::numeric_limits<double>::quiet_NaN();
  double cutoff_p = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> notes;
};

// Fits the values x (> 0 and finite ones; in the catalogue's order for the bootstrap).
// Values <= 0 or not finite are left out (counted in a note). Never throws for a sample
// that cannot be fitted: ok is false and no_fit_reason says why.
PowerLawFit fit_power_law(std::span<const double> x, const PowerLawOptions& opt = {});

// The maximum-likelihood exponent on [x_min, x_max] from the tail's count and the sum of
// ln x over it, with its Fisher error (exposed for tests and the bootstrap).
struct AlphaEstimate {
  double alpha = std::numeric_limits<double>::quiet_NaN();
  double err = std::numeric_limits<double>::quiet_NaN();
};
AlphaEstimate power_law_mle(std::int64_t n, double sum_ln_x, double x_min, double x_max,
                            bool discrete);

}  // namespace bkq
