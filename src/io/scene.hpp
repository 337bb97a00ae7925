// Scenes: every parameter of bkquake declared once (name, type, default, allowed range,
// units, one-line doc), read from INI files with Boost.Program_options plus
// `--set section.key=value` overrides, validated against that one table. The same table
// writes `bkquake run --dump-defaults` and the effective `scene.ini` of every run.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bkq {

// Path: a file name; a relative one is taken from the folder of the scene file that gives
// it (from the working directory on the command line) and kept absolute.
enum class ParamType { Real, Integer, Choice, Boolean, Path };

struct KeyDependency;  // an applies-when row of the table (io/scene.cpp)

// One row of the parameter table. Ranges are inclusive unless the *_open flag is set.
struct ParamSpec {
  std::string key;  // "section.key"
  ParamType type;
  std::string default_value;  // as written in a scene file
  double min = 0, max = 0;    // Real/Integer only
  bool min_open = false, max_open = false;
  bool has_min = false, has_max = false;
  std::vector<std::string> choices;  // Choice only
  std::string units;                 // "" for dimensionless or not applicable
  std::string doc;                   // one line
  bool allow_auto = false;           // Real only: the word `keyword` is accepted too
  std::string keyword = "auto";      // `auto` (chosen for you) or `none` (the output is off)
};

// The parameter table (the single place a key is declared).
const std::vector<ParamSpec>& parameter_table();
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

  // Scenes are equal when every effective value is equal (origin and which keys were
  // given explicitly do not count): from_text(s.to_ini(), ...) == s.
  bool operator==(const Scene& other) const { return values_ == other.values_; }

  std::string origin;  // the file it came from, or kBuiltInOrigin
  // The origin of a default-constructed scene (the provenance line of its outputs).
  static constexpr const char* kBuiltInOrigin = "built-in default (carlson-langer, event-driven)";
  // Where the scene came from, for the end of an error message: " (scene FILE)",
  // " (built-in default scene)", each "with --set overrides" when --set changed it.
  std::string where() const;

 private:
  // validate()'s checks of a continuous run: its step count, its speed schedule.
  void check_continuous_run(const std::string& where) const;
  // validate()'s checks of an OFC scene: events only, its catalogue format, its lattice.
  void check_ofc(const std::string& where) const;
  void check_lattice(const std::string& where) const;
  // model.range against one axis: count_key's sites with boundary_key's ends.
  void check_range(const std::string& count_key, const std::string& boundary_key,
                   const std::string& where) const;
  // The first applies-when row of `key` that does not hold (nullptr when it applies), and
  // why in words ("needs drive.schedule = steps, but drive.schedule = constant").
  const KeyDependency* failing_dependency(const std::string& key) const;
  std::string why_not(const std::string& key) const;
  // Makes the relative Path values absolute, taken from `folder`.
  void resolve_paths(const std::filesystem::path& folder);

  std::map<std::string, std::string> values_;
  std::map<std::string, bool> given_;
  std::map<std::string, std::string> set_by_;  // where each given key came from
};

// The allowed values of a key as text: "[0, 1)", "thesis|clst91|cl89", "true|false".
std::string allowed_text(const ParamSpec& spec);

// The value of a command-line option that stands for the scene key `key` (fit --mu-min is
// stats.mu_min), checked against that key's one declaration: the normalised text, or
// bkq::Error naming the option, the value and what is allowed.
std::string option_value(const std::string& option, const std::string& key,
                         const std::string& text);

// The commented scene file with all defaults (for --dump-defaults).
std::string dump_defaults();

}  // namespace bkq
