// Carlson & Langer 1989 (eq. 2.3): phi(y) = F0 sgn y/(1 + |y|/v_c), backslip allowed. It
// has no drop from static to kinetic friction, so it drives continuous runs only.
#pragma once

#include <cmath>
#include <string_view>

#include "model/laws/rational.hpp"

namespace bkq::law {

struct Cl89 : Rational {
  static constexpr std::string_view name = "cl89";
  static constexpr bool backslip = true;
  static constexpr bool frictionless = false;
  static constexpr bool drives_events = false;

  explicit Cl89(const ModelParams& p)
      : Rational{p.F0, std::isfinite(p.v_c) ? 1.0 / p.v_c : 0.0, p.threshold()} {}
  static void check_events(const ModelParams&) {
    throw Error(
        "friction.law: 'cl89' has no drop from static to kinetic friction, so event-driven runs "
        "never start an event; use thesis or clst91 with friction.sigma > 0, or drive.mode = "
        "continuous");
  }
  double magnitude(double y) const { return at(std::abs(y)); }
};

}  // namespace bkq::law
