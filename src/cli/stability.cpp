// `bkquake stability [SCENE]`: steady sliding at drive.speed and the eigenvalues of its
// linearisation, optionally over a sweep of one key (app/stability.hpp). Writes scene.ini
// (the effective scene with provenance), stability.csv, stability_summary.csv and, with
// --modes, modes.csv into --out, and prints the summary.
#include <cstdio>
#include <iostream>

#include "app/rsf_run.hpp"
#include "app/stability.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace {

int cmd_stability(const Args& args) {
  // Steady sliding is a continuously driven state: every scene is analysed as driven
  // continuously, so drive.speed applies (and --set drive.speed is accepted) whatever the
  // scene's drive.mode; event-only keys of a scene file are dropped with a warning.
  Scene scene = scene_from_command_line(args, {{"drive.mode", "continuous"}});
  if (scene_values(scene).model.kind == ModelChoice::Ofc)
    throw Error(
        "stability: model.kind = ofc: the automaton has no steady sliding to "
        "linearise; allowed: model.kind = bk, bkp or 1dof");
  if (scene_values(scene).drive.mode != DriveMode::Continuous)
    throw Error("stability: drive.mode = " + scene.text(key::drive_mode) +
                ": steady sliding at drive.speed is a continuously driven state, and stability "
                "analyses every scene so; remove --set drive.mode=" +
                scene.text(key::drive_mode));
  scene.validate();
  if (scene_values(scene).friction.law.rsf) {
    // Rate-and-state steady sliding: k_crit and the chain's modes (app/rsf_run.hpp).
    if (args.has("sweep") || args.has("dense") || args.has("modes"))
      throw Error(
          "stability: friction.law = rsf: --sweep, --dense and --modes are not written "
          "for rate-and-state yet");
    const OutputFolder out(args.text("out"), args.has("force"), false, "stability");
    const RsfStabilityReport r = rsf_stability(settings_from_scene(scene));
    write_file_atomic(out.path("scene.ini"), scene.to_ini(provenance_lines(scene)));
    write_file_atomic(out.path("stability.csv"), r.modes_csv);
    write_file_atomic(out.path("rsf_stability.csv"), r.summary_csv);
    std::cout << r.text << "outputs in " << out.dir()
              << "/ (stability.csv, rsf_stability.csv, scene.ini)\n";
    return 0;
  }
  StabilityOptions opt;
  if (args.has("sweep")) opt.sweep = parse_sweep(args.text("sweep"), args.has("log"));
  if (args.has("log") && !opt.sweep) throw Error("stability: --log needs --sweep");
  opt.dense = args.has("dense");
  for (const auto& m : args.texts("modes"))
    opt.shapes.push_back(parse_mode(m, "stability: --modes"));

  // The folder rule of every command that writes a folder (io/output.hpp): a new or empty
  // folder, or --force; its lock while the analysis runs.
  const OutputFolder out(args.text("out"), args.has("force"), false, "stability");
  const std::vector<StabilityPoint> points = run_stability(scene, opt);
  write_file_atomic(out.path("scene.ini"), scene.to_ini(provenance_lines(scene)));
  write_file_atomic(out.path("stability.csv"), stability_csv(points));
  write_file_atomic(out.path("stability_summary.csv"), stability_summary_csv(points));
  if (!opt.shapes.empty()) write_file_atomic(out.path("modes.csv"), modes_csv(points));

  const std::string key = opt.sweep ? opt.sweep->key : "drive.speed";
  std::printf("%-14s %6s %6s %12s %12s  %s\n", key.c_str(), "modes", "unst.", "max Re", "its freq.",
              "mode");
  for (const StabilityPoint& pt : points) {
    int unstable = 0;
    const Eigenmode* top = nullptr;
    for (const Eigenmode& m : pt.modes) {
      unstable += m.unstable() ? 1 : 0;
      if (!top || m.growth() > top->growth()) top = &m;
    }
    std::printf("%-14s %6zu %6d %12.6g %12.6g  %s\n", format_real(pt.value).c_str(),
                pt.modes.size(), unstable, top->growth(), top->frequency(),
                mode_name(*top).c_str());
  }
  std::cout << "outputs in " << out.dir() << "/ (stability.csv, stability_summary.csv"
            << (opt.shapes.empty() ? "" : ", modes.csv") << ", scene.ini)\n";
  return 0;
}

}  // namespace

Command stability_command_row() {
  return {"stability",
          "steady sliding and the complex eigenvalues of its linearisation",
          "[SCENE]",
          -1,
          "Steady sliding at the disc speed drive.speed and the complex eigenvalues of its\n"
          "linearisation: each mode's growth rate Re lambda, frequency Im lambda / 2 pi and\n"
          "whether it is unstable (docs/tutorials/stability.md, docs/validation/stability.md).\n"
          "Every scene is analysed as continuously driven (drive.mode = continuous), so\n"
          "drive.speed applies to an event-driven scene too.\n",
          {scene_set_option(),
           opt::text("sweep", "KEY=FROM:TO:COUNT",
                     "analyse at COUNT values of one real or integer key"),
           opt::flag("log", "space the sweep's values geometrically"),
           opt::flag("dense",
                     "use the dense state matrix (N <= 1000) instead of the exact modal "
                     "reduction"),
           opt::repeated("modes", "FAMILY,INDEX", "write this mode's shape to modes.csv"),
           opt::text("out", "DIR", "output folder (new or empty)", "stability"),
           opt::flag("force", "write over the files of an existing output folder")},
          cmd_stability};
}

}  // namespace bkq
