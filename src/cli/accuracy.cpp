// `bkquake accuracy [SCENE]`: the work–precision study of app/accuracy.hpp for a scene
// (the built-in default without one), driven event by event. Writes scene.ini (the
// effective scene with provenance), accuracy.csv and accuracy_orders.csv (the observed
// orders) into --out, and prints the table.
// Thin: the study itself lives in the engine.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <type_traits>

#include "app/accuracy.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"
#include "integrate/stepper.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace {

// "0.01,0.005" -> {0.01, 0.005}; every entry checked against the scene key it stands for.
std::vector<double> parse_list(const std::string& option, const std::string& key,
                               const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    out.push_back(std::strtod(option_value("accuracy: --" + option, key, item).c_str(), nullptr));
  if (out.empty()) throw Error("accuracy: --" + option + ": empty list");
  return out;
}

double real_option(const Args& args, const std::string& option, const std::string& key) {
  std::ostringstream text;
  text << std::setprecision(17) << args.real(option);
  return std::strtod(option_value("accuracy: --" + option, key, text.str()).c_str(), nullptr);
}

std::vector<std::string> parse_schemes(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto& known = stepper_keywords();
    if (std::find(known.begin(), known.end(), item) == known.end()) {
      std::string valid;
      for (const auto& k : known) valid += (valid.empty() ? "" : "|") + k;
      throw Error("accuracy: --schemes: '" + item + "' is not a scheme; expected a list of " +
                  valid);
    }
    out.push_back(item);
  }
  return out;
}

// "step,located" -> {"step", "located"}; each one a value of integrator.transitions.
std::vector<std::string> parse_transitions(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (item != "step" && item != "located")
      throw Error("accuracy: --transitions: '" + item +
                  "' is not a transition mode; expected a list of step|located");
    out.push_back(item);
  }
  if (out.empty()) throw Error("accuracy: --transitions: empty list");
  return out;
}

int cmd_accuracy(const Args& args) {
  Scene scene = scene_from_command_line(args);
  // The study relaxes events one at a time, whatever mode the scene runs in.
  scene.set("drive.mode", "events", "bkquake accuracy");
  drop_inapplicable_keys(scene);
  scene.validate();

  AccuracyOptions opt;
  opt.schemes = parse_schemes(args.text("schemes"));
  opt.dts = parse_list("dt", "integrator.dt", args.text("dt"));
  opt.tolerances = parse_list("tolerances", "integrator.tolerance", args.text("tolerances"));
  opt.transitions = parse_transitions(args.text("transitions"));
  opt.samples = args.integer("samples");
  opt.sample_spacing = args.integer("spacing");
  opt.long_events = args.integer64("long-events");
  opt.reference_tolerance = real_option(args, "reference-tolerance", "integrator.tolerance");
  opt.long_reference_tolerance =
      real_option(args, "long-reference-tolerance", "integrator.tolerance");
  check_accuracy_options(opt);  // before the output folder is touched

  const std::string dir = args.text("out");
  const bool force = args.has("force");
  const OutputFolder out(dir, force, false, "accuracy");
  if (!force && std::filesystem::exists(out.path("accuracy.csv")))
    throw Error("accuracy: " + out.path("accuracy.csv") +
                " already exists; use --force to overwrite it");
  write_file_atomic(out.path("scene.ini"), scene.to_ini(provenance_lines(scene)));

  const bool quiet = args.has("quiet");
  const AccuracyStudy study = run_accuracy(scene, opt, [&](const AccuracyPoint& p) {
    if (quiet) return;
    std::fprintf(stderr, "accuracy: %-11s dt %-7g %s%s\n", p.scheme.c_str(), p.dt,
                 p.tolerance > 0 ? ("tol " + format_real(p.tolerance) + " ").c_str() : "",
                 p.status.c_str());
  });
  write_file_atomic(out.path("accuracy.csv"), accuracy_csv(study));
  write_file_atomic(out.path("accuracy_orders.csv"), accuracy_orders_csv(study));
  std::cout << accuracy_table(study) << "outputs in " << dir
            << "/ (accuracy.csv, accuracy_orders.csv, scene.ini)\n";
  return 0;
}

}  // namespace

Command accuracy_command_row() {
  const AccuracyOptions d;
  const auto joined = [](const auto& items) {
    std::string text;
    for (const auto& x : items) {
      if (!text.empty()) text += ',';
      if constexpr (std::is_same_v<std::decay_t<decltype(x)>, double>)
        text += format_real(x);
      else
        text += x;
    }
    return text;
  };
  return {"accuracy",
          "work-precision study: error against cost for every scheme and dt",
          "[SCENE]",
          -1,
          "Work-precision study of the scene's model, driven event by event: per-event errors\n"
          "against an event-located adaptive reference, the distance of the magnitude\n"
          "distribution from the reference's, and the time per event, for each scheme and dt.\n",
          {scene_set_option(), opt::text("out", "DIR", "output folder", "accuracy"),
           opt::flag("force", "overwrite an accuracy.csv already in the output folder"),
           opt::flag("quiet", "no progress lines"),
           opt::text("schemes", "LIST", "schemes to compare", joined(d.schemes)),
           opt::text("dt", "LIST", "time steps of the fixed-step schemes", joined(d.dts)),
           opt::text("tolerances", "LIST",
                     "tolerances of the adaptive scheme (macro step: the scene's integrator.dt)",
                     joined(d.tolerances)),
           opt::text("transitions", "LIST",
                     "transition modes of rk2, rk4 and verlet (integrator.transitions)",
                     joined(d.transitions)),
           opt::integer("samples", "N",
                        "pre-event states for the per-event errors, in [1, " +
                            std::to_string(kMaxAccuracySamples) + "]",
                        std::to_string(d.samples)),
           opt::integer(
               "spacing", "N",
               "events between sampled states, in [1, " + std::to_string(kMaxAccuracySpacing) + "]",
               std::to_string(d.sample_spacing)),
           opt::integer64("long-events", "N", "events per long run (magnitude statistics and cost)",
                          std::to_string(d.long_events)),
           opt::real("reference-tolerance", "TOL",
                     "tolerance of the per-event reference (adaptive, event-located)",
                     format_real(d.reference_tolerance)),
           opt::real("long-reference-tolerance", "TOL", "tolerance of the reference long runs",
                     format_real(d.long_reference_tolerance))},
          cmd_accuracy};
}

}  // namespace bkq
