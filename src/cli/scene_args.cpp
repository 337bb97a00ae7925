// The shared SCENE / --set command line; see scene_args.hpp.
#include "cli/scene_args.hpp"

#include <cstdlib>
#include <iostream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/terminal_text.hpp"

namespace bkq {

Option scene_set_option() {
  return opt::repeated("set", "section.key=value",
                       "override one scene key (applied in order, after the scene file)");
}

Scene scene_from_command_line(const Args& args,
                              const std::vector<std::pair<std::string, std::string>>& presets) {
  const std::string& command = args.command();
  const std::vector<std::string> scenes = args.operands();
  if (scenes.size() > 1)
    throw Error(command + ": expected at most one scene file, got " +
                std::to_string(scenes.size()) + " ('" + scenes[0] + "', '" + scenes[1] + "', ...)");
  Scene scene = scenes.empty() ? Scene() : Scene::from_file(scenes.front());
  for (const auto& [key, value] : presets) scene.set(key, value, command);
  for (const auto& assignment : args.texts("set")) scene.apply_override(assignment);
  drop_inapplicable_keys(scene);
  return scene;
}

void drop_inapplicable_keys(Scene& scene) {
  for (const auto& w : scene.drop_inapplicable())
    std::cerr << "bkquake: warning: " << printable_text(w) << "\n";
}

std::optional<double> window_option(const Args& args, const char* name, const char* key) {
  if (!args.has(name)) return std::nullopt;
  const std::string v = option_value(args.command() + ": --" + name, key, args.text(name));
  if (v == "auto") return std::nullopt;
  return std::strtod(v.c_str(), nullptr);
}

}  // namespace bkq
