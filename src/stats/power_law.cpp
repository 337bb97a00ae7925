// Implementation of the power-law fits (see power_law.hpp; Clauset, Shalizi & Newman 2009).
// The continuous law on [a, b] is a truncated exponential in u = ln(x / a) with rate
// alpha - 1; the discrete one is normalised by Hurwitz zeta functions (GSL) for alpha > 1
// and by an explicit sum plus a midpoint integral of its smooth far part otherwise.
#include "stats/power_law.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_erf.h>
#include <gsl/gsl_sf_gamma.h>
#include <gsl/gsl_sf_zeta.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <random>

#include "core/format.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// Explicit terms of a discrete normalisation before its far part is integrated (the
// midpoint rule's relative error there is below alpha^2 / (24 x^2) ~ 1e-7).
constexpr double kExplicitTerms = 1000;

std::string fmt3(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// The upper incomplete gamma function Gamma(s, x), x > 0, any s: GSL's for s > 0 or x >= 1;
// below, from Gamma(s + m, x) with s + m > 0 by Gamma(s, x) = (Gamma(s + 1, x) - x^s e^-x)/s
// (GSL's own is inaccurate for s < 0 and small x: Gamma(-0.4, 1e-10) off by 30 %).
double upper_gamma(double s, double x) {
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  double g = kNaN;
  gsl_sf_result r;
  if (s > 0 || x >= 1) {
    if (gsl_sf_gamma_inc_e(s, x, &r) == GSL_SUCCESS) g = r.val;
  } else {
    if (s == std::floor(s)) s += 1e-9;  // Gamma(0, x) and below by continuity
    const double m = std::floor(-s) + 1;
    if (gsl_sf_gamma_inc_e(s + m, x, &r) == GSL_SUCCESS) {
      g = r.val;
      for (double j = m - 1; j >= 0; j -= 1) g = (g - std::pow(x, s + j) * std::exp(-x)) / (s + j);
    }
  }
  gsl_set_error_handler(old);
  return g;
}

// ln of the integral of x^-alpha e^{-lambda x} over [a, b] (b may be inf), by quadrature in
// u = ln(x / a).
double ln_integral(double alpha, double lambda, double a, double b) {
  if (lambda <= 0) {
    const double s = 1 - alpha;
    if (std::isinf(b)) return s < 0 ? std::log(-1 / s) + s * std::log(a) : kInf;
    const double L = std::log(b / a);
    if (std::fabs(s * L) < 1e-12) return std::log(a) * s + std::log(L);
    // a^s (e^{sL} - 1) / s
    return s * std::log(a) + std::log(std::expm1(s * L) / s);
  }
  // Closed form lambda^(alpha-1) [Gamma(1-alpha, lambda a) - Gamma(1-alpha, lambda b)].
  {
    const double ga = upper_gamma(1 - alpha, lambda * a);
    const double gb = std::isinf(b) ? 0.0 : upper_gamma(1 - alpha, lambda * b);
    const double diff = ga - gb;
    if (std::isfinite(diff) && diff > 1e-6 * std::fabs(ga))
      return (alpha - 1) * std::log(lambda) + std::log(diff);
  }
  double u_end = std::isinf(b) ? std::log(std::max(a, 800 / lambda) / a) : std::log(b / a);
  if (!(u_end > 0)) return -kInf;
  // The integrand in v = u: exp((1 - alpha) v - lambda a (e^v - 1)) (scaled by the value at
  // v = 0, e^{-lambda a}, and a^{1 - alpha}).
  struct P {
    double s, la;
  } p{1 - alpha, lambda * a};
  gsl_function F;
  F.function = [](double v, void* q) {
    const auto* pp = static_cast<const P*>(q);
    return std::exp(pp->s * v - pp->la * std::expm1(v));
  };
  F.params = &p;
  static thread_local std::unique_ptr<gsl_integration_workspace,
                                      decltype(&gsl_integration_workspace_free)>
      ws(gsl_integration_workspace_alloc(200), &gsl_integration_workspace_free);
  double result = 0, abserr = 0;
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  gsl_integration_qags(&F, 0, u_end, 0, 1e-10, 200, ws.get(), &result, &abserr);
  gsl_set_error_handler(old);
  return (1 - alpha) * std::log(a) - lambda * a + std::log(result);
}

// ln of sum_{x = a}^{b} x^-alpha e^{-lambda x} over integers (b may be inf).
double ln_sum(double alpha, double lambda, double a, double b) {
  if (lambda <= 0 && alpha > 1) {
    gsl_error_handler_t* old = gsl_set_error_handler_off();
    const double z = gsl_sf_hzeta(alpha, a) - (std::isinf(b) ? 0.0 : gsl_sf_hzeta(alpha, b + 1));
    gsl_set_error_handler(old);
    if (z > 0 && std::isfinite(z)) return std::log(z);
  }
  const double explicit_end = std::min(b, a + kExplicitTerms - 1);
  // Scaled by the first term to keep the sum in range.
  const double ln_first = -alpha * std::log(a) - lambda * a;
  double s = 0;
  for (double x = a; x <= explicit_end; x += 1)
    s += std::exp(-alpha * std::log(x) - lambda * x - ln_first);
  double total = ln_first + std::log(s);
  if (explicit_end < b) {
    const double far = ln_integral(alpha, lambda, explicit_end + 0.5, b + 0.5);
    if (std::isinf(far) && far > 0) return kInf;
    total =
        std::max(total, far) + std::log1p(std::exp(std::min(total, far) - std::max(total, far)));
  }
  return total;
}

double ln_norm(double alpha, double lambda, double a, double b, bool discrete) {
  return discrete ? ln_sum(alpha, lambda, a, b) : ln_integral(alpha, lambda, a, b);
}

// Golden-section maximum of a unimodal f on [lo, hi].
template <class F>
double maximise(const F& f, double lo, double hi) {
  constexpr double g = 0.6180339887498949;
  double a = lo, b = hi, c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < 200 && b - a > 1e-10 * std::max(1.0, std::fabs(a)); ++i) {
    if (fc > fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

// Nelder-Mead maximum of f over two parameters from p0 with initial steps.
template <class F>
std::array<double, 2> maximise2(const F& f, std::array<double, 2> p0, std::array<double, 2> step) {
  std::array<std::array<double, 2>, 3> s{p0, p0, p0};
  s[1][0] += step[0];
  s[2][1] += step[1];
  std::array<double, 3> v{f(s[0]), f(s[1]), f(s[2])};
  for (int it = 0; it < 400; ++it) {
    std::array<int, 3> o{0, 1, 2};
    std::sort(o.begin(), o.end(), [&](int i, int j) { return v[i] > v[j]; });
    const auto best = s[o[0]], mid = s[o[1]], worst = s[o[2]];
    const double vb = v[o[0]], vm = v[o[1]], vw = v[o[2]];
    if (std::fabs(vb - vw) < 1e-10 * (1 + std::fabs(vb)) && it > 20) break;
    const std::array<double, 2> c{0.5 * (best[0] + mid[0]), 0.5 * (best[1] + mid[1])};
    const auto at = [&](double t) {
      return std::array<double, 2>{c[0] + t * (worst[0] - c[0]), c[1] + t * (worst[1] - c[1])};
    };
    const auto r = at(-1);
    const double vr = f(r);
    auto replace = [&](const std::array<double, 2>& p, double val) {
      s[o[2]] = p;
      v[o[2]] = val;
    };
    if (vr > vb) {
      const auto e = at(-2);
      const double ve = f(e);
      ve > vr ? replace(e, ve) : replace(r, vr);
    } else if (vr > vm) {
      replace(r, vr);
    } else {
      const auto k = at(vr > vw ? -0.5 : 0.5);
      const double vk = f(k);
      if (vk > std::max(vr, vw)) {
        replace(k, vk);
      } else {  // shrink towards the best
        for (int i : {o[1], o[2]}) {
          s[i] = {0.5 * (s[i][0] + best[0]), 0.5 * (s[i][1] + best[1])};
          v[i] = f(s[i]);
        }
      }
    }
  }
  const int b = static_cast<int>(std::max_element(v.begin(), v.end()) - v.begin());
  return s[b];
}

// h(x) = 1/x - 1/(e^x - 1): the mean of a unit-length truncated exponential of rate x.
double h(double x) {
  if (std::fabs(x) < 1e-4) return 0.5 - x / 12;
  if (x > 700) return 1 / x;
  if (x < -700) return 1 / x + 1;
  return 1 / x - 1 / std::expm1(x);
}

// The tail of the sorted values: [i0, i1) with x_min <= x <= x_max.
struct Tail {
  std::size_t i0 = 0, i1 = 0;
  std::int64_t n() const { return static_cast<std::int64_t>(i1 - i0); }
};

struct Sample {
  std::vector<double> x;       // sorted
  std::vector<double> cum_ln;  // cum_ln[i] = sum_{j < i} ln x_j
  explicit Sample(std::vector<double> v) : x(std::move(v)) {
    std::sort(x.begin(), x.end());
    cum_ln.assign(x.size() + 1, 0);
    for (std::size_t i = 0; i < x.size(); ++i) cum_ln[i + 1] = cum_ln[i] + std::log(x[i]);
  }
  Tail tail(double x_min, double x_max) const {
    Tail t;
    t.i0 = static_cast<std::size_t>(std::lower_bound(x.begin(), x.end(), x_min) - x.begin());
    t.i1 = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), x_max) - x.begin());
    if (t.i1 < t.i0) t.i1 = t.i0;
    return t;
  }
  double sum_ln(const Tail& t) const { return cum_ln[t.i1] - cum_ln[t.i0]; }
};

