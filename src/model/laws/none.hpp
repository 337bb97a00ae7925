// No friction: every block slides freely and nothing ever sticks (threshold below 0).
// For verification against analytic solutions, in continuous runs.
#pragma once

#include <cmath>
#include <string_view>

#include "model/laws/rational.hpp"

namespace bkq::law {

struct None : Rational {
  static constexpr std::string_view name = "none";
  static constexpr bool backslip = true;
  static constexpr bool frictionless = true;
  static constexpr bool drives_events = false;

  explicit None(const ModelParams&) : Rational{0.0, 0.0, -1.0} {}
  static void check_events(const ModelParams&) {
    throw Error(
        "friction.law: 'none' cannot drive events (nothing ever sticks); use drive.mode = "
        "continuous");
  }
  double magnitude(double y) const { return at(std::abs(y)); }
};

}  // namespace bkq::law
