// Gutenberg-Richter fits of a magnitude distribution (SPEC section 4; thesis eqs. 2.7,
// 2.8 and 2.10). Magnitudes are natural logarithms of the moment (mu = ln M, thesis
// eq. 2.6), so the law is R(mu) = A e^{-b mu} with no ln 10 factors anywhere.
//
// What is fitted, on a window [mu_min, mu_max] of whole bins:
//  * b_aki:  unbinned maximum likelihood (Aki 1965, base e): b = 1 / (<mu> - mu_min).
//            With an explicit mu_max the truncated exponential is used (Page 1968):
//            <mu> - mu_min = 1/b - D/(e^{bD} - 1), D = mu_max - mu_min, solved for b.
//  * b_mle:  binned maximum likelihood (Tinti & Mulargia 1987, base e). For bins of
//            width w the bin index above the window's first bin is geometric with
//            p = e^{-bw}, so b = (1/w) ln(1 + w/(<mu_c> - mu_c1)) with <mu_c> the mean of
//            the bin centres and mu_c1 the CENTRE of the first bin of the window
//            (= lower edge + w/2; with the lower edge instead, b is biased low by ~10 %
//            at bw = 0.2). With an explicit mu_max the truncated geometric is used.
//  * errors: Shi & Bolt (1982) in base e, sigma_b = b^2 sqrt(sum (mu_i - <mu>)^2 /
//            (n (n-1))) for the untruncated continuous case; in general we use the same
//            standard error of the mean divided by |d<mu>/db| of the model (delta method),
//            which reduces to Shi & Bolt exactly when there is no truncation and w -> 0.
//  * b_lsq:  weighted least squares slope of ln R(mu) at the lower bin edges of the
//            window (weights R, the Poisson inverse variance of ln R). Its error is the
//            formal one from the weighted residuals; cumulative counts are correlated, so
//            it is optimistic.
//  * window: candidate windows run between bin edges, hold >= min_tail events, span
//            >= min_window_bins bins and >= 2 populated bins; a limit that is not given
//            sits on a populated bin (the window starts at an event and ends at the upper
//            edge of its largest event). On each, b_mle is fitted and the Kolmogorov-
//            Smirnov distance d between the empirical and fitted (binned, geometric)
//            survival functions is taken. The likelihood is truncated at mu_max when
//            mu_max is given or the window ends below the largest populated bin (events
//            above are left out); a window up to the largest event is left untruncated
//            (the sample maximum is not a physical cut-off).
//            - mu_max given, mu_min free: Clauset, Shalizi & Newman (2009), the mu_min
//              with the smallest d wins.
//            - mu_max free (mu_min free or given): both ends are scanned. The smallest d
//              alone would favour narrow windows low down (many events, nearly straight),
//              and d is blind to the top of the window, where few events sit. So
//              (1) a window is out when its own upper tail is in excess of its fit: at
//              some interior edge the window's events at or above it are more than the
//              fit predicts at one-sided Poisson probability < window_excess_alpha /
//              (interior edges) (Bonferroni); this is what keeps the bump of large
//              delocalised events (SPEC 4) out, since a truncated fit across it has too
//              many events at the top; (2) among the rest, windows whose d is within
//              ks_tolerance / sqrt(n_window) of the smallest (a fraction of the typical
//              KS fluctuation of an exact model, ~0.8 / sqrt(n)) are near-ties, and the
//              widest (most bins; then most events; then smallest d) wins: the scaling
//              region as wide as the data allow. When every candidate fails (1), (2) runs
//              on all of them and a note says so. Cost: O(bins^3), trivial at <= ~100 bins.
//            window_auto / mu_max_auto record which ends were scanned.
//  * two power laws (thesis eq. 2.10, Carlson et al. 1991): ln D(mu) is fitted by two
//            straight lines, slope -b1 below the crossover mu~ = ln M~ and -b2 above it,
//            each with its own constant (A at M~, A' at the upper cutoff M*), on the bins
//            from mu_min to the largest populated bin; the crossover bin edge is scanned
//            and the split with the smallest weighted (Poisson) residual wins.
//  * excess of large events: a bin edge mu is in excess when the observed R(mu) exceeds
//            the fitted line R = A e^{-b mu} (b = b_mle, A from the window count) by more
//            than 2 sigma in the Poisson sense (one-sided tail probability < 2.275 %).
//            Scanning down from the largest populated bin (skipping non-significant
//            isolated top bins), excess_mu is the lowest edge of the contiguous run of
//            edges in excess; excess_observed/expected are R_obs and R_fit there and
//            excess_count is the largest R_obs - R_fit over the run (when the fit window
//            includes the excess, b is pulled down and the difference at the onset
//            understates the number of excess events). With an explicit
//            mu_max the scan stops at mu_max (inside the window the line is normalised to
//            the window's own events).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "stats/histogram.hpp"

