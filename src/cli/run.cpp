// `bkquake run`: reads the scene (a file or the built-in default), applies --set
// overrides in order, validates, and hands the effective scene to the engine. Thin on
// purpose: everything it decides is in the scene table or the engine.
#include <boost/program_options.hpp>
#include <iostream>

#include "cli/commands.hpp"
#include "engine/run.hpp"
#include "io/error.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace po = boost::program_options;

int cmd_run(const std::vector<std::string>& args) {
  po::options_description opts("bkquake run [SCENE] [options]");
  opts.add_options()("set", po::value<std::vector<std::string>>()->composing(),
                     "section.key=value: override one scene key (repeatable, applied in order)")(
      "out", po::value<std::string>()->default_value("out"), "output folder")(
      "resume", "continue the run in the output folder from its checkpoint")(
      "force", "overwrite a finished run in the output folder")("quiet", "no progress output")(
      "dump-defaults", "print a commented scene with every key at its default, then exit")(
      "help,h", "this help");
  po::options_description hidden;
  hidden.add_options()("scene", po::value<std::vector<std::string>>(), "scene file");
  po::options_description all;
  all.add(opts).add(hidden);
  po::positional_options_description pos;
  pos.add("scene", -1);

  po::variables_map vm;
  try {
    // No abbreviations: `--for` silently meaning --force would be a surprise.
    const int style = po::command_line_style::unix_style & ~po::command_line_style::allow_guessing;
    po::store(po::command_line_parser(args).options(all).positional(pos).style(style).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    throw Error(std::string("run: ") + e.what() + "; try 'bkquake run --help'");
  }

  if (vm.count("help")) {
    std::cout << "Usage: bkquake run [SCENE] [--set section.key=value]... [--out DIR] [--resume]\n"
                 "Without SCENE, runs the built-in default (the Carlson-Langer reference, "
                 "event-driven).\n\n"
              << opts << "\n";
    return 0;
  }
  if (vm.count("dump-defaults")) {
    std::cout << dump_defaults();
    return 0;
  }

  std::vector<std::string> scenes;
  if (vm.count("scene")) scenes = vm["scene"].as<std::vector<std::string>>();
  if (scenes.size() > 1)
    throw Error("run: expected at most one scene file, got " + std::to_string(scenes.size()) +
                " ('" + scenes[0] + "', '" + scenes[1] + "', ...)");

  RunRequest request;
  request.scene = scenes.empty() ? Scene() : Scene::from_file(scenes.front());
  if (vm.count("set"))
    for (const auto& assignment : vm["set"].as<std::vector<std::string>>())
      request.scene.apply_override(assignment);
  request.scene.validate();
  request.out_dir = vm["out"].as<std::string>();
  request.resume = vm.count("resume") > 0;
  request.force = vm.count("force") > 0;
  request.quiet = vm.count("quiet") > 0;
  if (request.resume && request.force) throw Error("run: --resume and --force exclude each other");
  // Check the output folder now, so a bad --out fails in a second rather than after the
  // engine has set up; the engine opens the same folder again for writing.
  OutputFolder(request.out_dir, request.force, request.resume);
  return run_scene(request);
}

}  // namespace bkq
