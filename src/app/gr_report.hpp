// Presentation of a Gutenberg-Richter fit: the short human table printed by `bkquake fit`
// and the JSON object written by `bkquake fit --json` and `bkquake merge`. A minimal
// ordered JSON object writer lives here so the statistics do not depend on the I/O layer;
// non-finite numbers are written as null (JSON has no inf/nan).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "stats/event_classes.hpp"
#include "stats/gutenberg_richter.hpp"

namespace bkq {

class JsonObject {
 public:
  JsonObject& add(const std::string& key, double x);
  JsonObject& add(const std::string& key, std::int64_t i);
  JsonObject& add(const std::string& key, int i) { return add(key, static_cast<std::int64_t>(i)); }
  JsonObject& add(const std::string& key, bool b);
  JsonObject& add(const std::string& key, const std::string& s);
  JsonObject& add(const std::string& key, const char* s) { return add(key, std::string(s)); }
  JsonObject& add(const std::string& key, const JsonObject& o);
  JsonObject& add(const std::string& key, const std::vector<std::string>& strings);
  // Pretty text, two-space indent, no trailing newline.
  std::string str(int indent = 0) const;

 private:
  std::vector<std::pair<std::string, std::string>> raw_;  // key, JSON text (nested: marker)
  std::vector<JsonObject> nested_;
};

std::string json_string(const std::string& s);
std::string json_number(double x);

JsonObject gr_fit_json(const GrFit& f);
JsonObject class_counts_json(const EventClassCounts& c);

// Human-readable block of lines (trailing newline included).
std::string gr_fit_table(const GrFit& f);
std::string class_counts_table(const EventClassCounts& c);

}  // namespace bkq
