// Binned maximum-likelihood fits; see fits.hpp.
#include "stats/seismicity/fits.hpp"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_multimin.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

namespace bkq::seis {

namespace {

using Fn = std::function<double(const std::vector<double>&)>;
constexpr double kHuge = 1e300;

double call(const gsl_vector* v, void* params) {
  const Fn& f = *static_cast<const Fn*>(params);
  std::vector<double> x(v->size);
  for (std::size_t i = 0; i < v->size; ++i) x[i] = gsl_vector_get(v, i);
  const double y = f(x);
  return std::isfinite(y) ? y : kHuge;
}

// Nelder-Mead (GSL nmsimplex2) from x0 with initial steps `step`, restarted from its own
// minimum until a restart gains nothing (a simplex can stall on a ridge).
std::vector<double> minimize(const Fn& f, std::vector<double> x, const std::vector<double>& step) {
  const std::size_t n = x.size();
  gsl_multimin_function fn{&call, n, const_cast<Fn*>(&f)};
  double best = f(x);
  for (int restart = 0; restart < 6; ++restart) {
    gsl_multimin_fminimizer* s =
        gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, n);
    gsl_vector* x0 = gsl_vector_alloc(n);
    gsl_vector* ss = gsl_vector_alloc(n);
    for (std::size_t i = 0; i < n; ++i) {
      gsl_vector_set(x0, i, x[i]);
      gsl_vector_set(ss, i, step[i]);
    }
    gsl_multimin_fminimizer_set(s, &fn, x0, ss);
    for (int it = 0; it < 4000; ++it) {
      if (gsl_multimin_fminimizer_iterate(s)) break;
      if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(s), 1e-10) == GSL_SUCCESS) break;
    }
    const double y = s->fval;
    std::vector<double> xn(n);
    for (std::size_t i = 0; i < n; ++i) xn[i] = gsl_vector_get(s->x, i);
    gsl_vector_free(x0);
    gsl_vector_free(ss);
    gsl_multimin_fminimizer_free(s);
    const bool gained = y < best - 1e-9 * (1 + std::abs(best));
    if (y <= best) {
      best = y;
      x = xn;
    }
    if (!gained) break;
  }
  return x;
}

// Standard errors sqrt(diag I^-1) of the parameters `th` from the expected counts
// `expected(th)` (I_jk = sum_b dL_b/dth_j dL_b/dth_k / L_b), by central differences with
// steps `h`. NaN where the information is singular.
std::vector<double> fisher_errors(
    const std::function<std::vector<double>(const std::vector<double>&)>& expected,
    const std::vector<double>& th, const std::vector<double>& h) {
  const std::size_t n = th.size();
  const std::vector<double> L = expected(th);
  std::vector<std::vector<double>> dL(n);
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<double> a = th, b = th;
    a[j] += h[j];
    b[j] -= h[j];
    const auto La = expected(a), Lb = expected(b);
    dL[j].resize(L.size());
    for (std::size_t i = 0; i < L.size(); ++i) dL[j][i] = (La[i] - Lb[i]) / (2 * h[j]);
  }
  gsl_matrix* I = gsl_matrix_alloc(n, n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k) {
      double s = 0;
      for (std::size_t i = 0; i < L.size(); ++i)
        if (L[i] > 0) s += dL[j][i] * dL[k][i] / L[i];
      gsl_matrix_set(I, j, k, s);
    }
  std::vector<double> err(n, NAN);
  gsl_permutation* perm = gsl_permutation_alloc(n);
  gsl_matrix* inv = gsl_matrix_alloc(n, n);
  int sign = 0;
  gsl_set_error_handler_off();
  if (gsl_linalg_LU_decomp(I, perm, &sign) == 0 && std::abs(gsl_linalg_LU_det(I, sign)) > 0 &&
      gsl_linalg_LU_invert(I, perm, inv) == 0)
    for (std::size_t j = 0; j < n; ++j) {
      const double v = gsl_matrix_get(inv, j, j);
      if (v > 0 && std::isfinite(v)) err[j] = std::sqrt(v);
    }
  gsl_matrix_free(inv);
  gsl_permutation_free(perm);
  gsl_matrix_free(I);
  return err;
}

