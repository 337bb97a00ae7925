// The Scene that reads, checks and writes bkquake's parameter table. Every key is declared
// exactly once, as a row of io/scene_table.cpp (type, default, range, units, doc, member,
// when it applies); reading (INI files through io/ini.hpp, the one INI parser, and --set
// overrides), validation, --dump-defaults and the effective scene.ini of each run are all
// driven by those rows. Values are stored as normalised text (shortest
// round-trip reals, true/false booleans) so equal scenes hash equally.
#include "io/scene.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "core/fnv1a.hpp"
#include "core/format.hpp"
#include "core/terminal_text.hpp"
#include "io/ini.hpp"
#include "io/json.hpp"

namespace bkq {

namespace {

constexpr double kMaxInt64 = 9223372036854775807.0;  // 2^63 - 1 (rounds to 2^63 as a double)

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string bound_text(const ParamSpec& p, double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (p.type == ParamType::Integer) {
    if (x >= kMaxInt64) return "9223372036854775807";
    return std::to_string(static_cast<std::int64_t>(x));
  }
  return format_real(x);
}

std::string suffix(const std::string& origin) {
  return origin.empty() ? "" : " (" + origin + ")";
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

[[noreturn]] void unknown_key(const std::string& key, const std::string& origin) {
  throw Error("unknown key '" + key + "'" + suffix(origin) + key_suggestion(key));
}

// Parses `text` for `p`; returns the normalised text or throws naming key, value and range.
std::string normalise(const ParamSpec& p, const std::string& raw, const std::string& origin) {
  const std::string text = trim(raw);
  const std::string where = suffix(origin);
  // A NUL byte would end the message that quotes the value (a C string) and hide the rest.
  if (const auto nul = raw.find('\0'); nul != std::string::npos)
    throw Error(p.key + ": the value holds a NUL byte at character " + std::to_string(nul + 1) +
                ", which no value may contain" + where);
  switch (p.type) {
    case ParamType::Choice: {
      const std::vector<std::string> choices = p.allowed_choices();
      if (std::find(choices.begin(), choices.end(), text) == choices.end())
        throw Error(p.key + ": expected one of " + allowed_text(p) + ", got '" + text + "'" +
                    where);
      return text;
    }
    case ParamType::Path:
      return text;
    case ParamType::Boolean: {
      const std::string t = lower(text);
      if (t == "true" || t == "yes" || t == "1" || t == "on") return "true";
      if (t == "false" || t == "no" || t == "0" || t == "off") return "false";
      throw Error(p.key + ": expected a boolean (true|false|yes|no|on|off|1|0), got '" + text +
                  "'" + where);
    }
    case ParamType::Integer: {
      const std::string what = "expected an integer in " + allowed_text(p);
      std::int64_t v = 0;
      const char* b = text.data();
      const char* e = text.data() + text.size();
      if (b != e && *b == '+') ++b;
      const auto res = std::from_chars(b, e, v);
      if (text.empty() || res.ec == std::errc::invalid_argument || res.ptr != e)
        throw Error(p.key + ": " + what + ", got '" + text + "'" + where);
      if (res.ec == std::errc::result_out_of_range)
        throw Error(p.key + ": " + what + ", got " + text + " (too large)" + where);
      if (static_cast<double>(v) < p.min || static_cast<double>(v) > p.max)
        throw Error(p.key + ": " + what + ", got " + text + where);
      return std::to_string(v);
    }
    case ParamType::Real: {
      if (p.allow_auto && text == p.keyword) return text;
      const std::string what = "expected a value in " + allowed_text(p);
      double v = 0;
      const char* b = text.data();
      const char* e = text.data() + text.size();
      if (b != e && *b == '+') ++b;
      const auto res = std::from_chars(b, e, v);
      // from_chars reports tiny/huge magnitudes as out of range; those are still numbers
      // and are judged by the range check (huge ones end up as inf, outside every range).
      if (text.empty() || res.ec == std::errc::invalid_argument || res.ptr != e || std::isnan(v))
        throw Error(p.key + ": " + what + ", got '" + text + "'" + where);
      if (res.ec == std::errc::result_out_of_range)
        v = std::strtod(std::string(b, e).c_str(), nullptr);
      const bool below = p.min_open ? !(v > p.min) : !(v >= p.min);
      const bool above = p.max_open ? !(v < p.max) : !(v <= p.max);
      if (below || above || std::isinf(v))
        throw Error(p.key + ": " + what + ", got " + text + where);
      return format_real(v);
    }
  }
  return text;
}

}  // namespace

namespace {

std::string join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : sep) + p;
  return out;
}

// "drive.schedule = steps", "model.parameterisation = thesis or model.kind = bkp".
std::string needs_text(const Requirement& r) {
  std::vector<std::string> parts;
  for (const auto& c : r.any_of) parts.push_back(c.controller + " = " + join(c.allowed(), "|"));
  return join(parts, " or ");
}

// "drive.schedule = constant", "model.parameterisation = carlson-langer and model.kind = bk".
std::string now_text(const Scene& s, const Requirement& r) {
  std::vector<std::string> now;
  for (const auto& c : r.any_of) now.push_back(c.controller + " = " + s.text(c.controller));
  return join(now, " and ");
}

bool holds(const Scene& s, const Requirement& r) {
  if (r.holds) return r.holds(s);
  for (const auto& c : r.any_of) {
    const std::vector<std::string> values = c.allowed();
    if (std::find(values.begin(), values.end(), s.text(c.controller)) != values.end()) return true;
  }
  return false;
}

}  // namespace

