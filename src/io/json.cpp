// The JSON writer of json.hpp and the shared round-trip number formatter.
#include "io/json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

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
Json Json::number(double x) {
  Json j;
  if (!std::isfinite(x)) return j;
  j.kind_ = Kind::Number;
  j.x_ = x;
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
      // Keep numbers recognisably real for readers that distinguish ints from floats.
      if (t.find_first_of(".eE") == std::string::npos) t += ".0";
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

}  // namespace bkq