// A representative point of a bin for starting values.
double mid(double lo, double hi) {
  if (!std::isfinite(hi)) return lo;
  return lo > 0 ? std::sqrt(lo * hi) : 0.5 * hi;
}

// Mean and deviation of ln t over the bins' representative points (starting values).
std::pair<double, double> log_moments(const BinnedData& d) {
  double n = 0, s = 0, s2 = 0;
  for (std::size_t b = 0; b < d.lo.size(); ++b) {
    const double m = mid(d.lo[b], d.hi[b]);
    if (!(d.count[b] > 0) || !(m > 0)) continue;
    const double x = std::log(m);
    n += d.count[b];
    s += d.count[b] * x;
    s2 += d.count[b] * x * x;
  }
  const double mean = s / n;
  return {mean, std::sqrt(std::max(1e-6, s2 / n - mean * mean))};
}

bool enough_for_a_law(const BinnedData& d) {
  int filled = 0;
  for (double c : d.count) filled += c > 0;
  return d.total() >= 3 && filled >= 2;
}

// Multinomial -ln L and expected counts of a law given by its bin probabilities.
double grouped_nll(const BinnedData& d, const std::vector<double>& P) {
  double nll = 0;
  for (std::size_t b = 0; b < P.size(); ++b) {
    if (!(d.count[b] > 0)) continue;
    if (!(P[b] > 0)) return kHuge;
    nll -= d.count[b] * std::log(P[b]);
  }
  return nll;
}

std::vector<double> weibull_probs(const BinnedData& d, double lambda, double k) {
  std::vector<double> P(d.lo.size());
  for (std::size_t b = 0; b < P.size(); ++b) {
    const double a = std::pow(d.lo[b] / lambda, k);
    const double c = std::isfinite(d.hi[b]) ? std::pow(d.hi[b] / lambda, k) : INFINITY;
    P[b] = std::exp(-a) * -std::expm1(-(c - a));
  }
  return P;
}

std::vector<double> lognormal_probs(const BinnedData& d, double m, double s) {
  std::vector<double> P(d.lo.size());
  for (std::size_t b = 0; b < P.size(); ++b) {
    const double zl = d.lo[b] > 0 ? (std::log(d.lo[b]) - m) / s : -INFINITY;
    const double zh = std::isfinite(d.hi[b]) ? (std::log(d.hi[b]) - m) / s : INFINITY;
    P[b] = zl > 0 ? gsl_cdf_ugaussian_Q(zl) - gsl_cdf_ugaussian_Q(zh)
                  : gsl_cdf_ugaussian_P(zh) - gsl_cdf_ugaussian_P(zl);
  }
  return P;
}

// int_lo^hi (t + c)^-p dt.
double omori_integral(double lo, double hi, double c, double p) {
  const double a = lo + c, r = std::log((hi + c) / a), q = 1 - p;
  if (std::abs(q * r) < 1e-12) return std::pow(a, q) * r;
  return std::pow(a, q) * std::expm1(q * r) / q;
}

}  // namespace

double BinnedData::total() const {
  return std::accumulate(count.begin(), count.end(), 0.0);
}

double WeibullFit::survival(double t) const {
  return std::exp(-std::pow(t / lambda.value, k.value));
}

double LognormalFit::cdf(double t) const {
  return t > 0 ? gsl_cdf_ugaussian_P((std::log(t) - m.value) / s.value) : 0.0;
}