// P(X >= x) of the fitted law on [a, b].
double survival(double x, double alpha, double a, double b, bool discrete, double ln_z) {
  if (discrete) return std::exp(ln_sum(alpha, 0, x, b) - ln_z);
  const double beta = alpha - 1, L = std::log(x / a);
  if (std::isinf(b)) return std::exp(-beta * L);
  const double D = std::log(b / a);
  if (std::fabs(beta * D) < 1e-12) return 1 - L / D;
  return (std::exp(-beta * L) - std::exp(-beta * D)) / -std::expm1(-beta * D);
}

// KS distance between the tail's empirical distribution and the fitted law. Discrete:
// P(X >= x) is carried from one distinct value to the next by subtracting the terms in
// between (a Hurwitz zeta difference across a wide step).
double ks_tail(const Sample& s, const Tail& t, double alpha, double a, double b, bool discrete) {
  const auto n = static_cast<double>(t.n());
  if (n < 1 || !std::isfinite(alpha)) return kNaN;
  const double ln_z = discrete ? ln_sum(alpha, 0, a, b) : 0;
  double cur = a, s_cur = 1;  // discrete: P(X >= cur)
  const auto disc_survival = [&](double x) {
    if (x - cur > 64) {
      s_cur = x > b ? 0 : std::exp(ln_sum(alpha, 0, x, b) - ln_z);
    } else {
      for (double y = cur; y < x; y += 1) s_cur -= std::exp(-alpha * std::log(y) - ln_z);
    }
    cur = x;
    return std::max(0.0, s_cur);
  };
  double d = 0;
  for (std::size_t i = t.i0; i < t.i1;) {
    std::size_t j = i;
    while (j < t.i1 && s.x[j] == s.x[i]) ++j;
    // Empirical P(X >= x_i) at x_i and just above it (after the ties).
    const double emp_at = static_cast<double>(t.i1 - i) / n;
    const double emp_above = static_cast<double>(t.i1 - j) / n;
    if (discrete) {
      d = std::max(d, std::fabs(emp_at - disc_survival(s.x[i])));
      d = std::max(d, std::fabs(emp_above - disc_survival(s.x[i] + 1)));
    } else {
      const double fit_at = survival(s.x[i], alpha, a, b, false, 0);
      d = std::max({d, std::fabs(emp_at - fit_at), std::fabs(emp_above - fit_at)});
    }
    i = j;
  }
  return d;
}

