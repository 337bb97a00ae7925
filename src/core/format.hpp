// The one number formatter of every text output and error message: the shortest text
// that reads back to the same double ("nan", "inf", "-inf" for the non-finite ones).
#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace bkq {

inline std::string format_real(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

}  // namespace bkq
