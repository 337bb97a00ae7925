// The part of the command line that the commands simulating a scene (run, accuracy,
// special-speed, stability, sweep) share: one optional SCENE file (the built-in default
// without it) and any number of --set section.key=value overrides, applied in order after
// the file; and the fit window options checked as the scene keys they stand for.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "io/scene.hpp"

namespace bkq {

// The --set row of a command's options.
Option scene_set_option();

// A fit window end given as --<name> (--mu-min, --mu-max), checked against the scene key it
// stands for (`key`: one declaration of the range); nullopt when absent or "auto".
std::optional<double> window_option(const Args& args, const char* name, const char* key);

// The scene file (the operand, or the built-in default) with the --set overrides applied
// and the keys that do not apply dropped (drop_inapplicable_keys); the caller validates it
// (after settings of its own, if any). `presets` (key, value) are set after the file and
// before the overrides, as the command's own (stability analyses every scene continuously
// driven).
Scene scene_from_command_line(const Args& args,
                              const std::vector<std::pair<std::string, std::string>>& presets = {});

// Scene::drop_inapplicable, its warnings printed to stderr; call again after a command
// changes the scene itself (accuracy sets drive.mode = events).
void drop_inapplicable_keys(Scene& scene);

}  // namespace bkq
