// Scenes: every parameter of bkquake declared once (name, type, default, allowed range,
// units, one-line doc), read from INI files with Boost.Program_options plus
// `--set section.key=value` overrides, validated against that one table. The same table
// writes `bkquake run --dump-defaults` and the effective `scene.ini` of every run.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/scene_keys.hpp"

namespace bkq {

// Path: a file name; a relative one is taken from the folder of the scene file that gives
// it (from the working directory on the command line) and kept absolute.
enum class ParamType { Real, Integer, Choice, Boolean, Path };

class Scene;
struct SceneValues;

// One condition of an applies-when rule: the controlling key holds one of these values.
// `values_now`, when given, replaces `values` by a list read each time the rule is checked
// (integrator.transitions: the schemes whose traits allow located transitions, shipped or
// registered since the table was built).
struct KeyCondition {
  std::string controller;
  std::vector<std::string> values;
  std::function<std::vector<std::string>()> values_now;
  std::vector<std::string> allowed() const { return values_now ? values_now() : values; }
};

// One applies-when rule of a key: it holds when any of its conditions does. A rule that is
// not a list of controller values (model.rows > 1, ...) gives `holds`, the reason it does
// not ("needs model.rows > 1, but model.rows = 1") and validate()'s refusal of the key
// given anyway (without the scene's origin; empty: accepted, only written as a comment).
struct Requirement {
  std::vector<KeyCondition> any_of;
  std::function<bool(const Scene&)> holds;
  std::function<std::string(const Scene&)> why_not;
  std::function<std::string(const Scene&, const std::string& key)> refusal;
};

// One row of the parameter table. Ranges are inclusive unless the *_open flag is set.
struct ParamSpec {
  std::string key;  // "section.key"
  ParamType type;
  std::string default_value;  // as written in a scene file
  double min = 0, max = 0;    // Real/Integer only
  bool min_open = false, max_open = false;
  bool has_min = false, has_max = false;
  // Choice only. A choice read from a registry (integrator.scheme) gives `choices_now`, the
  // values allowed at the moment (shipped and registered since), read whenever a scene is
  // read or validated; `choices` then holds the shipped ones, which the reference docs list.
  std::vector<std::string> choices;
  std::function<std::vector<std::string>()> choices_now;
  std::vector<std::string> allowed_choices() const { return choices_now ? choices_now() : choices; }
  std::string units;             // "" for dimensionless or not applicable
  std::string doc;               // one line
  bool allow_auto = false;       // Real only: the word `keyword` is accepted too
  std::string keyword = "auto";  // `auto` (chosen for you) or `none` (the output is off)
  // When the key applies: every rule holds (in this order: the first that fails says why).
  std::vector<Requirement> applies_when;
  // Given in a scene file where it does not apply, it is not dropped with a warning but
  // left to validate() (model.blocks and model.rows with model.kind = 1dof: a contradiction).
  bool kept_when_inapplicable = false;
  // Added after scenes were first hashed: at its default, left out of Scene::hash() so that
  // the checkpoints and results made before the key existed keep their hash.
  bool added_later = false;
  // The member the key fills: from the normalised text, and back to it.
  std::function<void(SceneValues&, const std::string&)> fill;
  std::function<std::string(const SceneValues&)> text_of;
};

// The cross-key checks of validate() (contradictory combinations), in the order they run,
// each written beside the rows it joins (io/scene_table.cpp); each throws bkq::Error ending
// with `where`.
using CrossKeyRule = void (*)(const Scene&, const std::string& where);
const std::vector<CrossKeyRule>& cross_key_rules();

// The parameter table (the single place a key is declared: io/scene_table.cpp).
const std::vector<ParamSpec>& parameter_table();
// Builds it (parameter_table() keeps the one copy).
std::vector<ParamSpec> make_parameter_table();
const ParamSpec* find_param(const std::string& key);
// For a key that is not in the table: "; did you mean '<nearest key>'?" when one is a few
// edits away, else a pointer to --dump-defaults (the tail of an unknown-key message).
std::string key_suggestion(const std::string& key);

class Scene {
 public:
  // All defaults (the built-in carlson-langer event-driven reference).
  Scene();

  // Reads an INI file; unknown keys, bad values and unreadable files throw bkq::Error.
  static Scene from_file(const std::string& path);
  // Parses INI text; `origin` names the source in error messages.
  static Scene from_text(const std::string& text, const std::string& origin);