// The x_min candidates: the distinct values with >= min_tail events at or above them up to
// x_max, at most `grid` of them evenly spaced in ln x.
std::vector<double> x_min_grid(const Sample& s, double x_max, const PowerLawOptions& opt) {
  const Tail all = s.tail(0, x_max);
  const auto need = std::max<std::int64_t>(
      opt.min_tail,
      static_cast<std::int64_t>(std::ceil(opt.min_tail_share * static_cast<double>(all.n()))));
  if (all.n() < need) return {};
  const double lo = s.x[all.i0];
  const double hi = s.x[all.i1 - static_cast<std::size_t>(need)];
  std::vector<double> out;
  const auto add = [&](double v) {
    auto it = std::lower_bound(s.x.begin() + static_cast<std::ptrdiff_t>(all.i0),
                               s.x.begin() + static_cast<std::ptrdiff_t>(all.i1), v);
    if (it == s.x.end()) return;
    if (*it > hi) return;
    if (out.empty() || *it > out.back()) out.push_back(*it);
  };
  const auto K = std::max<std::int64_t>(1, opt.x_min_grid);
  if (!(hi > lo) || K == 1) {
    add(lo);
    return out;
  }
  const double l0 = std::log(lo), l1 = std::log(hi);
  for (std::int64_t k = 0; k < K; ++k)
    add(std::exp(l0 + (l1 - l0) * static_cast<double>(k) / static_cast<double>(K - 1)) *
        (1 - 1e-12));
  return out;
}

