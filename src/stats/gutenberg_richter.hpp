// Gutenberg-Richter fits of a magnitude distribution (Gutenberg & Richter 1944; Ferre 2018
// eqs. 2.7, 2.8 and 2.10). Magnitudes are natural logarithms of the moment (mu = ln M, thesis
// eq. 2.6), so the law is R(mu) = A e^{-b mu} with no ln 10 factors anywhere.
//
// The estimators (Aki, Tinti & Mulargia, Shi & Bolt, weighted least squares, two power
// laws), the automatic window (a ceiling below the first gap of empty bins and any rise of
// the distribution, the lower cut by b-value stability, the upper cut by a departure test
// of the events above, a goodness-of-fit test of the result), the systematic error of b,
// the block-bootstrap error of b on a catalogue and the large-event excess are described
// in docs/explanation/b-fit.md and docs/how-to/fit-window.md.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "stats/histogram.hpp"

namespace bkq {

// Bounds that keep every fit finite on any input (bkq::Error beyond them): a window, and
// the populated range of the histogram, span at most kMaxFitBins bins; the automatic
// window search (O(bins^3)) and the two-power-law scan (O(bins^2)) run on at most
// kMaxScanBins bins (300 units of mu at the default width 0.2).
inline constexpr std::int64_t kMaxFitBins = 100'000;
inline constexpr std::int64_t kMaxScanBins = 1'500;

// Thrown by the fits when GrFitOptions::cancelled says so (a run was asked to stop).
class FitCancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "fit cancelled"; }
};

struct GrFitOptions {
  std::int64_t min_tail = 50;  // fewest events in a candidate window
  // Fewest bins in a candidate window (10 bins of 0.2 = a factor e^2 in moment).
  std::int64_t min_window_bins = 10;
  double excess_tail_probability = 0.02275;  // one-sided 2 sigma
  // Ceiling of the automatic window: the running sum of the counts over smooth_width (in
  // mu) must not rise inside the window to more than rise_factor times its lowest value
  // further down, by more than rise_sigma Poisson standard deviations (the dip and bump of
  // large events).
  double smooth_width = 1.0;
  double rise_factor = 2.0;
  double rise_sigma = 3.0;
  // Gap: a run of empty bins at least gap_width long (in mu; 5 bins of 0.2, a factor e in
  // moment) that a density not rising above it would have filled: with m events in the B
  // bins above it (up to the largest event), each of its bins would expect at least m / B
  // events, and the run is a gap when its bins would expect gap_expected events together
  // (ln 100: an empty run has probability <= 1 %). The automatic window's top stays below
  // the first gap above its lower end. Integer sizes (OFC, few-block events) leave runs of
  // at most ln 2 = 0.69 in mu; in the sparse tail of a power law, runs of empty bins have
  // too few events above them.
  double gap_width = 1.0;
  double gap_expected = 4.605170185988091;
  // Lower cut, b-value stability (Cao & Gao 2002; Woessner & Wiemer 2005) adapted to
  // mu = ln M: mu_min is the lowest populated bin edge from which b (binned MLE up to the
  // upper cut) changes by at most max(stability_db, stability_sigma * sigma_b) from each
  // bin edge to the next over stability_width units of mu (1.6 in mu = 0.46 units of Mw,
  // about the 0.5 of Woessner & Wiemer; 0.03 is the step of Cao & Gao; sigma_b the Shi &
  // Bolt error of the later window, as Woessner & Wiemer's tolerance). When no edge is
  // stable, the most stable one that passes the goodness-of-fit test below.
  double stability_width = 1.6;
  double stability_db = 0.03;
  double stability_sigma = 2.0;
  // When no edge is stable on the windows up to the ceiling (a kink between the scaling
  // region and the bump makes b drift on all of them), the search is made again with each
  // edge's window ending where the events above depart from its law (the upper cut), and
  // an edge is taken when its steps stay within stability_relaxed times the tolerance and
  // its window passes the goodness-of-fit test.
  double stability_relaxed = 1.5;
  // Upper cut, departure from the power law: the events in the departure_width units of
  // mu above the window are fitted alone (truncated binned MLE); the law holds on when
  // that slope lies within [b / departure_ratio, b * departure_ratio] widened by
  // departure_sigma of its standard errors. mu_max is the highest window top (below the
  // ceiling) at which the law holds on; a segment of fewer than departure_min_events
  // events cannot show a departure.
  double departure_width = 1.6;
  double departure_ratio = 1.5;
  double departure_sigma = 2.0;
  std::int64_t departure_min_events = 20;
  // Systematic error: half the range of b over the windows whose lower end lies within
  // sys_width above mu_min and whose upper end lies within sys_width below mu_max, on
  // populated bins, with >= min_tail events and >= min_window_bins bins (given ends too:
  // a window by eye is a choice as well).
  double sys_width = 1.0;
  // Goodness of fit reported for every window (Wiemer & Wyss 2000, as a KS distance): a
  // window is a fit when d <= ks_systematic + ks_tolerance / sqrt(n_window).
  double ks_systematic = 0.03;
  double ks_tolerance = 0.5;
  // The secondary estimates (b_lsq, the two power laws) are given only where their own
  // chi^2 test gives p >= secondary_p.
  double secondary_p = 0.001;
  // Block bootstrap of b over contiguous stretches of the catalogue (block_bootstrap_b):
  // boot_resamples resamples from a generator seeded with boot_seed. The block length is
  // where the error stops growing with it (plateau_block_length): from the larger of
  // n^(1/3) (n events) and boot_block_factor times the integrated autocorrelation time of
  // the events' offsets in the window (Sokal's window, boot_window_factor), doubled up to
  // n / boot_min_blocks, the shortest whose batch-means error reaches boot_plateau of the
  // largest at it and above (loading cycles correlate events over thousands of events,
  // which an autocorrelation sum stopped at a few lags does not see).
  std::int64_t boot_resamples = 200;
  std::uint64_t boot_seed = 20261128;
  double boot_block_factor = 5.0;
  double boot_window_factor = 5.0;
  double boot_plateau = 0.9;
  std::int64_t boot_min_blocks = 10;
  // Polled between the steps of the fit (well under a millisecond apart at <= kMaxScanBins
  // bins); when it returns true the fit throws FitCancelled. Empty: never cancelled.
  std::function<bool()> cancelled;
};