namespace bkq {

struct GrFitOptions {
  std::int64_t min_tail = 50;  // CSN: fewest events above a candidate mu_min
  // CSN: fewest bins in a candidate window (10 bins of 0.2 = a factor e^2 in moment). Keeps
  // the scan from settling on the bump of large delocalised events at the top.
  std::int64_t min_window_bins = 10;
  double excess_tail_probability = 0.02275;  // one-sided 2 sigma
  // Automatic mu_max: a window is a near-tie of the best one when its KS distance is
  // within ks_tolerance / sqrt(n_window) of the smallest; the widest near-tie wins.
  double ks_tolerance = 0.5;
  // Automatic mu_max: a window is rejected when some edge inside it has more events above
  // it (up to mu_max) than its own fit predicts, at one-sided Poisson probability below
  // window_excess_alpha / (number of interior edges) (Bonferroni).
  double window_excess_alpha = 0.05;
};

struct GrFit {
  double bin_width = 0;
  std::int64_t n_total = 0;
  // Window [mu_min, mu_max] (whole bins).
  double mu_min = 0;
  double mu_max = 0;
  bool window_auto = false;  // mu_min chosen by the KS scan
  bool mu_max_auto = false;  // mu_max chosen by the KS scan (not given)
  // Truncated likelihoods: mu_max was given, or the automatic window ends below the
  // largest populated bin.
  bool truncated = false;
  std::int64_t n_in_window = 0;
  // Binned MLE (Tinti & Mulargia 1987) and its error.
  double b_mle = 0;
  double b_mle_err = 0;
  // Unbinned MLE (Aki 1965) and its error (Shi & Bolt 1982); NaN when the magnitudes
  // themselves are not available.
  double b_aki = 0;
  double b_aki_err = 0;
  // Least squares slope of ln R.
  double b_lsq = 0;
  double b_lsq_err = 0;
  // R(mu) = A e^{-b_mle mu}, normalised so the window holds n_in_window events.
  double ln_A = 0;
  double ks_distance = 0;
  // Two power laws (thesis eq. 2.10).
  bool two_law_ok = false;
  double two_law_b1 = 0;            // slope below the crossover (localised events)
  double two_law_b2 = 0;            // slope above the crossover (delocalised events)
  double two_law_mu_cross = 0;      // crossover magnitude mu~ = ln M~ (a bin edge)
  double two_law_moment_cross = 0;  // M~
  double two_law_ln_A1 = 0;         // ln A: D(mu~) of the lower branch
  double two_law_ln_A2 = 0;         // ln A': D(mu*) of the upper branch at the upper cutoff
  double two_law_mu_low = 0;        // ln M1, lower cutoff (fit range start)
  double two_law_mu_high = 0;       // ln M*, upper cutoff (fit range end)
  // Large-event excess.
  bool excess_found = false;
  double excess_mu = 0;
  std::int64_t excess_observed = 0;
  double excess_expected = 0;
  double excess_count = 0;  // largest observed - expected over the excess run
  std::vector<std::string> notes;
};

// A maximum-likelihood estimate with its standard error.
struct BEstimate {
  double b = 0;
  double err = 0;
  std::int64_t n = 0;
};

// Unbinned Aki MLE on the magnitudes in [mu_min, mu_max) (all above mu_min when mu_max is
// not given; then untruncated). bkq::Error when fewer than 2 magnitudes lie in the window.
BEstimate aki_mle(std::span<const double> mu, double mu_min, std::optional<double> mu_max);
// Binned Tinti-Mulargia MLE on bins k_lo..k_hi; truncated geometric if `truncated`.
BEstimate binned_mle(const MagnitudeHistogram& h, std::int64_t k_lo, std::int64_t k_hi,
                     bool truncated);
// Discrete KS distance between the empirical survival function on bins k_lo..k_hi and the
// fitted geometric one with exponent b.
double ks_distance_binned(const MagnitudeHistogram& h, std::int64_t k_lo, std::int64_t k_hi,
                          double b, bool truncated);

// Smallest one-sided Poisson probability P(X >= observed) over the interior edges of bins
// k_lo..k_hi, X of mean n_window times the fitted survival function at the edge and
// "observed" the window's events at or above the edge; 1 when no edge is in excess.
double tail_excess_p(const MagnitudeHistogram& h, std::int64_t k_lo, std::int64_t k_hi, double b,
                     bool truncated);

// Full fit of a histogram. Window limits are snapped inward to whole bins. b_aki is filled
// from the histogram's sums only when the window covers every event and the sums are exact;
// otherwise it is NaN (use fit_magnitudes).
GrFit fit_histogram(const MagnitudeHistogram& h, std::optional<double> mu_min,
                    std::optional<double> mu_max, const GrFitOptions& opt = {});
// The same from the magnitudes themselves (binned with width w), with b_aki filled in on
// the same window.
GrFit fit_magnitudes(std::span<const double> mu, double bin_width, std::optional<double> mu_min,
                     std::optional<double> mu_max, const GrFitOptions& opt = {});
// Adds the unbinned Aki estimate on fit's window.
void add_unbinned(GrFit& fit, std::span<const double> mu);

}  // namespace bkq