struct Scan {
  double x_min = kNaN, alpha = kNaN, err = kNaN, ks = kInf;
  Tail tail;
  std::int64_t candidates = 0;
};

Scan scan_x_min(const Sample& s, double x_max, const PowerLawOptions& opt) {
  Scan best;
  std::vector<double> grid =
      opt.x_min ? std::vector<double>{*opt.x_min} : x_min_grid(s, x_max, opt);
  best.candidates = static_cast<std::int64_t>(grid.size());
  for (double a : grid) {
    const Tail t = s.tail(a, x_max);
    if (t.n() < std::max<std::int64_t>(2, opt.x_min ? 2 : opt.min_tail)) continue;
    const AlphaEstimate e = power_law_mle(t.n(), s.sum_ln(t), a, x_max, opt.discrete);
    if (!std::isfinite(e.alpha)) continue;
    const double d = ks_tail(s, t, e.alpha, a, x_max, opt.discrete);
    if (d < best.ks) {
      best.x_min = a;
      best.alpha = e.alpha;
      best.err = e.err;
      best.ks = d;
      best.tail = t;
    }
  }
  return best;
}

// A draw from the fitted law on [a, b]. Discrete: by the table of its distribution up to
// a + table.size() and a continuous draw on the far part, rounded.
double draw(std::mt19937_64& rng, double alpha, double a, double b, bool discrete,
            const std::vector<double>& table) {
  const double r = uniform(rng);
  if (discrete && !table.empty() && r < table.back()) {
    const auto it = std::upper_bound(table.begin(), table.end(), r);
    return a + static_cast<double>(it - table.begin());
  }
  double lo = a, hi = b;
  double rr = r;
  if (discrete) {
    lo = a + static_cast<double>(table.size()) - 0.5;
    hi = std::isinf(b) ? b : b + 0.5;
    rr = table.empty() ? r : (r - table.back()) / (1 - table.back());
  }
  const double beta = alpha - 1;
  double x;
  if (std::isinf(hi)) {
    x = lo * std::exp(-std::log1p(-rr) / beta);
  } else {
    const double D = std::log(hi / lo);
    const double c = std::fabs(beta) < 1e-12 ? 0 : -std::expm1(-beta * D);
    x = std::fabs(beta) < 1e-12 ? lo * std::exp(rr * D)
                                : lo * std::exp(-std::log1p(-c * rr) / beta);
  }
  return discrete ? std::min(std::floor(x + 0.5), std::isinf(b) ? kInf : b) : x;
}

std::vector<double> discrete_table(double alpha, double a, double b) {
  std::vector<double> t;
  const double ln_z = ln_sum(alpha, 0, a, b);
  double c = 0;
  const double end = std::min(b, a + 1e5 - 1);
  for (double x = a; x <= end; x += 1) {
    c += std::exp(-alpha * std::log(x) - ln_z);
    t.push_back(std::min(c, 1.0));
  }
  if (end >= b) t.back() = 1;
  return t;
}