struct GrFit {
  // False when no acceptable window exists (automatic search) or b_mle <= 0 on the window:
  // then every b, its errors, ln_A, the KS distance and the excess are NaN/empty and
  // no_b_reason says why; the window fields keep the range that was looked at.
  bool b_ok = true;
  std::string no_b_reason;
  double bin_width = 0;
  std::int64_t n_total = 0;
  // Window [mu_min, mu_max] (whole bins).
  double mu_min = 0;
  double mu_max = 0;
  bool window_auto = false;  // mu_min chosen by the automatic window search
  bool mu_max_auto = false;  // mu_max chosen by the automatic window search (not given)
  // Truncated likelihoods: mu_max was given, or the automatic window ends below the
  // largest populated bin.
  bool truncated = false;
  std::int64_t n_in_window = 0;
  // Why the window's top is where it is: "given", "end of data" (the largest event),
  // "gap" (below a run of empty bins), "rise" (below a rise of the distribution),
  // "departure" (the events above depart from the law), "goodness of fit" (lowered until
  // the window passes the KS test). Empty when there is no window.
  std::string mu_max_reason;
  // A window (or an end) given by the user that crosses a gap, takes in a rise or fails
  // the goodness-of-fit test is fitted all the same, and each of these says so.
  std::vector<std::string> warnings;
  // Binned MLE (Tinti & Mulargia 1987) and its error (Shi & Bolt: independent events).
  double b_mle = 0;
  double b_mle_err = 0;
  // Statistical error of b_mle from a block bootstrap over the catalogue in its order
  // (block_bootstrap_b; accounts for correlated events), with the block length (events),
  // the integrated autocorrelation time it was chosen from and the number of resamples.
  // NaN/0 from a histogram alone (no order of events), with boot_note saying so.
  double b_mle_boot_err = std::numeric_limits<double>::quiet_NaN();
  std::int64_t boot_block = 0;
  double boot_tau_int = std::numeric_limits<double>::quiet_NaN();
  std::int64_t boot_resamples = 0;
  std::string boot_note = "no catalogue order (a histogram): no bootstrap error";
  // Systematic error of b_mle: half the range of b over the windows of
  // GrFitOptions::sys_width around this one (sys_windows of them); NaN when no b.
  double b_mle_sys_err = 0;
  std::int64_t sys_windows = 0;
  // Unbinned MLE (Aki 1965) and its error (Shi & Bolt 1982); NaN when the magnitudes
  // themselves are not available.
  double b_aki = 0;
  double b_aki_err = 0;
  // Least squares slope of ln R; NaN with b_lsq_reason when the line fails its own test
  // (Pearson chi^2 of the window's counts against the counts the line implies, bins
  // expecting >= 5 events, p < secondary_p).
  double b_lsq = 0;
  double b_lsq_err = 0;
  std::string b_lsq_reason;
  // R(mu) = A e^{-b_mle mu}, normalised so the window holds n_in_window events.
  double ln_A = 0;
  double ks_distance = 0;
  // Two power laws (Ferre 2018 eq. 2.10); not ok, with two_law_reason, when not fitted or
  // when the two lines fail their own test (chi^2 of ln D with Poisson weights, p <
  // secondary_p).
  bool two_law_ok = false;
  std::string two_law_reason;
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

// b per unit of moment magnitude Mw = (2/3) log10 M + const for a law that has slope b
// per unit of mu = ln M: mu = 1.5 ln(10) Mw + const, so R = A e^{-b mu} = A' 10^{-1.5 b Mw}.
// Errors scale the same way.
inline constexpr double kMwPerMu = 1.5;
inline double b_moment_magnitude(double b_mu) {
  return kMwPerMu * b_mu;
}

// One window of a b scan: the binned MLE on [mu_min, mu_max) and whether the automatic
// method counts it among the windows of the systematic error.
struct WindowFit {
  double mu_min = 0, mu_max = 0;
  std::int64_t events = 0;
  double b = 0, b_err = 0, ks_distance = 0;
  bool accepted = false;
};
// Every window [lo, hi) between populated bins with >= min_tail events and >=
// min_window_bins bins (lo in the order of the bins, then hi), fitted like the fit's own
// window (truncated unless it reaches the largest populated bin); `fit` marks as accepted
// the windows of its systematic error. At most kMaxScanBins bins (bkq::Error beyond).
std::vector<WindowFit> scan_windows(const MagnitudeHistogram& h, const GrFit& fit,
                                    const GrFitOptions& opt = {});

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

// Full fit of a histogram. Window limits are snapped inward to whole bins. b_aki is filled
// from the histogram's sums only when the window covers every event and the sums are exact;
// otherwise it is NaN (use fit_magnitudes).
GrFit fit_histogram(const MagnitudeHistogram& h, std::optional<double> mu_min,
                    std::optional<double> mu_max, const GrFitOptions& opt = {});
// The same from the magnitudes themselves (binned with width w), with b_aki filled in on
// the same window.
GrFit fit_magnitudes(std::span<const double> mu, double bin_width, std::optional<double> mu_min,
                     std::optional<double> mu_max, const GrFitOptions& opt = {});
// Adds the unbinned Aki estimate on fit's window, and the block-bootstrap error of b_mle
// (mu in the catalogue's order).
void add_unbinned(GrFit& fit, std::span<const double> mu, const GrFitOptions& opt = {});

// Block bootstrap of the binned MLE on a fixed window (Kuensch 1989, circular blocks of
// Politis & Romano 1992): the catalogue mu (in its order) is cut into blocks of `block`
// consecutive events (chosen from the data when 0: plateau_block_length of the in-window
// offsets from the larger of n^(1/3) and boot_block_factor times their integrated
// autocorrelation time, Sokal's window), opt.boot_resamples
// catalogues are drawn from them with a generator seeded by opt.boot_seed, and b's error is
// the standard deviation of b_mle over them. Events outside the window count towards a
// block's length but not its fit.
struct BootstrapError {
  double err = std::numeric_limits<double>::quiet_NaN();
  std::int64_t block = 0;
  double tau_int = std::numeric_limits<double>::quiet_NaN();
  std::int64_t resamples = 0;
};
BootstrapError block_bootstrap_b(std::span<const double> mu, double bin_width, double mu_min,
                                 double mu_max, bool truncated, const GrFitOptions& opt = {},
                                 std::int64_t block = 0);
// The top of a scaling region that starts at mu_start (as the automatic window's ceiling):
// the upper edge of the highest populated bin below the first gap (GrFitOptions::gap_width)
// and below the first rise above mu_start; reason "gap", "rise" or "end of data".
struct ScalingCeiling {
  double mu_max = 0;
  std::string reason;
};
ScalingCeiling scaling_ceiling(const MagnitudeHistogram& h, double mu_start,
                               const GrFitOptions& opt = {});

// The block length of a block bootstrap of the mean of z (an event's influence on the
// estimate, zero for events outside the fit): candidates first, 2 first, 4 first, ... up to
// n / min_blocks; for each, the batch-means error sqrt(sum of squared block sums, centred,
// times nb / (nb - 1)) over nb = n / L whole blocks. The shortest candidate whose error is
// at least `plateau` times the largest at it or any longer one (the plateau of the error
// against the block length, Flyvbjerg & Petersen 1989). `first` when it is beyond
// n / min_blocks already.
std::int64_t plateau_block_length(std::span<const double> z, std::int64_t first, double plateau,
                                  std::int64_t min_blocks);

// The integrated autocorrelation time 1 + 2 sum_t rho(t) of a series, summed up to the
// first lag M >= window_factor * tau(M) (Sokal 1997); 1 for an uncorrelated series.
double integrated_autocorrelation_time(std::span<const double> x, double window_factor = 5.0);

}  // namespace bkq
