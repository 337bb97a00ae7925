// Two-sample distances and the recurrence of large events (catalog_compare.hpp).
#include "stats/catalog_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stats/seismicity/moments.hpp"

namespace bkq {

double ks_distance(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  std::size_t i = 0, j = 0;
  double d = 0;
  // Walk the pooled values in order; after every value (all of its ties) compare the CDFs.
  while (i < a.size() || j < b.size()) {
    const double x = j == b.size() ? a[i] : i == a.size() ? b[j] : std::min(a[i], b[j]);
    while (i < a.size() && a[i] == x) ++i;
    while (j < b.size() && b[j] == x) ++j;
    d = std::max(d, std::abs(static_cast<double>(i) / na - static_cast<double>(j) / nb));
  }
  return d;
}

double ks_critical_5pct(std::size_t n, std::size_t m) {
  if (n == 0 || m == 0) return std::numeric_limits<double>::quiet_NaN();
  const double dn = static_cast<double>(n), dm = static_cast<double>(m);
  return 1.358 * std::sqrt((dn + dm) / (dn * dm));
}

double quantile(std::vector<double> x, double q) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(x.begin(), x.end());
  const double h = std::clamp(q, 0.0, 1.0) * static_cast<double>(x.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, x.size() - 1);
  return x[lo] + (h - static_cast<double>(lo)) * (x[hi] - x[lo]);
}

std::vector<double> intervals_of(const std::vector<double>& times) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < times.size(); ++i) dt.push_back(times[i] - times[i - 1]);
  return dt;
}

std::vector<double> intervals_of_runs(const std::vector<std::vector<double>>& times) {
  std::vector<double> dt;
  for (const std::vector<double>& t : times) {
    const std::vector<double> d = intervals_of(t);
    dt.insert(dt.end(), d.begin(), d.end());
  }
  return dt;
}

Recurrence recurrence_of(const std::vector<double>& times) {
  return recurrence_of_runs({times});
}

Recurrence recurrence_of_runs(const std::vector<std::vector<double>>& times) {
  Recurrence r;
  for (const std::vector<double>& t : times) r.count += t.size();
  r.count_err = std::sqrt(static_cast<double>(r.count));
  seis::Moments m;
  for (const double dt : intervals_of_runs(times)) m.add(dt);
  r.intervals = static_cast<std::size_t>(m.n());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.mean = r.intervals >= 2 ? m.mean() : nan;
  r.mean_err = r.intervals >= 2 ? std::sqrt(m.variance() / static_cast<double>(m.n())) : nan;
  r.cov = r.intervals >= 2 ? m.cov() : nan;
  r.cov_err = r.intervals >= 2 ? m.cov_err() : nan;
  return r;
}

}  // namespace bkq
