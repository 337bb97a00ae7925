// `bkquake run`: reads the scene (a file or the built-in default), applies --set
// overrides in order, validates, and hands the effective scene to app/run. Thin on
// purpose: everything it decides is in the scene table or the app layer.
#include <iostream>

#include "app/run.hpp"
#include "app/stability.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace {

int cmd_run(const Args& args) {
  RunRequest request;
  request.scene = scene_from_command_line(args);
  if (args.has("mode")) {
    const std::string text = args.text("mode");
    const ModeSelect m = parse_mode(text, "run: --mode");
    request.scene.set("run.start", "equilibrium", "--mode");
    request.scene.set("run.start_mode", to_string(m.family), "--mode");
    request.scene.set("run.start_mode_index", std::to_string(m.index), "--mode");
  }
  request.scene.validate();
  if (args.has("dump-defaults")) {
    // With a SCENE or --set: that scene, every key shown, those that do not apply commented.
    if (args.operands().empty() && !args.has("set"))
      std::cout << dump_defaults();
    else
      std::cout << request.scene.to_ini(
          {"bkquake scene: " + request.scene.origin + ", with the --set overrides applied",
           "keys shown as comments do not apply to this scene"});
    return 0;
  }
  request.out_dir = args.text("out");
  request.resume = args.has("resume");
  request.force = args.has("force");
  request.quiet = args.has("quiet");
  if (request.resume && request.force) throw Error("run: --resume and --force exclude each other");
  // run_scene checks (and locks) the output folder right after the quick checks of the scene.
  return run_scene(request);
}

}  // namespace

Command run_command_row() {
  return {"run",
          "simulate a scene and write its catalogue, histogram and summary",
          "[SCENE]",
          -1,
          "Without SCENE, runs the built-in default (the Carlson-Langer reference, "
          "event-driven).\n",
          {scene_set_option(), opt::text("out", "DIR", "output folder", "out"),
           opt::flag("resume",
                     "continue the run in the output folder from its checkpoint, or extend a "
                     "finished run to a larger run.events or run.duration"),
           opt::flag("force", "overwrite a finished run in the output folder (not with --resume)"),
           opt::flag("quiet", "no progress output"),
           opt::flag("dump-defaults",
                     "print a commented scene with every key (at its default, or as SCENE and "
                     "--set make it), then exit"),
           opt::text("mode", "FAMILY,INDEX",
                     "start at steady sliding plus this mode of bkquake stability (sets "
                     "run.start = equilibrium, run.start_mode, run.start_mode_index)")},
          cmd_run};
}

}  // namespace bkq
