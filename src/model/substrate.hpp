// The substrate's motion (Ferre 2018 ch. 4): constant speed, a step schedule (Ferre 2018 §4: start
// at v0 and add an increment every interval) or a linear ramp. The displacement s(t) is the exact
// integral of the speed, so long runs accumulate no drift from the schedule. Event-driven
// relaxation uses a frozen substrate (speed 0 at a fixed s).
#pragma once

#include <cmath>

#include "model/chain.hpp"

namespace bkq {

class Substrate {
 public:
  enum class Kind { Frozen, Constant, Steps, Ramp };

  Substrate() = default;
  static Substrate frozen(double s) { return Substrate(Kind::Frozen, s, 0, 0, 0, 1); }
  static Substrate constant(double v) { return Substrate(Kind::Constant, 0, v, 0, 0, 1); }
  static Substrate steps(double v0, double increment, double interval) {
    return Substrate(Kind::Steps, 0, v0, 0, increment, interval);
  }
  static Substrate ramp(double from, double to, double duration) {
    return Substrate(Kind::Ramp, 0, from, to, 0, duration);
  }

  Kind kind() const { return kind_; }

  SubstrateState at(double t) const {
    switch (kind_) {
      case Kind::Frozen:
        return {s0_, 0.0, 0.0};
      case Kind::Constant:
        return {v0_ * t, v0_, 0.0};
      case Kind::Steps: {
        // v = v0 + k inc on [k I, (k+1) I); s integrates it piecewise.
        const double k = std::floor(t / interval_);
        const double s =
            v0_ * t + inc_ * (interval_ * k * (k - 1.0) / 2.0 + k * (t - k * interval_));
        return {s, v0_ + k * inc_, 0.0};
      }
      case Kind::Ramp: {
        const double rate = (v1_ - v0_) / interval_;
        if (t <= interval_) return {v0_ * t + 0.5 * rate * t * t, v0_ + rate * t, rate};
        const double s_end = v0_ * interval_ + 0.5 * rate * interval_ * interval_;
        return {s_end + v1_ * (t - interval_), v1_, 0.0};
      }
    }
    return {};
  }

  // Speed jump at a schedule step inside (t0, t1] (0 if none): sliding blocks keep their
  // lab velocity u' = w' - v, so their velocity w' relative to the substrate jumps by this.
  double speed_jump(double t0, double t1) const {
    if (kind_ != Kind::Steps) return 0.0;
    const double k0 = std::floor(t0 / interval_), k1 = std::floor(t1 / interval_);
    return (k1 - k0) * inc_;
  }

 private:
  Substrate(Kind kind, double s0, double v0, double v1, double inc, double interval)
      : kind_(kind), s0_(s0), v0_(v0), v1_(v1), inc_(inc), interval_(interval) {}

  Kind kind_ = Kind::Frozen;
  double s0_ = 0, v0_ = 0, v1_ = 0, inc_ = 0, interval_ = 1;
};

}  // namespace bkq
