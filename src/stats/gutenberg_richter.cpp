// Implementation of the Gutenberg-Richter fits (see gutenberg_richter.hpp for the
// estimators and their sources). All likelihood estimates share one structure: the
// model fixes the mean m(b) of (mu - window start), the MLE solves m(b) = observed mean,
// and the error is the standard error of the mean over |m'(b)| (Shi & Bolt 1982).
#include "stats/gutenberg_richter.hpp"
#include "core/format.hpp"

#include <algorithm>
#include <array>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <tuple>
#include <utility>

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
std::string fmt3(double x) {  // 3 significant digits (a p-value)
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
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

namespace {

// The binned MLE on bins lo..hi, NaN when they hold fewer than 2 events.
BEstimate mle_or_nan(const MagnitudeHistogram& h, std::int64_t lo, std::int64_t hi,
                     bool truncated) {
  if (hi < lo || h.count_range(lo, hi) < 2) return {kNaN, kNaN, 0};
  return binned_mle(h, lo, hi, truncated);
}

struct AutoWindow {
  bool ok = false;
  std::int64_t lo = 0, hi = 0;
  std::string reason;      // why no window, when !ok
  std::string top_reason;  // GrFit::mu_max_reason
  std::vector<std::string> notes;
};

// Gaps (GrFitOptions::gap_width): runs [begin, end] of at least gap_width of empty bins
// within bins lo..hi that a density not rising above them would have filled: with m events
// in the B bins from the run's end to the last populated bin up to hi, a non-increasing
// density puts at least m / B expected events in each bin of the run, so the run is a gap
// when its length times m / B is at least gap_expected.
std::vector<std::pair<std::int64_t, std::int64_t>> find_gaps(const MagnitudeHistogram& h,
                                                             std::int64_t lo, std::int64_t hi,
                                                             const GrFitOptions& opt) {
  std::vector<std::pair<std::int64_t, std::int64_t>> gaps;
  const std::int64_t G = std::max<std::int64_t>(1, std::llround(opt.gap_width / h.bin_width()));
  lo = std::max(lo, h.first_bin());
  hi = std::min(hi, h.last_bin());
  for (std::int64_t k = lo; k <= hi;) {
    if (h.count(k) != 0) {
      ++k;
      continue;
    }
    std::int64_t e = k;
    while (e + 1 <= hi && h.count(e + 1) == 0) ++e;
    if (e - k + 1 >= G && e < hi) {
      std::int64_t top = hi;
      while (top > e && h.count(top) == 0) --top;
      const auto m = static_cast<double>(h.count_range(e + 1, top));
      if (top > e &&
          static_cast<double>(e - k + 1) * m / static_cast<double>(top - e) >= opt.gap_expected)
        gaps.emplace_back(k, e);
    }
    k = e + 1;
  }
  return gaps;
}

// The first bin k in start..end at which the running sum S of the counts over
// smooth_width climbs to rise_factor times its lowest value from start on, by rise_sigma
// Poisson standard deviations (GrFitOptions::rise_factor); nullopt when none does.
std::optional<std::int64_t> first_rise(const MagnitudeHistogram& h, std::int64_t start,
                                       std::int64_t end, const GrFitOptions& opt) {
  const double w = h.bin_width();
  const std::int64_t first = h.first_bin(), last = h.last_bin();
  const std::int64_t half =
      std::max<std::int64_t>(1, std::llround(0.5 * (opt.smooth_width / w - 1)));
  const auto S = [&](std::int64_t k) {
    return static_cast<double>(h.count_range(std::max(first, k - half), std::min(last, k + half)));
  };
  double s_min = S(start);
  for (std::int64_t k = start; k <= std::min(end, last); ++k) {
    const double s = S(k);
    if (s > opt.rise_factor * s_min && s - s_min > opt.rise_sigma * std::sqrt(s + s_min)) return k;
    s_min = std::min(s_min, s);
  }
  return std::nullopt;
}

// The goodness-of-fit tolerance of a window of n events (GrFitOptions::ks_tolerance).
double ks_limit(std::int64_t n, const GrFitOptions& opt) {
  return opt.ks_systematic + opt.ks_tolerance / std::sqrt(static_cast<double>(n));
}

// The automatic window (docs/how-to/fit-window.md): a ceiling below any rise of D(mu)
// (the dip and bump of large events), the lower cut by b-value stability, the upper cut
// by the departure test of the events above, each cut found again once with the other's
// result. A given end stays where it is.
template <class Poll>
AutoWindow automatic_window(const MagnitudeHistogram& h, std::optional<std::int64_t> lo_given,
                            std::optional<std::int64_t> hi_given, const GrFitOptions& opt,
                            const Poll& poll) {
  AutoWindow r;
  const double w = h.bin_width();
  const std::int64_t first = h.first_bin(), last = h.last_bin();
  const auto bins_of = [w](double width) {
    return std::max<std::int64_t>(1, std::llround(width / w));
  };
  const auto truncated = [&](std::int64_t hi) { return hi_given.has_value() || hi < last; };
  const auto big_enough = [&](std::int64_t lo, std::int64_t hi) {
    return hi - lo + 1 >= opt.min_window_bins && h.count_range(lo, hi) >= opt.min_tail;
  };
  // Goodness of fit (Wiemer & Wyss 2000, as a KS distance between the binned survival
  // functions): a share ks_systematic of the window's events plus the statistical
  // ks_tolerance / sqrt(n).
  const auto fits = [&](std::int64_t lo, std::int64_t hi, double b) {
    return ks_distance_binned(h, lo, hi, b, truncated(hi)) <= ks_limit(h.count_range(lo, hi), opt);
  };

  // Ceiling of a window starting at `start`: below the first gap above it (find_gaps),
  // and below the first rise (first_rise) of the running sum of the counts from there;
  // the highest populated bin before either, with the reason.
  const std::vector<std::pair<std::int64_t, std::int64_t>> gaps = find_gaps(h, first, last, opt);
  struct Ceiling {
    std::int64_t top;
    const char* reason;
  };
  const auto ceiling_of = [&](std::int64_t start) -> Ceiling {
    if (hi_given) return {*hi_given, "given"};
    std::int64_t top = last;
    const char* reason = "end of data";
    for (const auto& g : gaps)
      if (g.first > start) {
        top = g.first - 1;
        reason = "gap";
        break;
      }
    if (const auto k = first_rise(h, start, top, opt)) {
      top = *k - 1;
      reason = "rise";
    }
    while (top > start && h.count(top) == 0) --top;
    return {top, reason};
  };
  const auto ceiling = [&](std::int64_t start) { return ceiling_of(start).top; };

  // Lower cut: for each populated bin edge lo, b from lo + j up to hi (the upper cut, at
  // most lo's ceiling) for j = 0..L; lo is stable when b moves by at most
  // max(stability_db, sigma_b) from each edge to the next. The lowest stable edge wins;
  // when none is, the one whose largest step is the smallest share of its tolerance, with
  // a note.
  const std::int64_t L = bins_of(opt.stability_width);
  std::string fallback_note;  // set by the last lower_cut that found no stable edge
  // How far the last lower_cut got, for the reason when it found no edge: a candidate window
  // large enough, one of those with a finite b > 0.
  bool any_sized = false, any_positive = false;
  // The second try of the lower cut (when no edge passes with the ceiling as each window's
  // top): each candidate's top is where the events above still follow its law (upper_cut,
  // below). A kink below the bump (the dip's shallower slope) makes b drift over windows up
  // to the ceiling from every edge; up to the departure it does not.
  bool by_departure = false;
  std::function<std::optional<std::int64_t>(std::int64_t)> departure_top;
  const auto lower_cut = [&](std::int64_t hi_cap) -> std::optional<std::int64_t> {
    if (lo_given) return lo_given;
    std::optional<std::int64_t> best;
    double best_ratio = kInf;
    any_sized = any_positive = false;
    for (std::int64_t lo = first; lo + L <= hi_cap; ++lo) {
      if (h.count(lo) == 0) continue;
      poll();
      std::int64_t top = ceiling(lo);
      if (by_departure) {
        const auto t = departure_top(lo);
        if (!t) continue;
        top = *t;
      }
      const std::int64_t hi = std::min(hi_cap, top);
      if (hi < lo + L || !big_enough(lo, hi)) continue;
      any_sized = true;
      const BEstimate b0 = mle_or_nan(h, lo, hi, truncated(hi));
      if (!(b0.b > 0) || !std::isfinite(b0.err)) continue;
      any_positive = true;
      // worst: the largest step of b as a share of its tolerance max(db, k sigma_b).
      double worst = 0, prev = b0.b;
      for (std::int64_t j = 1; j <= L && std::isfinite(worst); ++j) {
        const BEstimate bj = mle_or_nan(h, lo + j, hi, truncated(hi));
        worst = std::isfinite(bj.b) && std::isfinite(bj.err)
                    ? std::max(worst, std::fabs(bj.b - prev) /
                                          std::max(opt.stability_db, opt.stability_sigma * bj.err))
                    : kInf;
        prev = bj.b;
      }
      if (worst <= 1 || (by_departure && worst <= opt.stability_relaxed && fits(lo, hi, b0.b)))
        return lo;
      if (worst < best_ratio && fits(lo, hi, b0.b)) {
        best_ratio = worst;
        best = lo;
      }
    }
    fallback_note.clear();
    if (best)
      fallback_note = ("b is stable to within max(" + fmt_short(opt.stability_db) + ", " +
                       fmt_short(opt.stability_sigma) + " sigma_b) from no lower cut; mu_min = " +
                       fmt(h.mu_low(*best)) + " is the most stable (steps up to " +
                       fmt_short(best_ratio) + " times the tolerance)");
    return best;
  };

  // Upper cut: the highest populated top <= lo's ceiling from which the events of the next
  // departure_width still follow the window's law (their own slope within a factor
  // departure_ratio of b, widened by departure_sigma standard errors).
  const std::int64_t D = bins_of(opt.departure_width);
  const auto upper_cut = [&](std::int64_t lo) -> std::optional<std::int64_t> {
    if (hi_given) return hi_given;
    for (std::int64_t hi = ceiling(lo); hi >= lo + opt.min_window_bins - 1; --hi) {
      poll();
      if (h.count(hi) == 0 || !big_enough(lo, hi)) continue;
      const BEstimate bw = mle_or_nan(h, lo, hi, truncated(hi));
      if (!(bw.b > 0) || !std::isfinite(bw.err)) continue;
      const std::int64_t s_hi = std::min(last, hi + D);
      if (h.count_range(hi + 1, s_hi) < opt.departure_min_events || s_hi - hi < 2) return hi;
      const BEstimate bs = mle_or_nan(h, hi + 1, s_hi, true);
      if (!std::isfinite(bs.b) || !std::isfinite(bs.err)) continue;
      const double z = opt.departure_sigma * bs.err;
      if (bs.b >= bw.b / opt.departure_ratio - z && bs.b <= bw.b * opt.departure_ratio + z)
        return hi;
    }
    return std::nullopt;
  };

  departure_top = upper_cut;
  std::optional<std::int64_t> lo = lower_cut(hi_given.value_or(last));
  if (!lo && !hi_given) {
    const bool sized = any_sized, positive = any_positive;
    by_departure = true;  // for the rest of the search
    lo = lower_cut(last);
    if (lo)
      r.notes.push_back("no lower cut keeps b stable on the windows up to the ceiling; mu_min = " +
                        fmt(h.mu_low(*lo)) + " is the lowest edge stable to within " +
                        fmt(opt.stability_relaxed) +
                        " times the tolerance on the windows up to where the events above "
                        "depart from the power law, and its window passes the KS test");
    else {
      any_sized = sized;
      any_positive = positive;
    }
  }
  if (!lo) {
    // Which of the lower cut's tests no candidate passed, in the order they are applied.
    const std::string window = "no window with >= " + std::to_string(opt.min_tail) +
                               " events and >= " + std::to_string(opt.min_window_bins) +
                               " bins (and >= " + format_real(opt.stability_width) +
                               " in mu, the span of the stability test) below a rise of the "
                               "distribution";
    if (!any_sized)
      r.reason = window;
    else if (!any_positive)
      r.reason = window + " has a finite b > 0";
    else
      r.reason = "no lower cut keeps b stable to within max(" + format_real(opt.stability_db) +
                 ", " + format_real(opt.stability_sigma) + " sigma_b) over the " +
                 format_real(opt.stability_width) +
                 " in mu above it, and no window with b > 0 is fitted by one power law to "
                 "within the KS distance " +
                 format_real(opt.ks_systematic) + " + " + format_real(opt.ks_tolerance) +
                 "/sqrt(n)";
    return r;
  }
  // When the events above depart from every top, the shortest window (and a note).
  const auto shortest = [&](std::int64_t from) {
    std::int64_t top = from + opt.min_window_bins - 1;
    while (top < last && (h.count(top) == 0 || h.count_range(from, top) < opt.min_tail)) ++top;
    return top;
  };
  std::optional<std::int64_t> hi = upper_cut(*lo);
  if (const auto lo2 = lower_cut(hi.value_or(shortest(*lo)))) lo = lo2;
  hi = upper_cut(*lo);
  if (!hi) {
    hi = shortest(*lo);
    if (!big_enough(*lo, *hi) || !(mle_or_nan(h, *lo, *hi, truncated(*hi)).b > 0)) {
      r.reason = "no window from mu_min = " + fmt(h.mu_low(*lo)) +
                 " below a rise of the distribution has b > 0";
      return r;
    }
    r.notes.push_back("the events above depart from the power law at every top from mu_min = " +
                      fmt(h.mu_low(*lo)) + "; mu_max is the top of the shortest window");
  }
  const Ceiling c = ceiling_of(*lo);
  r.top_reason = hi_given ? "given" : *hi == c.top ? c.reason : "departure";
  // Goodness of fit of the window found: when it fails, the highest lower top from mu_min
  // whose window passes; when none does, no b.
  const auto b_of = [&](std::int64_t top) { return mle_or_nan(h, *lo, top, truncated(top)).b; };
  if (!hi_given && !fits(*lo, *hi, b_of(*hi))) {
    const double d = ks_distance_binned(h, *lo, *hi, b_of(*hi), truncated(*hi));
    const std::string failed = "the window [" + fmt(h.mu_low(*lo)) + ", " + fmt(h.mu_high(*hi)) +
                               ") fails the goodness-of-fit test (KS distance " + fmt_short(d) +
                               " > " + fmt_short(ks_limit(h.count_range(*lo, *hi), opt)) + ")";
    std::optional<std::int64_t> passing;
    // At least min_window_bins and the stability test's span (in mu, whatever the bin
    // width): a window a few narrow bins wide passes any test.
    const std::int64_t min_bins = std::max(opt.min_window_bins, L);
    for (std::int64_t top = *hi - 1; !hi_given && top >= *lo + min_bins - 1; --top) {
      poll();
      if (h.count(top) == 0 || !big_enough(*lo, top)) continue;
      const double b = b_of(top);
      if (b > 0 && std::isfinite(b) && fits(*lo, top, b)) {
        passing = top;
        break;
      }
    }
    if (!passing) {
      r.reason =
          failed +
          ", and so does every shorter window from mu_min with >= " + std::to_string(opt.min_tail) +
          " events, >= " + std::to_string(opt.min_window_bins) +
          " bins and >= " + fmt(opt.stability_width) + " in mu (KS distance " +
          format_real(opt.ks_systematic) + " + " + format_real(opt.ks_tolerance) + "/sqrt(n))";
      return r;
    }
    r.notes.push_back(failed + "; mu_max lowered to " + fmt(h.mu_high(*passing)) +
                      ", the highest top whose window passes");
    hi = passing;
    r.top_reason = "goodness of fit";
  }
  r.ok = true;
  r.lo = *lo;
  r.hi = *hi;
  if (!fallback_note.empty()) r.notes.push_back(fallback_note);
  return r;
}

// Whether [lo, hi] is one of the windows of the systematic error of the fit on
// [k_lo, k_hi]: its ends within sys_width inside the fit's, on populated bins (or the
// fit's own ends), with >= min_tail events and >= min_window_bins bins.
bool in_sys_set(const MagnitudeHistogram& h, std::int64_t k_lo, std::int64_t k_hi, std::int64_t lo,
                std::int64_t hi, const GrFitOptions& opt) {
  const std::int64_t S = std::max<std::int64_t>(1, std::llround(opt.sys_width / h.bin_width()));
  if (lo < k_lo || lo >= k_lo + S || hi > k_hi || hi <= k_hi - S) return false;
  if ((lo != k_lo && h.count(lo) == 0) || (hi != k_hi && h.count(hi) == 0)) return false;
  return hi - lo + 1 >= opt.min_window_bins && h.count_range(lo, hi) >= opt.min_tail;
}

// Half the range of b over the windows of GrFitOptions::sys_width around [k_lo, k_hi]
// (the window itself included when it fits); with the number of windows.
std::pair<double, std::int64_t> systematic_spread(const MagnitudeHistogram& h, std::int64_t k_lo,
                                                  std::int64_t k_hi, bool truncated,
                                                  const GrFitOptions& opt) {
  const std::int64_t S = std::max<std::int64_t>(1, std::llround(opt.sys_width / h.bin_width()));
  double lo_b = kInf, hi_b = -kInf;
  std::int64_t n = 0;
  for (std::int64_t lo = k_lo; lo < k_lo + S; ++lo)
    for (std::int64_t hi = k_hi; hi > k_hi - S; --hi) {
      if (!in_sys_set(h, k_lo, k_hi, lo, hi, opt)) continue;
      const BEstimate e = mle_or_nan(h, lo, hi, truncated || hi < h.last_bin());
      if (!(e.b > 0) || !std::isfinite(e.b)) continue;
      lo_b = std::min(lo_b, e.b);
      hi_b = std::max(hi_b, e.b);
      ++n;
    }
  return {n > 0 ? 0.5 * (hi_b - lo_b) : kNaN, n};
}

}  // namespace

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
    const AutoWindow win = automatic_window(h, k_lo_given, k_hi_given, opt, poll);
    if (win.ok) {
      k_lo = win.lo;
      k_hi = win.hi;
      f.mu_max_reason = win.top_reason;
      f.notes.insert(f.notes.end(), win.notes.begin(), win.notes.end());
    } else {
      no_window = win.reason;
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
  std::tie(f.b_mle_sys_err, f.sys_windows) = systematic_spread(h, k_lo, k_hi, f.truncated, opt);
  if (!std::isfinite(e.b))
    f.notes.push_back("b_mle is unbounded: the window's events fill one bin");
  if (no_window.empty() && !(e.b > 0))
    no_window =
        "b_mle = " + fmt_short(e.b) + " on the window: the events do not decrease with magnitude";
  f.ks_distance = ks_distance_binned(h, k_lo, k_hi, e.b, f.truncated);
  if (mu_min && mu_max) f.mu_max_reason = "given";
  // A window given by the user is fitted whatever it crosses, and warned about.
  if ((mu_min || mu_max) && no_window.empty()) {
    for (const auto& g : find_gaps(h, k_lo, k_hi, opt))
      f.warnings.push_back("the window crosses a gap: no events in [" + fmt(h.mu_low(g.first)) +
                           ", " + fmt(h.mu_high(g.second)) + "), " +
                           std::to_string(g.second - g.first + 1) + " empty bins with " +
                           std::to_string(h.count_range(g.second + 1, k_hi)) +
                           " events above them in the window");
    if (const auto k = first_rise(h, std::max(k_lo, h.first_bin()), k_hi, opt))
      f.warnings.push_back(
          "the window takes in a rise of the distribution at mu = " + fmt(h.mu_low(*k)) +
          " (the counts over " + fmt(opt.smooth_width) + " in mu climb to more than " +
          fmt(opt.rise_factor) + " times their lowest value below)");
    const double limit = ks_limit(f.n_in_window, opt);
    if (std::isfinite(f.ks_distance) && f.ks_distance > limit)
      f.warnings.push_back("the window fails the goodness-of-fit test: KS distance " +
                           fmt_short(f.ks_distance) + " > " + fmt_short(limit) + " (" +
                           fmt(opt.ks_systematic) + " + " + fmt(opt.ks_tolerance) + "/sqrt(n))");
  }
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
    // Its own test: the counts the line implies in each bin, R(k) - R(k + 1), against the
    // observed ones (Pearson chi^2 over the bins expecting >= 5 events, 2 parameters).
    double chi2 = 0;
    std::int64_t used = 0;
    for (std::int64_t k = k_lo; k <= k_hi && std::isfinite(l.slope); ++k) {
      const double e = std::exp(l.intercept + l.slope * h.mu_low(k)) -
                       std::exp(l.intercept + l.slope * h.mu_high(k));
      if (!(e >= 5)) continue;
      const double d = static_cast<double>(h.count(k)) - e;
      chi2 += d * d / e;
      ++used;
    }
    const double p =
        used > 2 ? boost::math::gamma_q(0.5 * static_cast<double>(used - 2), 0.5 * chi2) : kNaN;
    if (!(p >= opt.secondary_p)) {
      f.b_lsq_reason =
          used > 2
              ? "the least-squares line of ln R fails its own test: the counts it implies "
                "differ from the window's by chi^2 = " +
                    fmt_short(chi2) + " over " + std::to_string(used) + " bins (p = " + fmt3(p) +
                    " < " + fmt_short(opt.secondary_p) + ")"
              : "fewer than 3 bins expecting >= 5 events: the least-squares line is not tested";
      f.b_lsq = f.b_lsq_err = kNaN;
    }
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
    std::size_t best_split = 0;
    std::pair<Line, Line> best_lines;
    const bool scan = x.size() <= static_cast<std::size_t>(kMaxScanBins);
    for (std::size_t s = kMinSide; scan && x.size() >= 2 * kMinSide && s + kMinSide <= x.size();
         ++s) {
      poll();
      const Line a = weighted_line(x, y, wt, 0, s);
      const Line b = weighted_line(x, y, wt, s, x.size());
      if (!std::isfinite(a.slope) || !std::isfinite(b.slope)) continue;
      if (a.ssr + b.ssr < best) {
        best = a.ssr + b.ssr;
        best_split = s;
        best_lines = {a, b};
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
      f.two_law_reason = "two-power-law fit skipped: more than " + std::to_string(kMaxScanBins) +
                         " populated bins above mu_min";
    else if (!f.two_law_ok)
      f.two_law_reason = "two-power-law fit skipped: fewer than 6 populated bins above mu_min";
    // Its own test: the Poisson deviance of the bins' counts against the counts the two
    // lines imply, chi^2 with (bins - 4) degrees of freedom.
    if (f.two_law_ok) {
      const double dof = static_cast<double>(x.size()) - 4;
      double dev = 0;
      for (std::size_t i = 0; i < x.size(); ++i) {
        const Line& l = i < best_split ? best_lines.first : best_lines.second;
        const double r = y[i] - (l.intercept + l.slope * x[i]);  // ln(c / expected)
        const double c = wt[i], expected = c * std::exp(-r);
        dev += 2 * (c * r - (c - expected));
      }
      best = dev;
      const double p = dof > 0 ? boost::math::gamma_q(0.5 * dof, 0.5 * dev) : kNaN;
      if (!(p >= opt.secondary_p)) {
        f.two_law_ok = false;
        f.two_law_reason =
            "two power laws fail their own test: Poisson deviance " + fmt_short(best) + " for " +
            std::to_string(static_cast<std::int64_t>(dof)) + " degrees of freedom (p = " + fmt3(p) +
            " < " + fmt_short(opt.secondary_p) + ")";
        f.two_law_b1 = f.two_law_b2 = f.two_law_mu_cross = f.two_law_moment_cross = kNaN;
        f.two_law_ln_A1 = f.two_law_ln_A2 = f.two_law_mu_low = f.two_law_mu_high = kNaN;
      }
    }
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
    f.b_mle = f.b_mle_err = f.b_mle_sys_err = f.b_aki = f.b_aki_err = f.b_lsq = f.b_lsq_err = kNaN;
    f.ln_A = f.ks_distance = kNaN;
    f.excess_found = false;
    f.excess_observed = 0;
    f.excess_expected = f.excess_count = 0;
  }
  return f;
}

void add_unbinned(GrFit& fit, std::span<const double> mu, const GrFitOptions& opt) {
  if (!fit.b_ok) {
    fit.boot_note = "no b, no bootstrap error";
    return;
  }
  const BEstimate a =
      aki_mle(mu, fit.mu_min, fit.truncated ? std::optional<double>(fit.mu_max) : std::nullopt);
  fit.b_aki = a.b;
  fit.b_aki_err = a.err;
  const BootstrapError boot =
      block_bootstrap_b(mu, fit.bin_width, fit.mu_min, fit.mu_max, fit.truncated, opt);
  fit.b_mle_boot_err = boot.err;
  fit.boot_block = boot.block;
  fit.boot_tau_int = boot.tau_int;
  fit.boot_resamples = boot.resamples;
  fit.boot_note = std::isfinite(boot.err)
                      ? "block bootstrap over the catalogue: " + std::to_string(boot.resamples) +
                            " resamples of blocks of " + std::to_string(boot.block) +
                            " events (where the batch-means error levels off, from the larger "
                            "of n^(1/3) and " +
                            fmt_short(opt.boot_block_factor) +
                            " x the integrated autocorrelation time " + fmt_short(boot.tau_int) +
                            " up to n/" + std::to_string(opt.boot_min_blocks) + "), seed " +
                            std::to_string(opt.boot_seed)
                      : "block bootstrap: too few events in the window";
}

ScalingCeiling scaling_ceiling(const MagnitudeHistogram& h, double mu_start,
                               const GrFitOptions& opt) {
  ScalingCeiling c;
  if (h.events() == 0) throw Error("scaling ceiling: no events");
  const std::int64_t start = std::max(h.first_bin(), h.bin_of(mu_start));
  std::int64_t top = h.last_bin();
  c.reason = "end of data";
  for (const auto& g : find_gaps(h, start, h.last_bin(), opt))
    if (g.first > start) {
      top = g.first - 1;
      c.reason = "gap";
      break;
    }
  if (const auto k = first_rise(h, start, top, opt)) {
    top = *k - 1;
    c.reason = "rise";
  }
  while (top > start && h.count(top) == 0) --top;
  c.mu_max = h.mu_high(top);
  return c;
}

double integrated_autocorrelation_time(std::span<const double> x, double window_factor) {
  const std::size_t n = x.size();
  if (n < 4) return 1;
  double mean = 0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(n);
  const auto C = [&](std::size_t t) {
    double c = 0;
    for (std::size_t i = 0; i + t < n; ++i) c += (x[i] - mean) * (x[i + t] - mean);
    return c / static_cast<double>(n - t);
  };
  const double c0 = C(0);
  if (!(c0 > 0)) return 1;
  double tau = 1;
  // Lags up to a tenth of the series at most: beyond, the estimate is noise.
  for (std::size_t t = 1; t < n / 10; ++t) {
    tau += 2 * C(t) / c0;
    if (static_cast<double>(t) >= window_factor * tau) break;
  }
  return std::max(tau, 1.0);
}

std::int64_t plateau_block_length(std::span<const double> z, std::int64_t first, double plateau,
                                  std::int64_t min_blocks) {
  const auto n = static_cast<std::int64_t>(z.size());
  first = std::max<std::int64_t>(first, 1);
  std::vector<std::int64_t> lengths;
  std::vector<double> errs;
  for (std::int64_t L = first; L * std::max<std::int64_t>(min_blocks, 2) <= n; L *= 2) {
    const std::int64_t nb = n / L;
    std::vector<double> sums(static_cast<std::size_t>(nb), 0);
    double mean = 0;
    for (std::int64_t b = 0; b < nb; ++b) {
      for (std::int64_t i = b * L; i < (b + 1) * L; ++i) sums[b] += z[i];
      mean += sums[b];
    }
    mean /= static_cast<double>(nb);
    double ss = 0;
    for (double v : sums) ss += (v - mean) * (v - mean);
    lengths.push_back(L);
    errs.push_back(std::sqrt(ss / static_cast<double>(nb - 1) * static_cast<double>(nb)));
  }
  if (lengths.empty()) return first;
  // The largest error at each candidate or any longer one.
  std::vector<double> above(errs.size());
  double top = 0;
  for (std::size_t j = errs.size(); j-- > 0;) above[j] = top = std::max(top, errs[j]);
  for (std::size_t j = 0; j < errs.size(); ++j)
    if (errs[j] >= plateau * above[j]) return lengths[j];
  return lengths.back();
}

static std::string fmt_sig6(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

BootstrapError block_bootstrap_b(std::span<const double> mu, double bin_width, double mu_min,
                                 double mu_max, bool truncated, const GrFitOptions& opt,
                                 std::int64_t block) {
  BootstrapError r;
  const std::size_t n = mu.size();
  const MagnitudeHistogram binner(bin_width);
  const std::int64_t k_lo = std::llround(mu_min / bin_width);
  const std::int64_t k_hi = std::llround(mu_max / bin_width) - 1;
  // Per event: in the window, and its offset (bin - first bin) * w, as binned_mle sums it.
  std::vector<double> in(n, 0), off(n, 0);
  std::int64_t n_in = 0;
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t k = binner.bin_of(mu[i]);
    if (k < k_lo || k > k_hi) continue;
    in[i] = 1;
    off[i] = static_cast<double>(k - k_lo) * bin_width;
    ++n_in;
    sum += off[i];
  }
  if (n_in < 2 || opt.boot_resamples < 2) return r;
  // The influence of each event on the window's mean offset: zero outside the window.
  {
    const double mean = sum / static_cast<double>(n_in);
    std::vector<double> z(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      if (in[i] != 0) z[i] = off[i] - mean;
    r.tau_int = integrated_autocorrelation_time(z, opt.boot_window_factor);
  }
  // From the larger of boot_block_factor tau_int and n^(1/3) (the rate of the optimal
  // block length for a variance, Hall, Horowitz & Jing 1995), up to the plateau.
  if (block > 0) {
    r.block = block;
  } else {
    std::vector<double> z(n, 0);
    const double mean = sum / static_cast<double>(n_in);
    for (std::size_t i = 0; i < n; ++i)
      if (in[i] != 0) z[i] = off[i] - mean;
    const auto first = static_cast<std::int64_t>(std::ceil(
        std::max({1.0, opt.boot_block_factor * r.tau_int, std::cbrt(static_cast<double>(n))})));
    r.block = plateau_block_length(z, first, opt.boot_plateau, opt.boot_min_blocks);
  }
  r.block = std::min<std::int64_t>(r.block, static_cast<std::int64_t>(n));
  // Prefix sums over the series and its first `block` events again (circular blocks).
  const std::size_t L = static_cast<std::size_t>(r.block);
  // (count, sum of offsets) side by side: one cache line per block end.
  std::vector<std::array<double, 2>> cum(n + L + 1, {0, 0});
  for (std::size_t i = 0; i < n + L; ++i)
    cum[i + 1] = {cum[i][0] + in[i % n], cum[i][1] + off[i % n]};
  const double w = bin_width;
  const Model model{truncated ? static_cast<double>(k_hi - k_lo + 1) * w : kInf, w};
  // A portable generator (the standard distributions are not): blocks start at
  // (rng() >> 11) * n / 2^53.
  std::mt19937_64 rng(opt.boot_seed);
  double s1 = 0, s2 = 0;
  std::int64_t m = 0;
  for (std::int64_t b = 0; b < opt.boot_resamples; ++b) {
    double cnt = 0, tot = 0;
    for (std::size_t filled = 0; filled < n; filled += L) {
      const auto start = static_cast<std::size_t>(static_cast<double>(rng() >> 11) * 0x1.0p-53 *
                                                  static_cast<double>(n));
      const std::size_t len = std::min(L, n - filled);
      cnt += cum[start + len][0] - cum[start][0];
      tot += cum[start + len][1] - cum[start][1];
    }
    if (cnt < 2) continue;
    const double bb = solve_b(model, tot / cnt);
    if (!std::isfinite(bb)) continue;
    s1 += bb;
    s2 += bb * bb;
    ++m;
  }
  r.resamples = m;
  if (m < 2) return r;
  const double mean_b = s1 / static_cast<double>(m);
  r.err = std::sqrt(
      std::max(0.0, (s2 - static_cast<double>(m) * mean_b * mean_b) / static_cast<double>(m - 1)));
  // Six significant digits (200 resamples leave it uncertain by 5 %): the last bits of exp
  // differ between libm variants, and the error is written the same with either.
  if (r.err > 0) r.err = std::stod(fmt_sig6(r.err));
  return r;
}

GrFit fit_magnitudes(std::span<const double> mu, double bin_width, std::optional<double> mu_min,
                     std::optional<double> mu_max, const GrFitOptions& opt) {
  MagnitudeHistogram h(bin_width);
  for (double m : mu) h.add(m);
  GrFit f = fit_histogram(h, mu_min, mu_max, opt);
  add_unbinned(f, mu, opt);
  return f;
}

std::vector<WindowFit> scan_windows(const MagnitudeHistogram& h, const GrFit& fit,
                                    const GrFitOptions& opt) {
  if (h.events() < 2)
    throw Error("b scan: need at least 2 events, found " + std::to_string(h.events()));
  const std::int64_t first = h.first_bin(), last = h.last_bin();
  if (last - first + 1 > kMaxScanBins)
    throw Error("b scan: the magnitudes span " + std::to_string(last - first + 1) +
                " bins, more than the " + std::to_string(kMaxScanBins) +
                " a scan covers; use a wider bin width");
  const double w = h.bin_width();
  const std::int64_t k_lo = std::llround(fit.mu_min / w), k_hi = std::llround(fit.mu_max / w) - 1;
  std::vector<WindowFit> rows;
  for (std::int64_t lo = first; lo <= last; ++lo) {
    if (h.count(lo) == 0 && lo != k_lo) continue;
    for (std::int64_t hi = lo + opt.min_window_bins - 1; hi <= last; ++hi) {
      if (h.count(hi) == 0 && hi != k_hi) continue;
      const std::int64_t n = h.count_range(lo, hi);
      if (n < opt.min_tail) continue;
      const bool truncated = !fit.mu_max_auto || hi < last;
      const BEstimate e = mle_or_nan(h, lo, hi, truncated);
      WindowFit r;
      r.mu_min = h.mu_low(lo);
      r.mu_max = h.mu_high(hi);
      r.events = n;
      r.b = e.b;
      r.b_err = e.err;
      r.ks_distance = ks_distance_binned(h, lo, hi, e.b, truncated);
      r.accepted =
          fit.b_ok && e.b > 0 && std::isfinite(e.b) && in_sys_set(h, k_lo, k_hi, lo, hi, opt);
      rows.push_back(r);
    }
  }
  return rows;
}

}  // namespace bkq
