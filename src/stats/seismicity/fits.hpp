// Maximum-likelihood fits on binned data, which is what a streamed catalogue keeps: the
// likelihood of counts in fixed bins is exact for grouped data (no approximation beyond the
// grouping), and the errors come from the expected Fisher information
// I_jk = sum_b (dL_b/dth_j)(dL_b/dth_k) / L_b of the expected counts L_b.
//  - Weibull and lognormal laws of intervals (recurrence times): multinomial likelihood of
//    the interval histogram.
//  - Omori-Utsu rate with a background, lambda(t) = mu + K/(t + c)^p, stacked over sequences
//    with their own windows: the Poisson likelihood of Ogata (1983, J. Phys. Earth 31, 115),
//    log L = sum_i ln lambda(t_i) - sum_s int_0^{T_s} lambda dt, with the times grouped in
//    fine log bins (log L = sum_b n_b ln L_b - L_b, L_b = E_b int_bin lambda dt, E_b the
//    number of sequences whose window covers bin b).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace bkq::seis {

// Counts in bins [lo, hi) (hi may be +inf) with, for rates, the exposure of each bin.
struct BinnedData {
  std::vector<double> lo, hi, count, exposure;
  double total() const;
};

struct Estimate {
  double value = NAN;
  double err = NAN;
};

// S(t) = exp(-(t/lambda)^k).
struct WeibullFit {
  bool ok = false;
  Estimate k, lambda;
  double survival(double t) const;
  double cdf(double t) const { return 1 - survival(t); }
};
// ln t normal with mean m and deviation s.
struct LognormalFit {
  bool ok = false;
  Estimate m, s;
  double cdf(double t) const;
};

// Both need at least 3 intervals in at least 2 bins; otherwise ok = false.
WeibullFit fit_weibull(const BinnedData& d);
LognormalFit fit_lognormal(const BinnedData& d);

struct OmoriFit {
  bool excess = false;  // the Omori term is needed (likelihood-ratio test below)
  Estimate K, c, p, background;
  double lr = 0;                // 2 (ln L_omori - ln L_background)
  double excess_events = 0;     // K int lambda over every window: the events above background
  double background_only = 0;   // the background rate when the Omori term is not needed
  std::string note;             // why there is no fit, when there is none
  double t_max = NAN;           // the times fitted: [0, t_max]
  double rate(double t) const;  // fitted lambda(t) (background alone without an excess)
};

// Significance of the Omori term: 2 Delta ln L above the chi-square quantile of 3 degrees
// of freedom at 0.999 (K, c, p added to the background), 16.27.
inline constexpr double kOmoriLrThreshold = 16.27;

// p is searched in (0, kMaxP]: a decaying excess (a rate that grows with time is no Omori
// sequence); a fit that runs to the bound is reported as no excess of that form.
inline constexpr double kMaxP = 5;

// `d.exposure[b]`: sequences covering bin b (fractional at a window's end); the bins up to
// t_max are fitted.
OmoriFit fit_omori(const BinnedData& d, double t_max);

}  // namespace bkq::seis
