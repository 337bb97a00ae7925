// The substrate's motion (SPEC §3): constant speed, a step schedule (thesis §4: start at
// v0 and add an increment every interval) or a linear ramp. The displacement s(t) is the
// exact integral of the speed, so long runs accumulate no drift from the schedule.
// Event-driven relaxation uses a frozen substrate (speed 0 at a fixed s).
#pragma once

#include <cmath>

#include "model/chain.hpp"

namespace bkq {

class Substrate {
 public:
  enum class Kind { Frozen, Constant, Steps, Ramp };

  static Substrate frozen(double s) {
    Substrate d;
    d.kind_ = Kind::Frozen;
    d.s0_ = s;
    return d;
  }
  static Substrate constant(double v) {
    Substrate d;
    d.kind_ = Kind::Constant;
    d.v0_ = v;
    return d;
  }
  static Substrate steps(double v0, double increment, double interval) {
    Substrate d;
    d.kind_ = Kind::Steps;
    d.v0_ = v0;
    d.inc_ = increment;
    d.interval_ = interval;
    return d;
  }
  static Substrate ramp(double from, double to, double duration) {
    Substrate d;
    d.kind_ = Kind::Ramp;
    d.v0_ = from;
    d.v1_ = to;
    d.interval_ = duration;
    return d;
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
  Kind kind_ = Kind::Frozen;
  double s0_ = 0, v0_ = 0, v1_ = 0, inc_ = 0, interval_ = 1;
};

}  // namespace bkq