WeibullFit fit_weibull(const BinnedData& d) {
  WeibullFit f;
  if (!enough_for_a_law(d)) return f;
  const auto [lm, ls] = log_moments(d);
  // Gumbel: ln t of a Weibull variable has deviation pi / (k sqrt 6).
  const double k0 = std::clamp(M_PI / (ls * std::sqrt(6.0)), 0.05, 50.0);
  const double l0 = std::exp(lm + 0.5772 / k0);
  auto nll = [&](const std::vector<double>& th) {
    return grouped_nll(d, weibull_probs(d, std::exp(th[0]), std::exp(th[1])));
  };
  const auto th = minimize(nll, {std::log(l0), std::log(k0)}, {0.3, 0.3});
  const double n = d.total();
  auto expected = [&](const std::vector<double>& t) {
    auto P = weibull_probs(d, std::exp(t[0]), std::exp(t[1]));
    for (double& p : P) p *= n;
    return P;
  };
  const auto err = fisher_errors(expected, th, {1e-5, 1e-5});
  f.lambda = {std::exp(th[0]), std::exp(th[0]) * err[0]};
  f.k = {std::exp(th[1]), std::exp(th[1]) * err[1]};
  f.ok = std::isfinite(f.k.value) && std::isfinite(f.lambda.value);
  return f;
}

LognormalFit fit_lognormal(const BinnedData& d) {
  LognormalFit f;
  if (!enough_for_a_law(d)) return f;
  const auto [lm, ls] = log_moments(d);
  auto nll = [&](const std::vector<double>& th) {
    return grouped_nll(d, lognormal_probs(d, th[0], std::exp(th[1])));
  };
  const auto th = minimize(nll, {lm, std::log(ls)}, {0.3 * ls, 0.3});
  const double n = d.total();
  auto expected = [&](const std::vector<double>& t) {
    auto P = lognormal_probs(d, t[0], std::exp(t[1]));
    for (double& p : P) p *= n;
    return P;
  };
  const auto err = fisher_errors(expected, th, {1e-5 * (1 + std::abs(th[0])), 1e-5});
  f.m = {th[0], err[0]};
  f.s = {std::exp(th[1]), std::exp(th[1]) * err[1]};
  f.ok = std::isfinite(f.m.value) && std::isfinite(f.s.value);
  return f;
}

double OmoriFit::rate(double t) const {
  if (!excess) return background_only;
  return background.value + K.value * std::pow(t + c.value, -p.value);
}

