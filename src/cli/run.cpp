// `bkquake run`: reads the scene (a file or the built-in default), applies --set
// overrides in order, validates, and hands the effective scene to app/run. Thin on
// purpose: everything it decides is in the scene table or the app layer.
#include <boost/program_options.hpp>
#include <iostream>

#include "app/run.hpp"
#include "app/stability.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace po = boost::program_options;

// What --help prints above the options.
constexpr const char* kUsage =
    "Usage: bkquake run [SCENE] [--set section.key=value]... [--out DIR] [--resume]\n"
    "Without SCENE, runs the built-in default (the Carlson-Langer reference, "
    "event-driven).\n\n";

int cmd_run(const std::vector<std::string>& args) {
  po::options_description opts("bkquake run [SCENE] [options]");
  add_scene_options(opts);
  opts.add_options()("out", po::value<std::string>()->default_value("out"), "output folder")(
      "resume",
      "continue the run in the output folder from its checkpoint, or extend a finished run "
      "to a larger run.events or run.duration")(
      "force", "overwrite a finished run in the output folder")("quiet", "no progress output")(
      "dump-defaults",
      "print a commented scene with every key (at its default, or as SCENE and --set make "
      "it), then exit")("mode", po::value<std::string>(),
                        "FAMILY,INDEX: start at steady sliding plus this mode of bkquake "
                        "stability (sets run.start = equilibrium, run.start_mode, "
                        "run.start_mode_index)")("help,h", "this help");
  const po::variables_map vm = parse_scene_command_line("run", args, opts);

  if (printed_help(vm, opts, kUsage)) return 0;
  RunRequest request;
  request.scene = scene_from_command_line("run", vm);
  if (vm.count("mode")) {
    const std::string text = vm["mode"].as<std::string>();
    const ModeSelect m = parse_mode(text, "run: --mode");
    request.scene.set("run.start", "equilibrium", "--mode");
    request.scene.set("run.start_mode", to_string(m.family), "--mode");
    request.scene.set("run.start_mode_index", std::to_string(m.index), "--mode");
  }
  request.scene.validate();
  if (vm.count("dump-defaults")) {
    // With a SCENE or --set: that scene, every key shown, those that do not apply commented.
    if (!vm.count("scene") && !vm.count("set"))
      std::cout << dump_defaults();
    else
      std::cout << request.scene.to_ini(
          {"bkquake scene: " + request.scene.origin + ", with the --set overrides applied",
           "keys shown as comments do not apply to this scene"});
    return 0;
  }
  request.out_dir = vm["out"].as<std::string>();
  request.resume = vm.count("resume") > 0;
  request.force = vm.count("force") > 0;
  request.quiet = vm.count("quiet") > 0;
  if (request.resume && request.force) throw Error("run: --resume and --force exclude each other");
  // run_scene checks (and locks) the output folder right after the quick checks of the scene.
  return run_scene(request);
}

}  // namespace bkq
