// Closed-form motion of a damped linear oscillator m xi'' + c xi' + k xi = 0 (Ferre 2018 eq.
// 3.11–3.13), all three regimes, plus a bound on |xi| over all later times. The event
// engine uses it for the pad once every block is stuck.
#pragma once

#include <algorithm>
#include <cmath>

namespace bkq {

class DampedOscillator {
 public:
  DampedOscillator(double m, double c, double k, double xi0, double v0) {
    gamma_ = c / (2.0 * m);
    const double w0sq = k / m;
    const double disc = gamma_ * gamma_ - w0sq;
    const double scale = std::max(w0sq, gamma_ * gamma_);
    if (disc < -1e-12 * scale) {
      regime_ = Under;
      wd_ = std::sqrt(-disc);
      a_ = xi0;
      b_ = (v0 + gamma_ * xi0) / wd_;
    } else if (disc > 1e-12 * scale) {
      regime_ = Over;
      const double r = std::sqrt(disc);
      l1_ = -gamma_ + r;  // slow
      l2_ = -gamma_ - r;  // fast
      // xi = a e^{l1 t} + b e^{l2 t}
      b_ = (v0 - l1_ * xi0) / (l2_ - l1_);
      a_ = xi0 - b_;
    } else {
      regime_ = Critical;
      a_ = xi0;
      b_ = v0 + gamma_ * xi0;
    }
  }

  double position(double t) const {
    switch (regime_) {
      case Under:
        return std::exp(-gamma_ * t) * (a_ * std::cos(wd_ * t) + b_ * std::sin(wd_ * t));
      case Over:
        return a_ * std::exp(l1_ * t) + b_ * std::exp(l2_ * t);
      case Critical:
        return (a_ + b_ * t) * std::exp(-gamma_ * t);
    }
    return 0;
  }
  double velocity(double t) const {
    switch (regime_) {
      case Under: {
        const double e = std::exp(-gamma_ * t), c = std::cos(wd_ * t), s = std::sin(wd_ * t);
        return e * ((b_ * wd_ - gamma_ * a_) * c - (a_ * wd_ + gamma_ * b_) * s);
      }
      case Over:
        return a_ * l1_ * std::exp(l1_ * t) + b_ * l2_ * std::exp(l2_ * t);
      case Critical:
        return (b_ - gamma_ * (a_ + b_ * t)) * std::exp(-gamma_ * t);
    }
    return 0;
  }
  // An upper bound of |xi(tau)| for every tau >= t (non-increasing in t).
  double bound_after(double t) const {
    switch (regime_) {
      case Under:
        return std::exp(-gamma_ * t) * std::hypot(a_, b_);
      case Over:
        return std::abs(a_) * std::exp(l1_ * t) + std::abs(b_) * std::exp(l2_ * t);
      case Critical: {
        const double a = std::abs(a_), b = std::abs(b_);
        const double peak = b > 0 && gamma_ > 0 ? 1.0 / gamma_ - a / b : t;
        const double tau = std::max(t, peak);
        return (a + b * tau) * std::exp(-gamma_ * tau);
      }
    }
    return 0;
  }
  // A time step that resolves every extremum of xi (1/16 of the fastest time scale).
  double resolution() const {
    switch (regime_) {
      case Under:
        return std::min(M_PI / wd_, gamma_ > 0 ? 1.0 / gamma_ : HUGE_VAL) / 16.0;
      case Over:
        return 1.0 / (16.0 * std::abs(l2_));
      case Critical:
        return 1.0 / (16.0 * gamma_);
    }
    return 1;
  }

 private:
  enum Regime { Under, Over, Critical } regime_;
  double gamma_ = 0, wd_ = 0, l1_ = 0, l2_ = 0, a_ = 0, b_ = 0;
};

}  // namespace bkq