OmoriFit fit_omori(const BinnedData& raw, double t_max) {
  OmoriFit f;
  f.t_max = t_max;
  // The bins some window covers up to t_max; the empty ones below the first event are
  // merged into one (exact for the grouped likelihood, and a smaller problem).
  BinnedData d;
  std::size_t first = raw.lo.size();
  for (std::size_t b = 0; b < raw.lo.size(); ++b)
    if (raw.count[b] > 0 && raw.exposure[b] > 0 && raw.hi[b] <= t_max) {
      first = b;
      break;
    }
  double merged_exposure_time = 0;
  for (std::size_t b = 0; b < first; ++b)
    if (raw.exposure[b] > 0 && std::isfinite(raw.hi[b]))
      merged_exposure_time += raw.exposure[b] * (raw.hi[b] - raw.lo[b]);
  if (first < raw.lo.size() && raw.lo[first] > 0 && merged_exposure_time > 0) {
    d.lo.push_back(0);
    d.hi.push_back(raw.lo[first]);
    d.count.push_back(0);
    d.exposure.push_back(merged_exposure_time / raw.lo[first]);
  }
  for (std::size_t b = first; b < raw.lo.size(); ++b) {
    if (!(raw.exposure[b] > 0) || !std::isfinite(raw.hi[b]) || raw.hi[b] > t_max) continue;
    d.lo.push_back(raw.lo[b]);
    d.hi.push_back(raw.hi[b]);
    d.count.push_back(raw.count[b]);
    d.exposure.push_back(raw.exposure[b]);
  }
  std::vector<std::size_t> use;
  double n = 0, exposure_time = 0;
  for (std::size_t b = 0; b < d.lo.size(); ++b) {
    use.push_back(b);
    n += d.count[b];
    exposure_time += d.exposure[b] * (d.hi[b] - d.lo[b]);
  }
  if (n < 10 || use.size() < 4) {
    f.note = "too few events in the windows (" + std::to_string(static_cast<long long>(n)) +
             ") to fit a rate";
    f.background_only = exposure_time > 0 ? n / exposure_time : NAN;
    return f;
  }
  const double mu0 = n / exposure_time;
  f.background_only = mu0;
  double nll0 = 0;
  for (std::size_t b : use) {
    const double L = d.exposure[b] * mu0 * (d.hi[b] - d.lo[b]);
    nll0 += L - (d.count[b] > 0 ? d.count[b] * std::log(L) : 0.0);
  }
  // Natural parameters (mu, K, c, p).
  auto expected = [&](const std::vector<double>& q) {
    std::vector<double> L(use.size());
    for (std::size_t i = 0; i < use.size(); ++i) {
      const std::size_t b = use[i];
      L[i] = d.exposure[b] *
             (q[0] * (d.hi[b] - d.lo[b]) + q[1] * omori_integral(d.lo[b], d.hi[b], q[2], q[3]));
    }
    return L;
  };
  auto nll_natural = [&](const std::vector<double>& q) {
    if (!(q[3] > 0 && q[3] <= kMaxP)) return kHuge;
    const auto L = expected(q);
    double s = 0;
    for (std::size_t i = 0; i < use.size(); ++i) {
      const double c = d.count[use[i]];
      if (c > 0 && !(L[i] > 0)) return kHuge;
      s += L[i] - (c > 0 ? c * std::log(L[i]) : 0.0);
    }
    return s;
  };
  // Searched over (ln mu, ln K, ln c, p) from starting points over c's decades and p.
  auto nll = [&](const std::vector<double>& th) {
    return nll_natural({std::exp(th[0]), std::exp(th[1]), std::exp(th[2]), th[3]});
  };
  double t_lo = INFINITY, t_hi = 0;
  for (std::size_t b : use) {
    if (d.count[b] > 0) t_lo = std::min(t_lo, d.hi[b]);
    t_hi = std::max(t_hi, d.hi[b]);
  }
  std::vector<std::pair<double, std::vector<double>>> starts;
  for (double lc = std::log10(t_lo) - 1; lc <= std::log10(t_hi); lc += 1)
    for (double p : {0.5, 1.0, 1.5}) {
      const double c = std::pow(10.0, lc);
      double I = 0;
      for (std::size_t b : use) I += d.exposure[b] * omori_integral(d.lo[b], d.hi[b], c, p);
      const std::vector<double> th = {std::log(0.5 * mu0), std::log(0.5 * n / I), std::log(c), p};
      starts.push_back({nll(th), th});
    }
  std::sort(starts.begin(), starts.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> best;
  double best_nll = INFINITY;
  for (std::size_t i = 0; i < std::min<std::size_t>(4, starts.size()); ++i) {
    const auto th = minimize(nll, starts[i].second, {0.5, 0.5, 1.0, 0.2});
    const double v = nll(th);
    if (v < best_nll) {
      best_nll = v;
      best = th;
    }
  }
  f.lr = 2 * (nll0 - best_nll);
  const std::vector<double> q = {std::exp(best[0]), std::exp(best[1]), std::exp(best[2]), best[3]};
  if (!(f.lr > kOmoriLrThreshold)) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "no excess over the background rate: 2 dlnL = %.3g below %.4g (chi-square, 3 "
                  "degrees of freedom, 0.999); the rate is flat at %.6g",
                  f.lr, kOmoriLrThreshold, mu0);
    f.note = buf;
    return f;
  }
  f.excess = true;
  const auto err = fisher_errors(
      expected, q, {1e-5 * q[0], 1e-5 * q[1], 1e-5 * q[2], 1e-5 * (1 + std::abs(q[3]))});
  f.background = {q[0], err[0]};
  f.K = {q[1], err[1]};
  f.c = {q[2], err[2]};
  f.p = {q[3], err[3]};
  for (std::size_t b : use)
    f.excess_events += d.exposure[b] * q[1] * omori_integral(d.lo[b], d.hi[b], q[2], q[3]);
  if (f.p.value > 0.999 * kMaxP) {
    f.excess = false;
    f.note = "the rate is not of the Omori-Utsu form: p runs to its bound " + std::to_string(kMaxP);
  }
  return f;
}

}  // namespace bkq::seis
