// Streaming mean, variance and the third and fourth central moments (Pébay 2008, Sandia
// report SAND2008-6212, eqs. 1.5 and 2.1), so the coefficient of variation of a stream and
// its standard error come from one pass in flat memory.
#pragma once

#include <cmath>
#include <cstdint>

namespace bkq::seis {

class Moments {
 public:
  void add(double x) {
    const double n1 = static_cast<double>(n_);
    ++n_;
    const double n = static_cast<double>(n_);
    const double d = x - mean_, dn = d / n, dn2 = dn * dn, t = d * dn * n1;
    m4_ += t * dn2 * (n * n - 3 * n + 3) + 6 * dn2 * m2_ - 4 * dn * m3_;
    m3_ += t * dn * (n - 2) - 3 * dn * m2_;
    m2_ += t;
    mean_ += dn;
  }
  std::int64_t n() const { return n_; }
  double mean() const { return n_ > 0 ? mean_ : NAN; }
  double variance() const { return n_ > 1 ? m2_ / static_cast<double>(n_ - 1) : NAN; }
  // Coefficient of variation s / mean: 1 for an exponential law (a Poisson process), 0 for
  // a periodic one.
  double cov() const { return std::sqrt(variance()) / mean(); }
  // Its standard error by the delta method over (mean, variance) with the sample's own
  // third and fourth central moments (Var s^2 = (m4 - s^4)/n, Cov(mean, s^2) = m3/n).
  double cov_err() const {
    if (n_ < 3) return NAN;
    const double n = static_cast<double>(n_), m = mean_, v = m2_ / n, s = std::sqrt(v);
    const double c2 = m3_ / n, c4 = m4_ / n;
    const double gm = -s / (m * m), gv = 1 / (2 * s * m);
    const double var = (gm * gm * v + 2 * gm * gv * c2 + gv * gv * (c4 - v * v)) / n;
    return var > 0 ? std::sqrt(var) : 0.0;
  }

 private:
  std::int64_t n_ = 0;
  double mean_ = 0, m2_ = 0, m3_ = 0, m4_ = 0;
};

// Streaming least squares of y on x (the scaling exponents): slope, intercept and the
// slope's standard error from centred sums.
class LineFit {
 public:
  void add(double x, double y) {
    ++n_;
    const double n = static_cast<double>(n_);
    const double dx = x - mx_, dy = y - my_;
    mx_ += dx / n;
    my_ += dy / n;
    sxx_ += dx * (x - mx_);
    sxy_ += dx * (y - my_);
    syy_ += dy * (y - my_);
  }
  std::int64_t n() const { return n_; }
  double slope() const { return n_ > 1 && sxx_ > 0 ? sxy_ / sxx_ : NAN; }
  double intercept() const { return my_ - slope() * mx_; }
  double slope_err() const {
    if (n_ < 3 || !(sxx_ > 0)) return NAN;
    const double rss = std::max(0.0, syy_ - sxy_ * sxy_ / sxx_);
    return std::sqrt(rss / static_cast<double>(n_ - 2) / sxx_);
  }

 private:
  std::int64_t n_ = 0;
  double mx_ = 0, my_ = 0, sxx_ = 0, sxy_ = 0, syy_ = 0;
};

}  // namespace bkq::seis
