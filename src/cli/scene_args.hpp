// The commands' shared command-line parsing, and the part that the commands simulating a
// scene (run, accuracy) share: one
// optional SCENE file (the built-in default without it) and any number of
// --set section.key=value overrides, applied in order after the file.
#pragma once

#include <boost/program_options.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/scene.hpp"

namespace bkq {

// Adds --set to a command's options.
void add_scene_options(boost::program_options::options_description& opts);

// Parses a command's `args` with `opts` plus positional arguments stored under
// `positional` (a string when max_positional is 1, else a list; -1: any number), without
// abbreviations (`--for` silently meaning --force would be a surprise). Errors read
// "<command>: ...; try 'bkquake <command> --help'".
boost::program_options::variables_map parse_command_line(
    const std::string& command, const std::vector<std::string>& args,
    const boost::program_options::options_description& opts, const char* positional,
    int max_positional);

// True, after printing `usage` and the options, when the command line asked for --help.
bool printed_help(const boost::program_options::variables_map& vm,
                  const boost::program_options::options_description& opts, const char* usage = "");

// A fit window end given as --<name> (--mu-min, --mu-max), checked against the scene key it
// stands for (`key`: one declaration of the range); nullopt when absent or "auto".
std::optional<double> window_option(const boost::program_options::variables_map& vm,
                                    const std::string& command, const char* name, const char* key);

// Parses `args` with `opts` plus the positional SCENE, without abbreviations (`--for`
// silently meaning --force would be a surprise). Errors read "<command>: ...".
boost::program_options::variables_map parse_scene_command_line(
    const std::string& command, const std::vector<std::string>& args,
    const boost::program_options::options_description& opts);

// The scene file (or the built-in default) with the --set overrides applied and the keys
// that do not apply dropped (drop_inapplicable_keys); the caller validates it (after
// settings of its own, if any). `presets` (key, value) are set after the file and before
// the overrides, as the command's own (stability analyses every scene continuously driven).
Scene scene_from_command_line(const std::string& command,
                              const boost::program_options::variables_map& vm,
                              const std::vector<std::pair<std::string, std::string>>& presets = {});

// Scene::drop_inapplicable, its warnings printed to stderr; call again after a command
// changes the scene itself (accuracy sets drive.mode = events).
void drop_inapplicable_keys(Scene& scene);

}  // namespace bkq
