// Implementation of the Gutenberg-Richter fits (see gutenberg_richter.hpp for the
// estimators and their sources). All likelihood estimates share one structure: the
// model fixes the mean m(b) of (mu - window start), the MLE solves m(b) = observed mean,
// and the error is the standard error of the mean over |m'(b)| (Shi & Bolt 1982).
#include "stats/gutenberg_richter.hpp"
#include "core/format.hpp"

#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.hpp"

namespace bkq {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// h(x) = 1/x - 1/(e^x - 1): the mean of a unit-width truncated exponential is h(b).
double h(double x) {
  if (std::fabs(x) < 1e-3) return 0.5 - x / 12 + x * x * x / 720;
  if (x > 700) return 1 / x;
  if (x < -700) return 1 / x + 1;
  return 1 / x - 1 / std::expm1(x);
}
double h_prime(double x) {
  if (std::fabs(x) < 1e-3) return -1.0 / 12 + x * x / 240;
  if (std::fabs(x) > 700) return -1 / (x * x);
  return -1 / (x * x) + 1 / (std::expm1(x) * -std::expm1(-x));
}

// Mean of (mu - a) and its derivative for the four models. D = window length, w = bin
// width (0: continuous). Binned means are of (bin centre - first bin centre).
struct Model {
  double D;  // +inf when untruncated
  double w;  // 0 when unbinned
  double m(double b) const {
    const double cont = std::isinf(D) ? 1 / b : D * h(b * D);
    return w > 0 ? cont - w * h(b * w) : cont;
  }
  double dm(double b) const {
    const double cont = std::isinf(D) ? -1 / (b * b) : D * D * h_prime(b * D);
    return w > 0 ? cont - w * w * h_prime(b * w) : cont;
  }
};
// Note on the binned untruncated mean: E[w j] = w/(e^{bw} - 1) = 1/b - w h(bw); for the
// truncated one with J = D/w bins: w/(e^{bw}-1) - D/(e^{bD}-1) = D h(bD) - w h(bw).

double solve_b(const Model& model, double m_obs) {
  if (!(m_obs > 0)) return kInf;  // every event in the first bin / at the threshold
  if (std::isinf(model.D)) {
    // Closed forms: Aki 1965 (continuous), Tinti & Mulargia 1987 (binned), base e.
    return model.w > 0 ? std::log1p(model.w / m_obs) / model.w : 1 / m_obs;
  }
  // Truncated: m(b) decreases from D - w (b -> -inf) to 0 (b -> +inf). Bisection.
  if (m_obs >= model.D - model.w) return -kInf;
  double lo = -1, hi = 1;
  while (model.m(hi) > m_obs && hi < 1e8) hi *= 2;
  while (model.m(lo) < m_obs && lo > -1e8) lo *= 2;
  for (int i = 0; i < 300 && hi - lo > 1e-15 * std::max(1.0, std::fabs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (model.m(mid) > m_obs ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

BEstimate estimate(const Model& model, std::int64_t n, double mean_minus_a, double var_sum) {
  BEstimate e;
  e.n = n;
  e.b = solve_b(model, mean_minus_a);
  // Shi & Bolt 1982: standard error of the mean, sqrt(sum (mu - <mu>)^2 / (n (n-1))).
  const double se_mean = std::sqrt(std::max(0.0, var_sum) / (static_cast<double>(n) * (n - 1)));
  e.err = std::isfinite(e.b) ? se_mean / std::fabs(model.dm(e.b)) : kNaN;
  return e;
}

struct Line {
  double slope = kNaN, intercept = kNaN, slope_err = kNaN, ssr = kInf;
  std::size_t n = 0;
};
// Weighted least squares y = intercept + slope x.
Line weighted_line(const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<double>& wt, std::size_t begin, std::size_t end) {
  Line l;
  l.n = end - begin;
  if (l.n < 2) return l;
  double W = 0, sx = 0, sy = 0;
  for (std::size_t i = begin; i < end; ++i) {
    W += wt[i];
    sx += wt[i] * x[i];
    sy += wt[i] * y[i];
  }
  const double xm = sx / W, ym = sy / W;
  double sxx = 0, sxy = 0;
  for (std::size_t i = begin; i < end; ++i) {
    sxx += wt[i] * (x[i] - xm) * (x[i] - xm);
    sxy += wt[i] * (x[i] - xm) * (y[i] - ym);
  }
  if (!(sxx > 0)) return l;
  l.slope = sxy / sxx;
  l.intercept = ym - l.slope * xm;
  l.ssr = 0;
  for (std::size_t i = begin; i < end; ++i) {
    const double r = y[i] - l.intercept - l.slope * x[i];
    l.ssr += wt[i] * r * r;
  }
  l.slope_err = l.n > 2 ? std::sqrt(l.ssr / static_cast<double>(l.n - 2) / sxx) : kNaN;
  return l;
}

std::string fmt(double x) {
  return format_real(x);
}
std::string fmt_short(double x) {  // 3 decimals, for a value in a sentence
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x);
  return buf;
}

}  // namespace

BEstimate aki_mle(std::span<const double> mu, double mu_min, std::optional<double> mu_max) {
  std::int64_t n = 0;
  double sum = 0;
  for (double m : mu)
    if (m >= mu_min && (!mu_max || m < *mu_max)) {
      ++n;
      sum += m - mu_min;
    }
  if (n < 2)
    throw Error("fit window [" + fmt(mu_min) + ", " + (mu_max ? fmt(*mu_max) : "inf") + ") holds " +
                std::to_string(n) + " events; need at least 2");
  const double mean = sum / static_cast<double>(n);
  double var_sum = 0;
  for (double m : mu)
    if (m >= mu_min && (!mu_max || m < *mu_max))
      var_sum += (m - mu_min - mean) * (m - mu_min - mean);
  const Model model{mu_max ? *mu_max - mu_min : kInf, 0};
  return estimate(model, n, mean, var_sum);
}

BEstimate binned_mle(const MagnitudeHistogram& h, std::int64_t k_lo, std::int64_t k_hi,
                     bool truncated) {
  const double w = h.bin_width();
  std::int64_t n = 0;
  double s = 0;
  // Only the populated bins contribute; the loops stay within them whatever the window.
  const std::int64_t k_begin = std::max(k_lo, h.first_bin()), k_end = std::min(k_hi, h.last_bin());
  for (std::int64_t k = k_begin; k <= k_end; ++k) {
    n += h.count(k);
    s += static_cast<double>(h.count(k)) * static_cast<double>(k - k_lo) * w;
  }
  if (n < 2)
    throw Error("fit window [" + fmt(h.mu_low(k_lo)) + ", " + fmt(h.mu_high(k_hi)) + ") holds " +
                std::to_string(n) + " events; need at least 2");
  // Mean of (bin centre - centre of the first bin): Tinti & Mulargia 1987.
  const double mean = s / static_cast<double>(n);
  double var_sum = 0;
  for (std::int64_t k = k_begin; k <= k_end; ++k) {
    const double d = static_cast<double>(k - k_lo) * w - mean;
    var_sum += static_cast<double>(h.count(k)) * d * d;
  }
  const Model model{truncated ? static_cast<double>(k_hi - k_lo + 1) * w : kInf, w};
  return estimate(model, n, mean, var_sum);
}

// Fitted fraction of a window's events at or above bin i (of J bins, width w) for the
// binned exponential law, truncated at the window's top when `truncated`.
static double fitted_survival(double b, double w, double i, double J, bool truncated) {
  if (!truncated) return std::exp(-b * w * i);
  if (std::fabs(b * w * J) < 1e-12) return (J - i) / J;
  return (std::exp(-b * w * i) - std::exp(-b * w * J)) / -std::expm1(-b * w * J);
}

double ks_distance_binned(const MagnitudeHistogram& h, std::int64_t k_lo, std::int64_t k_hi,
                          double b, bool truncated) {
  const double w = h.bin_width();
  const std::int64_t n = h.count_range(k_lo, k_hi);
  if (n == 0 || !std::isfinite(b)) return kNaN;
  const double J = static_cast<double>(k_hi - k_lo + 1);
  double d = 0;
  std::int64_t above = n;
  // Below the populated bins the empirical survival is 1 and above them 0 while the fitted
  // one decreases, so the largest distance outside them is at their edges: j runs over
  // first_bin..last_bin + 1 only.
  const std::int64_t j_begin = std::max(k_lo + 1, h.first_bin());
  const std::int64_t j_end = std::min(k_hi + 1, h.last_bin() + 1);
  for (std::int64_t j = j_begin; j <= j_end; ++j) {
    above -= h.count(j - 1);
    const double s_emp = static_cast<double>(above) / static_cast<double>(n);
    const double i = static_cast<double>(j - k_lo);
    const double s_fit = fitted_survival(b, w, i, J, truncated);
    d = std::max(d, std::fabs(s_emp - s_fit));
  }
  return d;
}

GrFit fit_histogram(const MagnitudeHistogram& h, std::optional<double> mu_min,
                    std::optional<double> mu_max, const GrFitOptions& opt) {
  GrFit f;
  f.bin_width = h.bin_width();
  f.n_total = h.events();
  if (h.events() < 2)
    throw Error("need at least 2 events to fit, found " + std::to_string(h.events()));
  const double w = h.bin_width();
  constexpr double eps = 1e-9;
  const auto poll = [&opt] {
    if (opt.cancelled && opt.cancelled()) throw FitCancelled();
  };
  // Bin indices far from the int64 limits (a bin width of 1e-300 puts every magnitude in
  // the lowest one), so that k +- kMaxFitBins and k * w are exact and no loop wraps round.
  constexpr std::int64_t kMaxBinIndex = std::int64_t{1} << 52;
  if (h.first_bin() < -kMaxBinIndex || h.last_bin() > kMaxBinIndex)
    throw Error("the bin width " + fmt(w) + " is too small for the magnitudes " + fmt(h.min_mu()) +
                " .. " + fmt(h.max_mu()));
  const std::int64_t span = h.last_bin() - h.first_bin() + 1;
  if (span > kMaxFitBins)
    throw Error("the magnitudes " + fmt(h.min_mu()) + " .. " + fmt(h.max_mu()) + " span " +
                std::to_string(span) + " bins of width " + fmt(w) + ", more than the " +
                std::to_string(kMaxFitBins) + " a fit covers; use a wider bin width");
  // A limit must be finite and within kMaxFitBins bins of the magnitudes, so that the bin
  // indices below are exact integers and the window's loops are short.
  const auto check_limit = [&](const char* name, double v) {
    if (!std::isfinite(v))
      throw Error(std::string("fit window: ") + name + " = " + fmt(v) + " is not a finite number");
    const double k = v / w, lo = static_cast<double>(h.first_bin() - kMaxFitBins),
                 hi = static_cast<double>(h.last_bin() + kMaxFitBins);
    if (!(k >= lo && k <= hi))
      throw Error(std::string("fit window: ") + name + " = " + fmt(v) + " lies more than " +
                  std::to_string(kMaxFitBins) + " bins of width " + fmt(w) +
                  " from the magnitudes " + fmt(h.min_mu()) + " .. " + fmt(h.max_mu()));
  };
  if (mu_min) check_limit("mu_min", *mu_min);
  if (mu_max) check_limit("mu_max", *mu_max);

  // Explicit limits, snapped inward to whole bins.
  std::optional<std::int64_t> k_hi_given, k_lo_given;
  if (mu_max) {
    k_hi_given = static_cast<std::int64_t>(std::floor(*mu_max / w + eps)) - 1;
    if (std::fabs(h.mu_high(*k_hi_given) - *mu_max) > eps * std::max(1.0, std::fabs(*mu_max)))
      f.notes.push_back("mu_max " + fmt(*mu_max) + " snapped down to the bin edge " +
                        fmt(h.mu_high(*k_hi_given)));
  }
  if (mu_min) {
    k_lo_given = static_cast<std::int64_t>(std::ceil(*mu_min / w - eps));
    if (std::fabs(h.mu_low(*k_lo_given) - *mu_min) > eps * std::max(1.0, std::fabs(*mu_min)))
      f.notes.push_back("mu_min " + fmt(*mu_min) + " snapped up to the bin edge " +
                        fmt(h.mu_low(*k_lo_given)));
  }
  // The likelihood is truncated at mu_max when mu_max was given, or when the automatic
  // window ends below the largest populated bin (events above it are left out).
  auto truncated_at = [&](std::int64_t top) { return mu_max.has_value() || top < h.last_bin(); };

  std::int64_t k_lo = k_lo_given.value_or(h.first_bin());
  std::int64_t k_hi = k_hi_given.value_or(h.last_bin());
  f.window_auto = !mu_min;
  f.mu_max_auto = !mu_max;
  std::string no_window;  // why no acceptable window exists (empty: one does)
  if (!mu_min || !mu_max) {
    if (span > kMaxScanBins)
      throw Error("automatic fit window: the magnitudes " + fmt(h.min_mu()) + " .. " +
                  fmt(h.max_mu()) + " span " + std::to_string(span) + " bins of width " + fmt(w) +
                  ", more than the " + std::to_string(kMaxScanBins) +
                  " the window search covers; use a wider bin width or give mu_min and mu_max");
    // The rule (docs/explanation/b-fit.md): among the windows whose ends sit on populated
    // bins (unless given), with >= min_window_bins bins, >= min_tail events and >= 2
    // populated bins, keep those (1) in which, unless mu_max is given, the running sum S
    // of the counts over smooth_width never rises to more than rise_factor times its
    // lowest value further down the window (at rise_sigma Poisson standard deviations): no
    // bump, and no climbing out of the dip before it; (2) whose binned MLE b is > 0; (3) whose KS
    // distance is within ks_systematic + ks_tolerance / sqrt(n_window). The widest wins
    // (most bins, then most events, then smallest KS distance).
    const std::int64_t first = h.first_bin(), last = h.last_bin();
    std::vector<std::int64_t> prefix(static_cast<std::size_t>(span + 1), 0);  // counts below
    for (std::int64_t i = 0; i < span; ++i)
      prefix[static_cast<std::size_t>(i + 1)] =
          prefix[static_cast<std::size_t>(i)] + h.count(first + i);
    const auto below = [&](std::int64_t k) {  // events in bins < k
      return prefix[static_cast<std::size_t>(std::clamp(k, first, last + 1) - first)];
    };
    const std::int64_t half =
        std::max<std::int64_t>(1, std::llround(0.5 * (opt.smooth_width / w - 1)));
    const auto S = [&](std::int64_t k) {
      return static_cast<double>(below(k + half + 1) - below(k - half));
    };
    const std::int64_t lo_first = k_lo_given.value_or(first);
    const std::int64_t lo_last = k_lo_given.value_or(last);
    const std::int64_t hi_first = k_hi_given.value_or(first);
    const std::int64_t hi_last = k_hi_given.value_or(last);
    struct Pick {
      std::int64_t lo, hi, n;
      double d;
    };
    // First the cheap conditions (ends, size, no rise) over every window, in the order
    // lo, then hi; then the fits (binned MLE, KS distance), widest windows first: once a
    // width holds an accepted window no narrower one can win, so the rest are not fitted.
    // Equal widths keep the lo order, so ties go to the same window as in one pass.
    std::vector<Pick> cands;
    for (std::int64_t lo = lo_first; lo <= lo_last; ++lo) {
      if (!k_lo_given && h.count(lo) == 0) continue;
      poll();
      double s_min = S(lo);
      for (std::int64_t hi = lo; hi <= hi_last; ++hi) {
        const double s = S(hi);
        // A rise inside [lo, hi] stays inside every wider window: stop here. A given mu_max
        // includes what lies below it, rise or not.
        if (!k_hi_given && s > opt.rise_factor * s_min &&
            s - s_min > opt.rise_sigma * std::sqrt(s + s_min))
          break;
        s_min = std::min(s_min, s);
        if (hi < hi_first || hi - lo + 1 < opt.min_window_bins) continue;
        if (!k_hi_given && h.count(hi) == 0) continue;
        const std::int64_t n = below(hi + 1) - below(lo);
        if (n < opt.min_tail) continue;
        int populated = 0;
        for (std::int64_t j = lo; j <= hi && populated < 2; ++j) populated += h.count(j) > 0;
        if (populated < 2) continue;
        cands.push_back(Pick{lo, hi, n, 0});
      }
    }
    std::stable_sort(cands.begin(), cands.end(),
                     [](const Pick& a, const Pick& b) { return a.hi - a.lo > b.hi - b.lo; });
    std::optional<Pick> pick;
    const auto candidates = static_cast<std::int64_t>(cands.size());
    std::int64_t positive = 0;
    for (const Pick& c : cands) {
      if (pick && c.hi - c.lo < pick->hi - pick->lo) break;
      poll();
      const bool tr = truncated_at(c.hi);
      const BEstimate e = binned_mle(h, c.lo, c.hi, tr);
      if (!(e.b > 0) || !std::isfinite(e.err)) continue;
      ++positive;
      const double d = ks_distance_binned(h, c.lo, c.hi, e.b, tr);
      if (!(d <= opt.ks_systematic + opt.ks_tolerance / std::sqrt(static_cast<double>(c.n))))
        continue;
      if (!pick || c.n > pick->n || (c.n == pick->n && d < pick->d))
        pick = Pick{c.lo, c.hi, c.n, d};
    }
    if (pick) {
      k_lo = pick->lo;
      k_hi = pick->hi;
    } else if (candidates == 0) {
      no_window = "no window with >= " + std::to_string(opt.min_tail) +
                  " events and >= " + std::to_string(opt.min_window_bins) +
                  " bins lies below a rise of the distribution";
    } else if (positive == 0) {
      no_window = "the events do not decrease with magnitude in any window (b <= 0)";
    } else {
      no_window = "no window is fitted by one power law to within the KS tolerance";
    }
  }
  poll();
  f.truncated = truncated_at(k_hi);
  if (k_hi - k_lo + 1 > kMaxFitBins)
    throw Error("fit window [" + fmt(h.mu_low(k_lo)) + ", " + fmt(h.mu_high(k_hi)) + ") spans " +
                std::to_string(k_hi - k_lo + 1) + " bins of width " + fmt(w) + ", more than the " +
                std::to_string(kMaxFitBins) + " a fit covers");
  if (k_hi < k_lo)
    throw Error("fit window [" + fmt(h.mu_low(k_lo)) + ", " + fmt(h.mu_high(k_hi)) + ") is empty");
  f.mu_min = h.mu_low(k_lo);
  f.mu_max = h.mu_high(k_hi);
  f.n_in_window = h.count_range(k_lo, k_hi);

  const BEstimate e = binned_mle(h, k_lo, k_hi, f.truncated);
  f.b_mle = e.b;
  f.b_mle_err = e.err;
  if (!std::isfinite(e.b))
    f.notes.push_back("b_mle is unbounded: the window's events fill one bin");
  if (no_window.empty() && !(e.b > 0))
    no_window =
        "b_mle = " + fmt_short(e.b) + " on the window: the events do not decrease with magnitude";
  f.ks_distance = ks_distance_binned(h, k_lo, k_hi, e.b, f.truncated);
  const double nw = static_cast<double>(f.n_in_window);
  f.ln_A = std::log(nw) + f.b_mle * f.mu_min;
  if (f.truncated) f.ln_A -= std::log(-std::expm1(-f.b_mle * (f.mu_max - f.mu_min)));

  // Unbinned estimate from the exact sums when the window holds every event.
  f.b_aki = f.b_aki_err = kNaN;
  if (h.exact_moments() && !f.truncated && k_lo <= h.first_bin()) {
    const double n = static_cast<double>(h.events());
    const double mean = h.mean_mu();
    const double var_sum = std::max(0.0, h.sum_mu2() - n * mean * mean);
    const BEstimate a = estimate(Model{kInf, 0}, h.events(), mean - f.mu_min, var_sum);
    f.b_aki = a.b;
    f.b_aki_err = a.err;
  }

  // Least squares on ln R at the lower bin edges, weights R (Poisson).
  {
    std::vector<double> x, y, wt;
    std::int64_t r = h.R(k_hi + 1);  // R(k), kept as a running sum from the top down
    for (std::int64_t k = k_hi; k >= k_lo; --k) {
      r += h.count(k);
      if (r <= 0) continue;
      x.push_back(h.mu_low(k));
      y.push_back(std::log(static_cast<double>(r)));
      wt.push_back(static_cast<double>(r));
    }
    std::reverse(x.begin(), x.end());
    std::reverse(y.begin(), y.end());
    std::reverse(wt.begin(), wt.end());
    const Line l = weighted_line(x, y, wt, 0, x.size());
    f.b_lsq = -l.slope;
    f.b_lsq_err = l.slope_err;
  }

  // Two power laws on ln D (Ferre 2018 eq. 2.10), crossover scanned over the bin edges.
  {
    std::vector<double> x, y, wt;
    std::vector<std::int64_t> kk;
    for (std::int64_t k = std::max(k_lo, h.first_bin()); k <= h.last_bin(); ++k) {
      if (h.count(k) <= 0) continue;
      x.push_back(0.5 * (h.mu_low(k) + h.mu_high(k)));
      y.push_back(std::log(h.D(k)));
      wt.push_back(static_cast<double>(h.count(k)));
      kk.push_back(k);
    }
    constexpr std::size_t kMinSide = 3;
    double best = kInf;
    const bool scan = x.size() <= static_cast<std::size_t>(kMaxScanBins);
    for (std::size_t s = kMinSide; scan && x.size() >= 2 * kMinSide && s + kMinSide <= x.size();
         ++s) {
      poll();
      const Line a = weighted_line(x, y, wt, 0, s);
      const Line b = weighted_line(x, y, wt, s, x.size());
      if (!std::isfinite(a.slope) || !std::isfinite(b.slope)) continue;
      if (a.ssr + b.ssr < best) {
        best = a.ssr + b.ssr;
        f.two_law_ok = true;
        f.two_law_b1 = -a.slope;
        f.two_law_b2 = -b.slope;
        f.two_law_mu_cross = h.mu_low(kk[s]);
        f.two_law_moment_cross = std::exp(f.two_law_mu_cross);
        f.two_law_mu_low = h.mu_low(k_lo);
        f.two_law_mu_high = h.mu_high(h.last_bin());
        f.two_law_ln_A1 = a.intercept + a.slope * f.two_law_mu_cross;
        f.two_law_ln_A2 = b.intercept + b.slope * f.two_law_mu_high;
      }
    }
    if (!scan)
      f.notes.push_back("two-power-law fit skipped: more than " + std::to_string(kMaxScanBins) +
                        " populated bins above mu_min");
    else if (!f.two_law_ok)
      f.notes.push_back("two-power-law fit skipped: fewer than 6 populated bins above mu_min");
  }

  // Large-event excess over the fitted line R = A e^{-b mu}. Inside a truncated window
  // the line is normalised to the window's events, so the scan stops at mu_max there.
  if (std::isfinite(f.b_mle)) {
    // Edges below the populated bins are not scanned (the loops stay within them).
    const std::int64_t floor_k = std::max(f.truncated ? k_hi + 1 : k_lo, h.first_bin());
    std::vector<std::int64_t> R_of(static_cast<std::size_t>(span + 1), 0);  // R(first_bin + i)
    for (std::int64_t i = span - 1; i >= 0; --i)
      R_of[static_cast<std::size_t>(i)] =
          R_of[static_cast<std::size_t>(i + 1)] + h.count(h.first_bin() + i);
    const auto R = [&](std::int64_t k) {
      return R_of[static_cast<std::size_t>(k - h.first_bin())];
    };
    auto significant = [&](std::int64_t k) {
      const auto r = R(k);
      const double expected = std::exp(f.ln_A - f.b_mle * h.mu_low(k));
      if (r <= 0 || !(static_cast<double>(r) > expected)) return false;
      // P(X >= r) for Poisson X of mean `expected` is the regularised lower incomplete
      // gamma function P(r, expected).
      return boost::math::gamma_p(static_cast<double>(r), expected) < opt.excess_tail_probability;
    };
    // Skip isolated non-significant bins at the very top (a single largest event), then
    // take the contiguous significant run downwards.
    std::int64_t k = h.last_bin();
    while (k >= floor_k && !significant(k)) --k;
    for (; k >= floor_k && significant(k); --k) {
      f.excess_found = true;
      f.excess_mu = h.mu_low(k);
      f.excess_observed = R(k);
      f.excess_expected = std::exp(f.ln_A - f.b_mle * h.mu_low(k));
      f.excess_count =
          std::max(f.excess_count, static_cast<double>(f.excess_observed) - f.excess_expected);
    }
  }
  // No acceptable window: no b at all (a headline b is never <= 0 or from a rejected
  // window); the window fields keep the range that was looked at, the two-law fit stays.
  if (!no_window.empty()) {
    f.b_ok = false;
    f.no_b_reason = no_window;
    f.b_mle = f.b_mle_err = f.b_aki = f.b_aki_err = f.b_lsq = f.b_lsq_err = kNaN;
    f.ln_A = f.ks_distance = kNaN;
    f.excess_found = false;
    f.excess_observed = 0;
    f.excess_expected = f.excess_count = 0;
  }
  return f;
}

void add_unbinned(GrFit& fit, std::span<const double> mu) {
  if (!fit.b_ok) return;
  const BEstimate a =
      aki_mle(mu, fit.mu_min, fit.truncated ? std::optional<double>(fit.mu_max) : std::nullopt);
  fit.b_aki = a.b;
  fit.b_aki_err = a.err;
}

GrFit fit_magnitudes(std::span<const double> mu, double bin_width, std::optional<double> mu_min,
                     std::optional<double> mu_max, const GrFitOptions& opt) {
  MagnitudeHistogram h(bin_width);
  for (double m : mu) h.add(m);
  GrFit f = fit_histogram(h, mu_min, mu_max, opt);
  add_unbinned(f, mu);
  return f;
}

}  // namespace bkq
