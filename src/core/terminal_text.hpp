// Text for a terminal: a message quotes paths, values and file content, which may hold any
// bytes. Printable ASCII and well-formed UTF-8 of printable characters (a path with ü, a
// scene comment in Greek) are kept as they are; every other byte (control characters, the
// bytes of malformed UTF-8, C1 controls, the bidirectional overrides that could make a line
// read other than it is) is written as \xHH. So a message is one line the terminal shows as
// written, and always valid UTF-8 (Python takes it as a str).
#pragma once

#include <cstddef>
#include <string>

namespace bkq {

namespace detail {

// The length of the well-formed UTF-8 sequence of a printable character at s[i] (2 to 4
// bytes), or 0.
inline std::size_t printable_utf8_length(const std::string& s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
  const auto cont = [&](std::size_t k) { return i + k < s.size() && (b(k) & 0xc0) == 0x80; };
  const unsigned char c = b(0);
  std::size_t len = 0;
  char32_t cp = 0;
  if (c >= 0xc2 && c <= 0xdf) {
    len = 2;
    cp = c & 0x1f;
  } else if (c >= 0xe0 && c <= 0xef) {
    len = 3;
    cp = c & 0x0f;
  } else if (c >= 0xf0 && c <= 0xf4) {
    len = 4;
    cp = c & 0x07;
  } else {
    return 0;
  }
  for (std::size_t k = 1; k < len; ++k) {
    if (!cont(k)) return 0;
    cp = (cp << 6) | (b(k) & 0x3f);
  }
  const char32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < least[len] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  if (cp < 0xa0) return 0;                                                         // C1 controls
  if ((cp >= 0x202a && cp <= 0x202e) || (cp >= 0x2066 && cp <= 0x2069)) return 0;  // bidi
  if (cp == 0x2028 || cp == 0x2029 || cp == 0xfeff) return 0;  // line breaks, BOM
  return len;
}

}  // namespace detail

// `s` with what a terminal would not show as written escaped as \xHH (see above), at most
// `max` characters kept (then "...").
inline std::string printable_text(const std::string& s, std::size_t max = 1000) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < s.size();) {
    if (kept++ == max) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++i;
    } else if (const std::size_t len = detail::printable_utf8_length(s, i)) {
      out.append(s, i, len);
      i += len;
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
      ++i;
    }
  }
  return out;
}

// `s` in single quotes for an error message, as printable_text.
inline std::string quote_text(const std::string& s, std::size_t max = 80) {
  std::string out(1, '\'');
  out += printable_text(s, max);
  out += '\'';
  return out;
}

}  // namespace bkq