const Requirement* Scene::failing_requirement(const ParamSpec& p) const {
  for (const Requirement& r : p.applies_when)
    if (!holds(*this, r)) return &r;
  return nullptr;
}

std::string Scene::why_not(const std::string& key) const {
  const ParamSpec* p = find_param(key);
  if (!p) throw std::logic_error("scene: no parameter '" + key + "'");
  const Requirement* r = failing_requirement(*p);
  if (!r) return "";
  if (r->why_not) return r->why_not(*this);
  return "needs " + needs_text(*r) + ", but " + now_text(*this, *r);
}

const std::vector<ParamSpec>& parameter_table() {
  static const std::vector<ParamSpec> table = make_parameter_table();
  return table;
}

const ParamSpec* find_param(const std::string& key) {
  for (const auto& p : parameter_table())
    if (p.key == key) return &p;
  return nullptr;
}

namespace {
std::string allowed_text(const ParamSpec& p, const std::vector<std::string>& choices) {
  switch (p.type) {
    case ParamType::Choice:
      return join(choices, "|");
    case ParamType::Boolean:
      return "true|false";
    case ParamType::Path:
      return "a file path";
    case ParamType::Integer:
    case ParamType::Real: {
      std::string s = std::string(p.min_open ? "(" : "[") + bound_text(p, p.min) + ", " +
                      bound_text(p, p.max) + (p.max_open ? ")" : "]");
      if (p.allow_auto) s += " or " + p.keyword;
      return s;
    }
  }
  return "";
}
}  // namespace

std::string allowed_text(const ParamSpec& p) {
  return allowed_text(p, p.allowed_choices());
}

std::string documented_allowed_text(const ParamSpec& p) {
  return allowed_text(p, p.choices);
}

std::string option_value(const std::string& option, const std::string& key,
                         const std::string& text) {
  const ParamSpec* p = find_param(key);
  if (!p) throw std::logic_error("option_value: no parameter '" + key + "'");
  try {
    return normalise(*p, text, "");
  } catch (const Error&) {
    throw Error(option + ": expected " +
                (p->type == ParamType::Integer ? "an integer" : std::string("a value")) + " in " +
                allowed_text(*p) + " (as " + key + "), got " + quote_text(trim(text)));
  }
}

Scene::Scene() : origin(kBuiltInOrigin) {
  for (const auto& p : parameter_table()) {
    values_[p.key] = normalise(p, p.default_value, "default");
    given_[p.key] = false;
  }
}

Scene Scene::from_file(const std::string& path) {
  Scene scene = from_text(read_text_file(path, "scene file"), path);
  scene.resolve_paths(std::filesystem::absolute(path).parent_path());
  return scene;
}

void Scene::resolve_paths(const std::filesystem::path& folder) {
  for (const auto& p : parameter_table()) {
    std::string& v = values_[p.key];
    if (p.type == ParamType::Path && !v.empty() && std::filesystem::path(v).is_relative())
      v = (folder / v).lexically_normal().string();
  }
}

Scene Scene::from_text(const std::string& text, const std::string& origin_name) {
  Scene scene;
  scene.origin = origin_name;
  const std::string where = "in " + origin_name;
  std::set<std::string> seen;
  for (const auto& [key, value] : parse_ini(text, where)) {
    if (!find_param(key)) unknown_key(key, where);
    if (!seen.insert(key).second) throw Error(key + ": given more than once" + suffix(where));
    scene.set(key, value, where);
  }
  return scene;
}

