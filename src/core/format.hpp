// The one number formatter of every text output and error message: the shortest text
// that reads back to the same double ("nan", "inf", "-inf" for the non-finite ones).
#pragma once

#include <charconv>
#include <cmath>
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

}  // namespace bkq

namespace bkq {

// `s` in single quotes for an error message, with every byte that is not printable ASCII
// written as \xHH and at most `max` characters kept (then "..."): a corrupt or binary file
// never puts raw bytes on a terminal.
inline std::string quote_printable(const std::string& s, std::size_t max = 80) {
  static const char* hex = "0123456789abcdef";
  std::string out = "'";
  std::size_t kept = 0;
  for (const char ch : s) {
    if (kept++ == max) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out + "'";
}

}  // namespace bkq
