// Carlson, Langer, Shaw & Tang 1991 (eq. 2.9): phi(y) = F0 (1-s)/(1 + y/((1-s) v_c)) for
// y > 0 only: a block never slides backwards (backslip forbidden).
#pragma once

#include <algorithm>
#include <string_view>

#include "model/laws/rational.hpp"

namespace bkq::law {

struct Clst91 : Rational {
  static constexpr std::string_view name = "clst91";
  static constexpr bool backslip = false;
  static constexpr bool frictionless = false;
  static constexpr bool drives_events = true;

  explicit Clst91(const ModelParams& p) : Rational(weakening(p)) {}
  static void check_events(const ModelParams& p) { require_drop(p); }
  double magnitude(double y) const { return at(std::max(y, 0.0)); }
};

}  // namespace bkq::law