void Scene::set(const std::string& key, const std::string& value, const std::string& where) {
  const ParamSpec* p = find_param(key);
  if (!p) unknown_key(key, where);
  values_[key] = normalise(*p, value, where);
  given_[key] = true;
  set_by_[key] = where;
}

void Scene::apply_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos)
    throw Error("--set expects section.key=value, got '" + assignment + "'");
  const std::string key = trim(assignment.substr(0, eq));
  if (key.empty()) throw Error("--set expects section.key=value, got '" + assignment + "'");
  set(key, assignment.substr(eq + 1), "--set");
  resolve_paths(std::filesystem::current_path());
}

bool Scene::applies(const std::string& key) const {
  const ParamSpec* p = find_param(key);
  if (!p) throw std::logic_error("scene: no parameter '" + key + "'");
  return failing_requirement(*p) == nullptr;
}

std::vector<std::string> Scene::drop_inapplicable() {
  std::vector<std::string> warnings;
  // In table order, so a controller is settled before the keys that depend on it.
  for (const auto& p : parameter_table()) {
    if (!is_set(p.key) || p.kept_when_inapplicable || applies(p.key)) continue;
    const std::string& from = set_by_.at(p.key);
    if (from == "--set")
      throw Error("--set " + p.key + "=" + text(p.key) + " does not apply to this scene: it " +
                  why_not(p.key) + "; remove it or change what it depends on");
    warnings.push_back(p.key + " = " + text(p.key) + " (" + from + ") does not apply to this " +
                       "scene: it " + why_not(p.key) + "; ignored");
    values_[p.key] = normalise(p, p.default_value, "default");
    given_[p.key] = false;
  }
  return warnings;
}

bool Scene::overridden() const {
  for (const auto& [key, from] : set_by_)
    if (from == "--set") return true;
  return false;
}

std::string Scene::provenance() const {
  if (origin != kBuiltInOrigin || !overridden()) return origin;
  const std::string& kind = text(key::model_kind);
  const std::string mode = text(key::drive_mode) == "events" ? "event-driven" : "continuous";
  std::string words;
  if (kind == "ofc") {
    words = "ofc";
  } else {
    words = (kind == "bk" ? "" : kind + ", ") + text(key::model_parameterisation);
    if (text(key::friction_law) == "rsf") words += ", rsf";
  }
  return "built-in default with --set overrides (" + words + ", " + mode + ")";
}

std::string Scene::where() const {
  const bool overridden = this->overridden();
  // The built-in default's origin describes the scene it starts as (event-driven); once
  // --set has changed it, that description may no longer hold (drive.mode = continuous).
  if (origin == kBuiltInOrigin)
    return overridden ? " (built-in default scene with --set overrides)"
                      : " (built-in default scene)";
  return suffix("scene " + origin + (overridden ? " with --set overrides" : ""));
}

void Scene::validate() const {
  const std::string where = this->where();
  for (const auto& p : parameter_table()) {
    // A registry's choice read while its value was registered, validated after it was
    // taken away (a test's scheme): refused as reading it now would refuse it.
    if (p.choices_now) {
      const std::vector<std::string> choices = p.choices_now();
      if (std::find(choices.begin(), choices.end(), text(p.key)) == choices.end())
        throw Error(p.key + ": expected one of " + allowed_text(p, choices) + ", got '" +
                    text(p.key) + "'" + where);
    }
    if (!is_set(p.key)) continue;
    const Requirement* r = failing_requirement(p);
    if (!r) continue;
    const std::string refusal = r->refusal ? r->refusal(*this, p.key)
                                           : p.key + " = " + text(p.key) + " applies only with " +
                                                 needs_text(*r) + ", but " + now_text(*this, *r);
    if (!refusal.empty()) throw Error(refusal + where);
  }
  for (const CrossKeyRule rule : cross_key_rules()) rule(*this, where);
}

namespace {
const ParamSpec& spec_of(const std::string& key, ParamType type) {
  const ParamSpec* p = find_param(key);
  if (!p) throw std::logic_error("scene: no parameter '" + key + "'");
  if (p->type != type) throw std::logic_error("scene: parameter '" + key + "' read as wrong type");
  return *p;
}
}  // namespace

double Scene::real(const std::string& key) const {
  const ParamSpec& p = spec_of(key, ParamType::Real);
  const std::string& t = values_.at(key);
  if (p.allow_auto && t == p.keyword)
    throw std::logic_error("scene: " + key + " is " + t + "; read it with real_or_auto()");
  return std::strtod(t.c_str(), nullptr);
}

