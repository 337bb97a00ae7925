// The JSON writer and number reader of json.hpp.
#include "io/json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <utility>

#include "core/error.hpp"

namespace bkq {

Json Json::boolean(bool b) {
  Json j;
  j.kind_ = Kind::Bool;
  j.b_ = b;
  return j;
}
Json Json::integer(std::int64_t i) {
  Json j;
  j.kind_ = Kind::Integer;
  j.i_ = i;
  return j;
}
Json Json::number(double x, Real style) {
  Json j;
  if (!std::isfinite(x)) return j;
  j.kind_ = Kind::Number;
  j.x_ = x;
  j.style_ = style;
  return j;
}
Json Json::string(std::string s) {
  Json j;
  j.kind_ = Kind::String;
  j.s_ = std::move(s);
  return j;
}
Json Json::array() {
  Json j;
  j.kind_ = Kind::Array;
  return j;
}
Json Json::inline_array() {
  Json j = array();
  j.inline_ = true;
  return j;
}
Json Json::strings(const std::vector<std::string>& items) {
  Json j = inline_array();
  for (const auto& s : items) j.push(string(s));
  return j;
}
Json Json::object() {
  Json j;
  j.kind_ = Kind::Object;
  return j;
}

Json& Json::set(const std::string& key, Json value) {
  kind_ = Kind::Object;
  for (auto& m : members_) {
    if (m.first == key) {
      m.second = std::move(value);
      return *this;
    }
  }
  members_.emplace_back(key, std::move(value));
  return *this;
}

Json& Json::push(Json value) {
  kind_ = Kind::Array;
  items_.push_back(std::move(value));
  return *this;
}

std::string json_quote(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  out += '"';
  return out;
}

void Json::write(std::string& out, int indent) const {
  const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
  const std::string close_pad(static_cast<std::size_t>(indent), ' ');
  switch (kind_) {
    case Kind::Null:
      out += "null";
      break;
    case Kind::Bool:
      out += b_ ? "true" : "false";
      break;
    case Kind::Integer:
      out += std::to_string(i_);
      break;
    case Kind::Number: {
      std::string t = format_real(x_);
      if (style_ == Real::point && t.find_first_of(".eE") == std::string::npos) t += ".0";
      out += t;
      break;
    }
    case Kind::String:
      out += json_quote(s_);
      break;
    case Kind::Array:
      if (items_.empty()) {
        out += "[]";
        break;
      }
      if (inline_) {
        out += "[";
        for (std::size_t k = 0; k < items_.size(); ++k) {
          if (k) out += ", ";
          items_[k].write(out, indent);
        }
        out += "]";
        break;
      }
      out += "[\n";
      for (std::size_t k = 0; k < items_.size(); ++k) {
        out += pad;
        items_[k].write(out, indent + 2);
        out += k + 1 < items_.size() ? ",\n" : "\n";
      }
      out += close_pad + "]";
      break;
    case Kind::Object:
      if (members_.empty()) {
        out += "{}";
        break;
      }
      out += "{\n";
      for (std::size_t k = 0; k < members_.size(); ++k) {
        out += pad + json_quote(members_[k].first) + ": ";
        members_[k].second.write(out, indent + 2);
        out += k + 1 < members_.size() ? ",\n" : "\n";
      }
      out += close_pad + "}";
      break;
  }
}

std::string Json::str() const {
  std::string out;
  write(out, 0);
  return out;
}

namespace {

// A forward-only scanner over JSON text: enough to walk an object's members and skip any
// value, so a top-level key is never confused with a nested one or with a string value.
class Scanner {
 public:
  Scanner(const std::string& text, const std::string& origin) : t_(text), origin_(origin) {}