// Per-value log-likelihoods of the tail's values under the fitted power law and lognormal.
double ln_pl(double x, double alpha, double ln_z) {
  return -alpha * std::log(x) - ln_z;
}
// ln Phi(z) - accurate in both tails.
double ln_Phi(double z) {
  return gsl_sf_log_erfc(-z / std::sqrt(2.0)) - std::log(2.0);
}
// ln(Phi(z2) - Phi(z1)), z1 < z2.
double ln_Phi_diff(double z1, double z2) {
  if (!(z2 > z1)) return -kInf;
  if (std::isinf(z2)) return ln_Phi(-z1);
  if (std::isinf(z1)) return ln_Phi(z2);
  if (z1 > 0) {  // both upper tails: Q(z1) - Q(z2) with Q(z) = Phi(-z)
    const double q1 = ln_Phi(-z1), q2 = ln_Phi(-z2);
    return q1 + std::log1p(-std::exp(q2 - q1));
  }
  const double p2 = ln_Phi(z2), p1 = ln_Phi(z1);
  return p2 + std::log1p(-std::exp(p1 - p2));
}

}  // namespace

AlphaEstimate power_law_mle(std::int64_t n, double sum_ln_x, double x_min, double x_max,
                            bool discrete) {
  AlphaEstimate e;
  if (n < 2) return e;
  const auto nn = static_cast<double>(n);
  const bool bounded = std::isfinite(x_max);
  if (!discrete) {
    // u = ln(x / x_min) is exponential with rate beta = alpha - 1 (truncated at D).
    const double m = sum_ln_x / nn - std::log(x_min);
    if (!(m > 0)) return e;
    double beta;
    if (!bounded) {
      beta = 1 / m;
    } else {
      const double D = std::log(x_max / x_min);
      if (m >= D) return e;
      double lo = -1, hi = 1;
      while (D * h(hi * D) > m && hi < 1e6) hi *= 2;
      while (D * h(lo * D) < m && lo > -1e6) lo *= 2;
      for (int i = 0; i < 80 && hi - lo > 1e-14 * std::max(1.0, std::fabs(hi)); ++i) {
        const double mid = 0.5 * (lo + hi);
        (D * h(mid * D) > m ? lo : hi) = mid;
      }
      beta = 0.5 * (lo + hi);
    }
    e.alpha = 1 + beta;
  } else {
    const double lo = bounded ? -4.0 : 1.0 + 1e-9, hi = 12.0;
    const auto ll = [&](double a) { return -a * sum_ln_x - nn * ln_sum(a, 0, x_min, x_max); };
    e.alpha = maximise(ll, lo, hi);
    if (e.alpha > hi - 1e-6 || e.alpha < lo + 1e-6) return {kNaN, kNaN};
  }
  // Fisher information per event: the variance of ln x under the law, d2 ln Z / d alpha^2.
  const double st = 1e-3;
  const auto lz = [&](double a) { return ln_norm(a, 0, x_min, x_max, discrete); };
  const double var = (lz(e.alpha + st) - 2 * lz(e.alpha) + lz(e.alpha - st)) / (st * st);
  e.err = var > 0 ? 1 / std::sqrt(nn * var) : kNaN;
  return e;
}

