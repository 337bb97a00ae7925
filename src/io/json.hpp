// A tiny JSON writer for summary.json and other small machine-read outputs. An ordered
// object builder (keys keep the order they were added, so files diff cleanly), numbers
// printed so they read back to the same double, strings escaped, pretty-printed by str().
// Numbers go through core/format.hpp's format_real().
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/format.hpp"

namespace bkq {

class Json {
 public:
  enum class Kind { Null, Bool, Integer, Number, String, Array, Object };

  Json() = default;  // null
  static Json null() { return Json(); }
  static Json boolean(bool b);
  static Json integer(std::int64_t i);
  static Json number(double x);  // non-finite values are written as null (JSON has no inf/nan)
  static Json string(std::string s);
  static Json array();
  static Json object();

  // Object: appends (or replaces, keeping its place) a member; returns *this for chaining.
  Json& set(const std::string& key, Json value);
  Json& set(const std::string& key, double x) { return set(key, number(x)); }
  Json& set(const std::string& key, int i) { return set(key, integer(i)); }
  Json& set(const std::string& key, std::int64_t i) { return set(key, integer(i)); }
  Json& set(const std::string& key, bool b) { return set(key, boolean(b)); }
  Json& set(const std::string& key, const char* s) { return set(key, string(s)); }
  Json& set(const std::string& key, const std::string& s) { return set(key, string(s)); }
  // Array: appends an element.
  Json& push(Json value);

  Kind kind() const { return kind_; }
  // Pretty text (two-space indent), no trailing newline.
  std::string str() const;

 private:
  void write(std::string& out, int indent) const;

  Kind kind_ = Kind::Null;
  bool b_ = false;
  std::int64_t i_ = 0;
  double x_ = 0;
  std::string s_;
  std::vector<std::pair<std::string, Json>> members_;  // Object
  std::vector<Json> items_;                            // Array
};

// A JSON string literal with quotes and escapes.
std::string json_quote(const std::string& s);

}  // namespace bkq
