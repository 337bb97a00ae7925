// Two or more catalogues side by side (`bkquake compare`): the two-sample Kolmogorov-Smirnov
// distance between samples (magnitudes, recurrence intervals) with its 5 % critical value, and
// the recurrence of the large events (count, mean interval, coefficient of variation, each
// with its standard error). Pure functions over numbers: the app reads the catalogues.
#pragma once

#include <cstddef>
#include <vector>

namespace bkq {

// sup_x |F_a(x) - F_b(x)| over the empirical distribution functions of a and b (taken by
// value: they are sorted here). 0 for identical samples, 1 when every value of one lies
// below every value of the other; NaN when either is empty.
double ks_distance(std::vector<double> a, std::vector<double> b);

// The distance two samples of n and m values from one law exceed with probability 5 %:
// 1.358 sqrt((n + m)/(n m)) (the asymptotic Kolmogorov law). NaN when n or m is 0.
double ks_critical_5pct(std::size_t n, std::size_t m);

// The q-quantile of the sample (type 7 of Hyndman & Fan 1996, linear between order
// statistics); NaN when empty.
double quantile(std::vector<double> x, double q);

// The intervals between consecutive times (times sorted ascending).
std::vector<double> intervals_of(const std::vector<double>& times);

// The recurrence of the large events from their times (sorted ascending).
struct Recurrence {
  std::size_t count = 0;          // large events
  double count_err = 0;           // Poisson: sqrt(count)
  std::size_t intervals = 0;      // count - 1
  double mean = 0, mean_err = 0;  // mean interval, s / sqrt(n)      (NaN below 2 intervals)
  double cov = 0, cov_err = 0;    // s / mean and its delta-method error (Pébay 2008 moments)
};
Recurrence recurrence_of(const std::vector<double>& times);

// Several runs of one scene pooled: the intervals within each run (each run's times sorted
// ascending; none across two runs), and their recurrence (the count is the sum).
std::vector<double> intervals_of_runs(const std::vector<std::vector<double>>& times);
Recurrence recurrence_of_runs(const std::vector<std::vector<double>>& times);

}  // namespace bkq