std::optional<double> Scene::real_or_auto(const std::string& key) const {
  const ParamSpec& p = spec_of(key, ParamType::Real);
  const std::string& t = values_.at(key);
  if (p.allow_auto && t == p.keyword) return std::nullopt;
  return std::strtod(t.c_str(), nullptr);
}

std::int64_t Scene::integer(const std::string& key) const {
  spec_of(key, ParamType::Integer);
  return std::stoll(values_.at(key));
}

const std::string& Scene::choice(const std::string& key) const {
  spec_of(key, ParamType::Choice);
  return values_.at(key);
}

bool Scene::flag(const std::string& key) const {
  spec_of(key, ParamType::Boolean);
  return values_.at(key) == "true";
}

bool Scene::is_set(const std::string& key) const {
  const auto it = given_.find(key);
  if (it == given_.end()) throw std::logic_error("scene: no parameter '" + key + "'");
  return it->second;
}

const std::string& Scene::text(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) throw std::logic_error("scene: no parameter '" + key + "'");
  return it->second;
}

std::string Scene::to_ini(const std::vector<std::string>& header) const {
  std::ostringstream out;
  for (const auto& h : header) out << "# " << h << "\n";
  if (!header.empty()) out << "\n";
  // A section none of whose keys applies (the automaton's [ofc] in a chain's scene, the
  // chain's [friction] in the automaton's) is written as comments, header and all, so a
  // scene's non-comment lines are those of the keys it uses.
  std::map<std::string, bool> used;
  for (const auto& p : parameter_table()) used[p.key.substr(0, p.key.find('.'))] |= applies(p.key);
  std::string section;
  for (const auto& p : parameter_table()) {
    const auto dot = p.key.find('.');
    const std::string sec = p.key.substr(0, dot);
    const std::string name = p.key.substr(dot + 1);
    if (sec != section) {
      const char* mark = used[sec] ? "" : "# ";
      if (!section.empty()) out << (used[sec] ? "\n" : "#\n");
      out << mark << "[" << sec << "]\n";
      section = sec;
    }
    out << "# " << p.doc;
    if (!p.units.empty()) out << " [" << p.units << "]";
    out << " (allowed: " << allowed_text(p) << ")\n";
    const std::string& v = values_.at(p.key);
    if (applies(p.key))
      out << name << " = " << v << "\n";
    else
      out << "# " << name << " = " << v << "  (unused: " << why_not(p.key) << ")\n";
  }
  return out.str();
}

std::uint64_t Scene::hash() const {
  std::uint64_t h = kFnv1a64Basis;
  for (const auto& p : parameter_table()) {
    // An unset file key leaves the hash of the scenes that do not use it as it was; so do
    // the keys added after scenes, their checkpoints and summaries were first hashed, at
    // their defaults (ParamSpec::added_later), so that those keep their hash.
    if (p.type == ParamType::Path && values_.at(p.key).empty()) continue;
    if (p.added_later && values_.at(p.key) == normalise(p, p.default_value, "default")) continue;
    h = fnv1a64(p.key + "=" + values_.at(p.key) + "\n", h);
    // The per-block file's bytes, so that an edited file is another scene (a resume refuses
    // it). An unreadable file hashes as its name alone (the run refuses it when it reads it).
    if (p.key == key::rsf_blocks.name) {
      std::ifstream in(values_.at(p.key), std::ios::binary);
      std::ostringstream bytes;
      if (in && (bytes << in.rdbuf())) h = fnv1a64("rsf.blocks bytes=" + bytes.str() + "\n", h);
    }
  }
  return h;
}

std::string dump_defaults() {
  return Scene().to_ini({"bkquake scene with every key at its default value",
                         "the built-in default: the Carlson-Langer reference, event-driven",
                         "keys shown as comments are unused by this scene's choices"});
}

std::string key_suggestion(const std::string& key) {
  const ParamSpec* best = nullptr;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const auto& p : parameter_table()) {
    const std::size_t d = edit_distance(key, p.key);
    if (d < best_d) {
      best_d = d;
      best = &p;
    }
  }
  // A far-off "suggestion" only confuses; offer one when it plausibly is a typo.
  if (best && best_d <= std::max<std::size_t>(3, key.size() / 3))
    return "; did you mean '" + best->key + "'?";
  return "; see 'bkquake run --dump-defaults' for all keys";
}

}  // namespace bkq
