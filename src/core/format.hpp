// The one number formatter of every text output and error message: the shortest text
// that reads back to the same double ("nan", "inf", "-inf" for the non-finite ones).
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

namespace bkq {

// The longest text format_real_to writes ("-2.2250738585072014e-308").
inline constexpr int kMaxRealChars = 24;

// format_real's text written at `out` (room for kMaxRealChars); returns the end.
inline char* format_real_to(char* out, double x) {
  if (std::isnan(x)) return std::char_traits<char>::copy(out, "nan", 3) + 3;
  if (std::isinf(x))
    return x > 0 ? std::char_traits<char>::copy(out, "inf", 3) + 3
                 : std::char_traits<char>::copy(out, "-inf", 4) + 4;
  return std::to_chars(out, out + kMaxRealChars, x).ptr;
}

inline std::string format_real(double x) {
  char buf[kMaxRealChars];
  return std::string(buf, format_real_to(buf, x));
}

// "0.90012 ± 0.00040": a value and its standard error with enough decimals that the error
// shows two significant digits (at least `min_decimals`), so an error never rounds to zero.
// Both must be finite (a caller says why there is no estimate otherwise).
inline std::string format_with_error(double value, double error, int min_decimals = 3) {
  int decimals = min_decimals;
  if (error > 0 && std::isfinite(error))
    decimals =
        std::max(decimals, std::min(15, 1 - static_cast<int>(std::floor(std::log10(error)))));
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.*f ± %.*f", decimals, value, decimals, error);
  return buf;
}

// `s` with every byte that is not printable ASCII written as \xHH, at most
// `max` characters of it kept (then "..."): file content and user values in a message
// never put raw bytes on a terminal.
inline std::string escape_unprintable(const std::string& s, std::size_t max = 1000) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  std::size_t kept = 0;
  for (const char ch : s) {
    if (kept++ == max) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

// `s` in single quotes for an error message, escaped and shortened as above.
inline std::string quote_printable(const std::string& s, std::size_t max = 80) {
  std::string out(1, '\'');  // appended, not "'" + ...: GCC 12 warns falsely (-Wrestrict)
  out += escape_unprintable(s, max);
  out += '\'';
  return out;
}

}  // namespace bkq
