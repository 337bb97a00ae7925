// The thesis law (eq. 3.5): phi(y) = F0 (1-s)/(1 + |y|/((1-s) v_c)) sgn y; a block may
// slide both ways (backslip).
#pragma once

#include <cmath>
#include <string_view>

#include "model/laws/rational.hpp"

namespace bkq::law {

struct Thesis : Rational {
  static constexpr std::string_view name = "thesis";
  static constexpr bool backslip = true;
  static constexpr bool frictionless = false;
  static constexpr bool drives_events = true;

  explicit Thesis(const ModelParams& p) : Rational(weakening(p)) {}
  static void check_events(const ModelParams& p) { require_drop(p); }
  double magnitude(double y) const { return at(std::abs(y)); }
};

}  // namespace bkq::law
