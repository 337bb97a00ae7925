// The shared SCENE / --set command line; see scene_args.hpp.
#include "cli/scene_args.hpp"

#include <cstdlib>
#include <iostream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/terminal_text.hpp"

namespace bkq {

namespace po = boost::program_options;

void add_scene_options(po::options_description& opts) {
  opts.add_options()("set", po::value<std::vector<std::string>>()->composing(),
                     "section.key=value: override one scene key (repeatable, applied in order)");
}

po::variables_map parse_command_line(const std::string& command,
                                     const std::vector<std::string>& args,
                                     const po::options_description& opts, const char* positional,
                                     int max_positional) {
  po::options_description hidden;
  if (max_positional == 1)
    hidden.add_options()(positional, po::value<std::string>());
  else
    hidden.add_options()(positional, po::value<std::vector<std::string>>());
  po::options_description all;
  all.add(opts).add(hidden);
  po::positional_options_description pos;
  pos.add(positional, max_positional);
  po::variables_map vm;
  try {
    const int style = po::command_line_style::unix_style & ~po::command_line_style::allow_guessing;
    po::store(po::command_line_parser(args).options(all).positional(pos).style(style).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    throw Error(command + ": " + e.what() + "; try 'bkquake " + command + " --help'");
  }
  return vm;
}

bool printed_help(const po::variables_map& vm, const po::options_description& opts,
                  const char* usage) {
  if (!vm.count("help")) return false;
  std::cout << usage << opts << "\n";
  return true;
}

po::variables_map parse_scene_command_line(const std::string& command,
                                           const std::vector<std::string>& args,
                                           const po::options_description& opts) {
  return parse_command_line(command, args, opts, "scene", -1);
}

Scene scene_from_command_line(const std::string& command, const po::variables_map& vm,
                              const std::vector<std::pair<std::string, std::string>>& presets) {
  std::vector<std::string> scenes;
  if (vm.count("scene")) scenes = vm["scene"].as<std::vector<std::string>>();
  if (scenes.size() > 1)
    throw Error(command + ": expected at most one scene file, got " +
                std::to_string(scenes.size()) + " ('" + scenes[0] + "', '" + scenes[1] + "', ...)");
  Scene scene = scenes.empty() ? Scene() : Scene::from_file(scenes.front());
  for (const auto& [key, value] : presets) scene.set(key, value, command);
  if (vm.count("set"))
    for (const auto& assignment : vm["set"].as<std::vector<std::string>>())
      scene.apply_override(assignment);
  drop_inapplicable_keys(scene);
  return scene;
}

void drop_inapplicable_keys(Scene& scene) {
  for (const auto& w : scene.drop_inapplicable())
    std::cerr << "bkquake: warning: " << printable_text(w) << "\n";
}

std::optional<double> window_option(const po::variables_map& vm, const std::string& command,
                                    const char* name, const char* key) {
  if (!vm.count(name)) return std::nullopt;
  const std::string v = option_value(command + ": --" + name, key, vm[name].as<std::string>());
  if (v == "auto") return std::nullopt;
  return std::strtod(v.c_str(), nullptr);
}

}  // namespace bkq