  void space() {
    while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\t' || t_[i_] == '\n' || t_[i_] == '\r'))
      ++i_;
  }
  bool at(char c) {
    space();
    return i_ < t_.size() && t_[i_] == c;
  }
  void expect(char c) {
    if (!at(c)) fail(std::string("expected '") + c + "'");
    ++i_;
  }
  std::string string() {
    expect('"');
    std::string s;
    while (i_ < t_.size() && t_[i_] != '"') {
      if (t_[i_] == '\\') ++i_;  // the escaped character is kept as written: keys are plain
      if (i_ < t_.size()) s += t_[i_++];
    }
    if (i_ >= t_.size()) fail("unterminated string");
    ++i_;
    return s;
  }
  // A scalar token (number, true, false, null) as written.
  std::string token() {
    space();
    const std::size_t b = i_;
    while (i_ < t_.size() && std::string_view(",}] \t\r\n").find(t_[i_]) == std::string_view::npos)
      ++i_;
    if (i_ == b) fail("expected a value");
    return t_.substr(b, i_ - b);
  }
  // Skips one value of any kind without recursion: nesting deeper than kMaxJsonDepth is
  // refused, so a hostile or damaged file cannot exhaust the stack.
  void skip_value() {
    std::string open;  // the closing bracket of each structure entered
    while (true) {
      if (at('"')) {
        string();
      } else if (at('{') || at('[')) {
        const char close = t_[i_] == '{' ? '}' : ']';
        ++i_;
        if (at(close)) {
          ++i_;
        } else {
          if (open.size() >= kMaxJsonDepth)
            fail("nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
          open += close;
          if (close == '}') {
            string();
            expect(':');
          }
          continue;  // the structure's first value
        }
      } else {
        token();
      }
      // After a value: the next one of the innermost structure, or its end.
      while (true) {
        if (open.empty()) return;
        if (at(',')) {
          ++i_;
          if (open.back() == '}') {
            string();
            expect(':');
          }
          break;
        }
        expect(open.back());
        open.pop_back();
      }
    }
  }
  std::size_t pos() {
    space();
    return i_;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(origin_ + ": not a JSON object: " + what + " at offset " + std::to_string(i_));
  }

 private:
  const std::string& t_;
  const std::string& origin_;
  std::size_t i_ = 0;
};

}  // namespace

namespace {

// Walks the top-level members of the object in `text` to `key` and returns read(scanner)
// positioned at its value; nullopt when the key is absent.
template <class Read>
auto read_top_level(const std::string& text, const std::string& key, const std::string& origin,
                    Read read) -> decltype(read(std::declval<Scanner&>())) {
  Scanner s(text, origin);
  s.expect('{');
  if (s.at('}')) return std::nullopt;
  while (true) {
    const std::string k = s.string();
    s.expect(':');
    if (k == key) return read(s);
    s.skip_value();
    if (s.at(',')) {
      s.expect(',');
      continue;
    }
    s.expect('}');
    return std::nullopt;
  }
}

}  // namespace

std::optional<double> json_top_level_number(const std::string& text, const std::string& key,
                                            const std::string& origin) {
  return read_top_level(text, key, origin, [&](Scanner& s) -> std::optional<double> {
    if (s.at('"') || s.at('{') || s.at('[')) {
      throw Error(origin + ": \"" + key + "\": expected a number, got a " +
                  (s.at('"') ? "string" : "structure"));
    }
    const std::string v = s.token();
    if (v == "null") return std::nullopt;
    double x = 0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
    if (ec != std::errc() || ptr != v.data() + v.size())
      throw Error(origin + ": \"" + key + "\": expected a number, got " + v);
    return x;
  });
}

std::optional<std::string> json_top_level_string(const std::string& text, const std::string& key,
                                                 const std::string& origin) {
  return read_top_level(text, key, origin, [&](Scanner& s) -> std::optional<std::string> {
    if (s.at('"')) return s.string();
    if (s.at('{') || s.at('[')) s.fail("\"" + key + "\": expected a string, got a structure");
    const std::string v = s.token();
    if (v == "null") return std::nullopt;
    throw Error(origin + ": \"" + key + "\": expected a string, got " + quote_printable(v));
  });
}

namespace {

// The text of the object at `path` ("a.b": member b of the top-level member a); nullopt
// when a member on the way is absent or null. `last` gets the path's last key.
std::optional<std::string> enclosing_object(const std::string& text, const std::string& path,
                                            const std::string& origin, std::string& last) {
  std::string inner = text;
  std::size_t from = 0;
  for (std::size_t dot = path.find('.'); dot != std::string::npos; dot = path.find('.', from)) {
    const std::string key = path.substr(from, dot - from);
    const auto member =
        read_top_level(inner, key, origin, [&](Scanner& s) -> std::optional<std::string> {
          if (!s.at('{')) {
            if (s.token() == "null") return std::nullopt;
            throw Error(origin + ": \"" + path.substr(0, dot) + "\": expected an object");
          }
          const std::size_t b = s.pos();
          s.skip_value();
          return inner.substr(b, s.pos() - b);
        });
    if (!member) return std::nullopt;
    inner = *member;
    from = dot + 1;
  }
  last = path.substr(from);
  return inner;
}

}  // namespace

std::optional<double> json_number_at(const std::string& text, const std::string& path,
                                     const std::string& origin) {
  std::string key;
  const auto inner = enclosing_object(text, path, origin, key);
  return inner ? json_top_level_number(*inner, key, origin + " (" + path + ")") : std::nullopt;
}

std::optional<std::string> json_string_at(const std::string& text, const std::string& path,
                                          const std::string& origin) {
  std::string key;
  const auto inner = enclosing_object(text, path, origin, key);
  return inner ? json_top_level_string(*inner, key, origin + " (" + path + ")") : std::nullopt;
}

}  // namespace bkq