  // Sets one key from text ("section.key", "value"); validates type and range.
  void set(const std::string& key, const std::string& value, const std::string& origin = "--set");
  // Applies "section.key=value" (the --set syntax).
  void apply_override(const std::string& assignment);

  // Keys given where they do not apply (the applies-when part of their declaration: a
  // damping ratio for the plain chain, run.events in a continuous run, ...): one given by
  // --set throws bkq::Error (an explicit request that would have no effect); one from a scene
  // file, which may be shared between scenes, is reset to its default and reported in the
  // returned warnings. Call after all sets, before validate().
  std::vector<std::string> drop_inapplicable();
  // Cross-key checks (contradictory combinations, a key given where it does not apply);
  // throws bkq::Error. Call after all sets.
  void validate() const;

  double real(const std::string& key) const;
  std::int64_t integer(const std::string& key) const;
  const std::string& choice(const std::string& key) const;
  bool flag(const std::string& key) const;
  // A Real key that also accepts `auto` (stats.mu_min, stats.mu_max): nullopt for auto.
  std::optional<double> real_or_auto(const std::string& key) const;
  // The same for a Real key that also accepts `none` (output.event_slip): nullopt for none.
  std::optional<double> real_or_none(const std::string& key) const { return real_or_auto(key); }
  // True when the key was given explicitly (file or --set), false when it holds its default.
  bool is_set(const std::string& key) const;
  // The value as text (default or given).
  const std::string& text(const std::string& key) const;

  // The effective scene as an INI file: every key, commented with its doc, units and range;
  // `header` lines (provenance) go first as comments.
  std::string to_ini(const std::vector<std::string>& header = {}) const;
  // A stable hash of the effective values (for checkpoints).
  std::uint64_t hash() const;
  // False for a key this scene does not use (a thesis-only key in a carlson-langer scene,
  // drive.step_* without the steps schedule, ...): validate() rejects such a key when it is
  // given, and to_ini() writes it as a comment so the effective scene reads back cleanly.
  bool applies(const std::string& key) const;
  // Why `key` does not apply: "needs drive.schedule = steps, but drive.schedule = constant";
  // empty when it applies.
  std::string why_not(const std::string& key) const;

  // Scenes are equal when every effective value is equal (origin and which keys were
  // given explicitly do not count): from_text(s.to_ini(), ...) == s.
  bool operator==(const Scene& other) const { return values_ == other.values_; }

  std::string origin;  // the file it came from, or kBuiltInOrigin
  // The origin of a default-constructed scene (the provenance line of its outputs).
  static constexpr const char* kBuiltInOrigin = "built-in default (carlson-langer, event-driven)";
  // True when a --set override gave a key.
  bool overridden() const;
  // Where the scene came from, as an output's provenance states it (summary.json's "scene"):
  // the origin, or for the built-in default changed by --set what it became, "built-in
  // default with --set overrides (bkp, thesis, continuous)" (the model kind unless bk, the
  // parameterisation, rsf for rate-and-state friction, the drive mode; the automaton: "ofc,
  // event-driven").
  std::string provenance() const;
  // Where the scene came from, for the end of an error message: " (scene FILE)",
  // " (built-in default scene)", each "with --set overrides" when --set changed it.
  std::string where() const;

 private:
  // The first applies-when rule of `p` that does not hold in this scene, or nullptr.
  const Requirement* failing_requirement(const ParamSpec& p) const;
  // Makes the relative Path values absolute, taken from `folder`.
  void resolve_paths(const std::filesystem::path& folder);

  std::map<std::string, std::string> values_;
  std::map<std::string, bool> given_;
  std::map<std::string, std::string> set_by_;  // where each given key came from
};

// The allowed values of a key as text: "[0, 1)", "thesis|clst91|cl89", "true|false"
// (a registry's choice: the values allowed now).
std::string allowed_text(const ParamSpec& spec);
// The same as the reference docs list it: a registry's choice lists its shipped values.
std::string documented_allowed_text(const ParamSpec& spec);

// The value of a command-line option that stands for the scene key `key` (fit --mu-min is
// stats.mu_min), checked against that key's one declaration: the normalised text, or
// bkq::Error naming the option, the value and what is allowed.
std::string option_value(const std::string& option, const std::string& key,
                         const std::string& text);

// The commented scene file with all defaults (for --dump-defaults).
std::string dump_defaults();

}  // namespace bkq
