// The one JSON writer of bkquake (summary.json, `bkquake fit --json`, merge's summary.json)
// and a small reader for the numbers other commands take back from those files. An ordered
// object builder (keys keep the order they were added, so files diff cleanly), numbers
// printed so they read back to the same double (core/format.hpp's format_real()), non-finite
// numbers written as null (JSON has no inf/nan), strings escaped, pretty-printed by str().
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/format.hpp"

namespace bkq {

class Json {
 public:
  enum class Kind { Null, Bool, Integer, Number, String, Array, Object };
  // How a real number is written: `point` keeps it recognisably real ("2.0", for readers
  // that tell ints from floats: summary.json of a run); `shortest` writes format_real()
  // as it is ("2": the fit reports of `bkquake fit --json` and `bkquake merge`).
  enum class Real { point, shortest };

  Json() = default;  // null
  static Json null() { return Json(); }
  static Json boolean(bool b);
  static Json integer(std::int64_t i);
  // Non-finite values are written as null (JSON has no inf/nan).
  static Json number(double x, Real style = Real::point);
  static Json string(std::string s);
  static Json array();
  // An array written on one line, `["a", "b"]`: short lists such as notes or run folders.
  static Json inline_array();
  static Json strings(const std::vector<std::string>& items);  // an inline array of strings
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
  Real style_ = Real::point;  // Number
  bool inline_ = false;       // Array
  bool b_ = false;
  std::int64_t i_ = 0;
  double x_ = 0;
  std::string s_;
  std::vector<std::pair<std::string, Json>> members_;  // Object
  std::vector<Json> items_;                            // Array
};

// The deepest nesting the reader follows (bkquake writes at most 3 levels); deeper text is
// refused with bkq::Error, as is any text the reader cannot walk.
inline constexpr std::size_t kMaxJsonDepth = 256;

// A JSON string literal with quotes and escapes.
std::string json_quote(const std::string& s);

// The number stored under a top-level `key` of the JSON object in `text`; nullopt when the
// key is absent or null. bkq::Error naming `origin` when the text is not a JSON object or the
// value is not a number. Nested objects and arrays are skipped, not searched.
std::optional<double> json_top_level_number(const std::string& text, const std::string& key,
                                            const std::string& origin);
// The same for a string value (escapes kept as written); nullopt when absent or null.
std::optional<std::string> json_top_level_string(const std::string& text, const std::string& key,
                                                 const std::string& origin);

// The same at a dotted path through nested objects ("omori.p": member p of the top-level
// object omori); nullopt when a member on the way is absent or null.
std::optional<double> json_number_at(const std::string& text, const std::string& path,
                                     const std::string& origin);
std::optional<std::string> json_string_at(const std::string& text, const std::string& path,
                                          const std::string& origin);

}  // namespace bkq