PowerLawFit fit_power_law(std::span<const double> x_in, const PowerLawOptions& opt) {
  PowerLawFit f;
  f.discrete = opt.discrete;
  f.x_min_auto = !opt.x_min.has_value();
  std::vector<double> v;
  v.reserve(x_in.size());
  std::int64_t dropped = 0;
  for (double x : x_in) {
    if (std::isfinite(x) && x > 0 && (!opt.discrete || x >= 1))
      v.push_back(opt.discrete ? std::round(x) : x);
    else
      ++dropped;
  }
  f.n_total = static_cast<std::int64_t>(v.size());
  if (dropped > 0)
    f.notes.push_back(std::to_string(dropped) + " values <= 0" +
                      (opt.discrete ? std::string(" (or < 1)") : std::string()) +
                      " or not finite left out");
  if (f.n_total < std::max<std::int64_t>(opt.min_tail, 2)) {
    f.no_fit_reason =
        "fewer than " + std::to_string(std::max<std::int64_t>(opt.min_tail, 2)) + " values > 0";
    return f;
  }
  // Upper cut: given, or below the first gap or rise of the distribution of ln x (the
  // automatic window's ceiling, gutenberg_richter.hpp), from its lowest bin.
  if (opt.x_max) {
    f.x_max = *opt.x_max;
    f.x_max_reason = "given";
  } else if (opt.x_max_auto) {
    MagnitudeHistogram hl(MagnitudeHistogram::kDefaultBinWidth);
    for (double x : v) hl.add(std::log(x));
    // From the given x_min, else from the mode of ln x (the first bin for a power law).
    std::int64_t mode = hl.first_bin();
    for (std::int64_t k = hl.first_bin(); k <= hl.last_bin(); ++k)
      if (hl.count(k) > hl.count(mode)) mode = k;
    const ScalingCeiling c =
        scaling_ceiling(hl, opt.x_min ? std::log(*opt.x_min) : hl.mu_low(mode));
    if (c.reason == "end of data") {
      f.x_max_reason = "none";
    } else {
      f.x_max = opt.discrete ? std::floor(std::exp(c.mu_max)) : std::exp(c.mu_max);
      f.x_max_reason = c.reason;
      f.notes.push_back("x_max = " + fmt3(f.x_max) + ": below the first " + c.reason +
                        " of the distribution of ln x");
    }
  } else {
    f.x_max_reason = "none";
  }
  const Sample s(v);
  const Scan sc = scan_x_min(s, f.x_max, opt);
  f.x_min_candidates = sc.candidates;
  if (!std::isfinite(sc.alpha)) {
    f.no_fit_reason = "no x_min with >= " + std::to_string(opt.min_tail) +
                      " values up to x_max gives a finite exponent";
    return f;
  }
  f.ok = true;
  f.x_min = sc.x_min;
  f.alpha = sc.alpha;
  f.alpha_err = sc.err;
  f.ks = sc.ks;
  f.n_tail = sc.tail.n();
  const double a = f.x_min, b = f.x_max;

  // Block bootstrap of alpha over the catalogue's order (x_min and x_max fixed).
  {
    const std::size_t n = x_in.size();
    std::vector<double> in(n, 0), lnx(n, 0);
    double sum = 0;
    std::int64_t cnt = 0;
    for (std::size_t i = 0; i < n; ++i) {
      double x = x_in[i];
      if (!(std::isfinite(x) && x > 0)) continue;
      if (opt.discrete) x = std::round(x);
      if (x < a || x > b) continue;
      in[i] = 1;
      lnx[i] = std::log(x);
      sum += lnx[i];
      ++cnt;
    }
    std::vector<double> z(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      if (in[i] != 0) z[i] = lnx[i] - sum / static_cast<double>(cnt);
    f.boot_tau_int = integrated_autocorrelation_time(z);
    // As b's (block_bootstrap_b): where the batch-means error levels off.
    const auto first = static_cast<std::int64_t>(std::ceil(std::max(
        {1.0, opt.boot_block_factor * f.boot_tau_int, std::cbrt(static_cast<double>(n))})));
    const auto L = static_cast<std::size_t>(std::min<std::int64_t>(
        static_cast<std::int64_t>(n),
        plateau_block_length(z, first, opt.boot_plateau, opt.boot_min_blocks)));
    f.boot_block = static_cast<std::int64_t>(L);
    std::vector<double> c_in(n + L + 1, 0), c_ln(n + L + 1, 0);
    for (std::size_t i = 0; i < n + L; ++i) {
      c_in[i + 1] = c_in[i] + in[i % n];
      c_ln[i + 1] = c_ln[i] + lnx[i % n];
    }
    std::mt19937_64 rng(opt.seed);
    double s1 = 0, s2 = 0;
    std::int64_t m = 0;
    for (std::int64_t r = 0; r < opt.boot_resamples; ++r) {
      double c = 0, t = 0;
      for (std::size_t filled = 0; filled < n; filled += L) {
        const auto start = static_cast<std::size_t>(uniform(rng) * static_cast<double>(n));
        const std::size_t len = std::min(L, n - filled);
        c += c_in[start + len] - c_in[start];
        t += c_ln[start + len] - c_ln[start];
      }
      const AlphaEstimate e = power_law_mle(static_cast<std::int64_t>(c), t, a, b, opt.discrete);
      if (!std::isfinite(e.alpha)) continue;
      s1 += e.alpha;
      s2 += e.alpha * e.alpha;
      ++m;
    }
    if (m >= 2) {
      const double mean = s1 / static_cast<double>(m);
      f.alpha_boot_err = std::sqrt(
          std::max(0.0, (s2 - static_cast<double>(m) * mean * mean) / static_cast<double>(m - 1)));
      // Six significant digits, as b's: the same with every libm variant.
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", f.alpha_boot_err);
      f.alpha_boot_err = std::strtod(buf, nullptr);
    }
  }

  // Goodness of fit (Clauset et al. 2009 sec. 4.1): synthetic sets of the size of the data
  // up to x_max, each value from the fitted law with probability n_tail / n, else drawn
  // from the data below x_min; each fitted as the data were (x_min scanned on its own
  // grid); p is the share of sets whose KS distance is at least the data's.
  if (opt.gof_sets > 0) {
    const Tail below = s.tail(0, a * (1 - 1e-12));
    const Tail upto = s.tail(0, b);
    const std::int64_t n_all = upto.n();
    // Sets of at most kMaxSyntheticSize values, their KS distances compared as sqrt(n) D
    // (whose distribution does not depend on n for large n), so that 10^6 events stay fast.
    constexpr std::int64_t kMaxSyntheticSize = 100'000;
    const std::int64_t n_syn = std::min(n_all, kMaxSyntheticSize);
    if (n_syn < n_all)
      f.notes.push_back("goodness of fit: synthetic sets of " + std::to_string(n_syn) +
                        " values, KS distances compared as sqrt(n) D");
    const std::vector<double> table =
        opt.discrete ? discrete_table(f.alpha, a, b) : std::vector<double>{};
    std::mt19937_64 rng(opt.seed + 1);
    std::int64_t worse = 0, done = 0;
    PowerLawOptions o2 = opt;
    for (std::int64_t k = 0; k < opt.gof_sets; ++k) {
      if (opt.cancelled && opt.cancelled()) throw FitCancelled();
      std::vector<double> syn(static_cast<std::size_t>(n_syn));
      const double p_tail = static_cast<double>(f.n_tail) / static_cast<double>(n_all);
      for (auto& y : syn) {
        if (below.n() == 0 || uniform(rng) < p_tail)
          y = draw(rng, f.alpha, a, b, opt.discrete, table);
        else
          y = s.x[below.i0 +
                  static_cast<std::size_t>(uniform(rng) * static_cast<double>(below.n()))];
      }
      const Sample ss(std::move(syn));
      const Scan sk = scan_x_min(ss, b, o2);
      if (!std::isfinite(sk.ks)) continue;
      ++done;
      const bool no_better = n_syn < n_all ? sk.ks * std::sqrt(static_cast<double>(sk.tail.n())) >=
                                                 f.ks * std::sqrt(static_cast<double>(f.n_tail))
                                           : sk.ks >= f.ks;
      if (no_better) ++worse;
    }
    f.gof_sets = done;
    if (done > 0) f.p = static_cast<double>(worse) / static_cast<double>(done);
  }

  if (opt.compare) {
    const Tail& t = sc.tail;
    const auto n = static_cast<double>(t.n());
    const bool disc = opt.discrete;
    const double ln_z = ln_norm(f.alpha, 0, a, b, disc);
    // Lognormal on the same tail (continuous: truncated to [a, b]; discrete: the mass of
    // [x - 1/2, x + 1/2] of a lognormal truncated to [a - 1/2, b + 1/2]).
    double m1 = 0, m2 = 0;
    for (std::size_t i = t.i0; i < t.i1; ++i) {
      const double l = std::log(s.x[i]);
      m1 += l;
      m2 += l * l;
    }
    m1 /= n;
    const double sd0 = std::sqrt(std::max(1e-6, m2 / n - m1 * m1));
    const double la = std::log(disc ? a - 0.5 : a);
    const double lb = std::isinf(b) ? kInf : std::log(disc ? b + 0.5 : b);
    const auto ln_ln = [&](double x, double mu, double sg) {
      const double norm = ln_Phi_diff((la - mu) / sg, std::isinf(lb) ? kInf : (lb - mu) / sg);
      if (disc)
        return ln_Phi_diff((std::log(x - 0.5) - mu) / sg, (std::log(x + 0.5) - mu) / sg) - norm;
      const double z = (std::log(x) - mu) / sg;
      return -std::log(x) - std::log(sg) - 0.5 * std::log(2 * std::numbers::pi) - 0.5 * z * z -
             norm;
    };
    const auto ll_ln = [&](const std::array<double, 2>& p) {
      const double mu = p[0], sg = std::exp(p[1]);
      if (!(sg > 1e-4 && sg < 1e3) || std::fabs(mu - la) > 200) return -kInf;
      double ll = 0;
      for (std::size_t i = t.i0; i < t.i1;) {
        std::size_t j = i;
        while (j < t.i1 && s.x[j] == s.x[i]) ++j;
        ll += static_cast<double>(j - i) * ln_ln(s.x[i], mu, sg);
        i = j;
      }
      return std::isfinite(ll) ? ll : -kInf;
    };
    const auto best_ln = maximise2(ll_ln, {m1, std::log(sd0)}, {0.5 * sd0, 0.3});
    f.lognormal_mu = best_ln[0];
    f.lognormal_sigma = std::exp(best_ln[1]);
    // Vuong 1989: R = sum of d_i = ln p_pl - ln p_ln, normalised by sqrt(n) sd(d).
    double R = 0, R2 = 0;
    for (std::size_t i = t.i0; i < t.i1; ++i) {
      const double d =
          ln_pl(s.x[i], f.alpha, ln_z) - ln_ln(s.x[i], f.lognormal_mu, f.lognormal_sigma);
      R += d;
      R2 += d * d;
    }
    const double sd = std::sqrt(std::max(0.0, R2 / n - (R / n) * (R / n)));
    if (sd > 0) {
      f.lognormal_ratio = R / (sd * std::sqrt(n));
      f.lognormal_p = std::erfc(std::fabs(f.lognormal_ratio) / std::sqrt(2.0));
    }
    // Power law with an exponential cut-off (nested, lambda >= 0): lambda = e^eta / a.
    double sx = 0;
    for (std::size_t i = t.i0; i < t.i1; ++i) sx += s.x[i];
    const double sl = s.sum_ln(t);
    const auto ll_cut = [&](const std::array<double, 2>& p) {
      // Below lambda a = e^-40 the cut-off is not seen in any sample: the power law.
      const double al = p[0], lam = p[1] < -40 ? 0.0 : std::exp(p[1]) / a;
      if (al < -4 || al > 12 || p[1] > 10) return -kInf;
      const double lz = ln_norm(al, lam, a, b, disc);
      const double ll = -al * sl - lam * sx - n * lz;
      return std::isfinite(ll) ? ll : -kInf;
    };
    const double ll_pl = -f.alpha * sl - n * ln_z;
    double best_cut = ll_pl;
    f.cutoff_alpha = f.alpha;
    f.cutoff_lambda = 0;
    for (double eta0 : {-8.0, -4.0, -1.0}) {
      const auto p = maximise2(ll_cut, {f.alpha - 0.2, eta0}, {0.2, 1.0});
      const double v = ll_cut(p);
      if (v > best_cut) {
        best_cut = v;
        f.cutoff_alpha = p[0];
        f.cutoff_lambda = p[1] < -40 ? 0.0 : std::exp(p[1]) / a;
      }
    }
    f.cutoff_ratio = 2 * (best_cut - ll_pl);
    // Self & Liang 1987: on the boundary lambda = 0, half a chi-squared with one degree.
    f.cutoff_p = 0.5 * std::erfc(std::sqrt(std::max(0.0, f.cutoff_ratio) / 2));
  }
  return f;
}

}  // namespace bkq
