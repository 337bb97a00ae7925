// `bkquake accuracy [SCENE]`: the work–precision study of app/accuracy.hpp for a scene
// (the built-in default without one), driven event by event. Writes scene.ini (the
// effective scene with provenance), accuracy.csv and accuracy_orders.csv (the observed
// orders) into --out, and prints the table.
// Thin: the study itself lives in the engine.
#include <algorithm>
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app/accuracy.hpp"
#include "cli/commands.hpp"
#include "cli/scene_args.hpp"
#include "core/error.hpp"
#include "integrate/stepper.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace po = boost::program_options;

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

double real_option(const po::variables_map& vm, const std::string& option, const std::string& key) {
  std::ostringstream text;
  text << std::setprecision(17) << vm[option].as<double>();
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

}  // namespace

// What --help prints above the options.
constexpr const char* kUsage =
    "Usage: bkquake accuracy [SCENE] [--set section.key=value]... [--out DIR]\n"
    "Work-precision study of the scene's model, driven event by event: per-event errors\n"
    "against an event-located adaptive reference, the distance of the magnitude\n"
    "distribution from the reference's, and the time per event, for each scheme and dt.\n\n";

int cmd_accuracy(const std::vector<std::string>& args) {
  const AccuracyOptions defaults;
  po::options_description opts("bkquake accuracy [SCENE] [options]");
  // clang-format off
  add_scene_options(opts);
  opts.add_options()
    ("out", po::value<std::string>()->default_value("accuracy"), "output folder")
    ("force", "overwrite an accuracy.csv already in the output folder")
    ("quiet", "no progress lines")
    ("schemes", po::value<std::string>()->default_value("rk2,rk4,verlet,theta,adaptive"), "schemes to compare")
    ("dt", po::value<std::string>()->default_value("0.05,0.02,0.01,0.005,0.002,0.001"),
           "time steps of the fixed-step schemes")
    ("tolerances", po::value<std::string>()->default_value("1e-3,1e-5,1e-7,1e-9"),
                   "tolerances of the adaptive scheme (macro step: the scene's integrator.dt)")
    ("transitions", po::value<std::string>()->default_value("step,located"),
                    "transition modes of rk2, rk4 and verlet (integrator.transitions)")
    ("samples", po::value<int>()->default_value(defaults.samples), ("pre-event states for the per-event errors, in [1, " + std::to_string(kMaxAccuracySamples) + "]").c_str())
    ("spacing", po::value<int>()->default_value(defaults.sample_spacing), ("events between sampled states, in [1, " + std::to_string(kMaxAccuracySpacing) + "]").c_str())
    ("long-events", po::value<std::int64_t>()->default_value(defaults.long_events),
                    "events per long run (magnitude statistics and cost)")
    ("reference-tolerance", po::value<double>()->default_value(defaults.reference_tolerance),
                            "tolerance of the per-event reference (adaptive, event-located)")
    ("long-reference-tolerance", po::value<double>()->default_value(defaults.long_reference_tolerance),
                                 "tolerance of the reference long runs")
    ("help,h", "this help");
  // clang-format on
  const po::variables_map vm = parse_scene_command_line("accuracy", args, opts);
  if (printed_help(vm, opts, kUsage)) return 0;
  Scene scene = scene_from_command_line("accuracy", vm);
  // The study relaxes events one at a time, whatever mode the scene runs in.
  scene.set("drive.mode", "events", "bkquake accuracy");
  drop_inapplicable_keys(scene);
  scene.validate();

  AccuracyOptions opt;
  opt.schemes = parse_schemes(vm["schemes"].as<std::string>());
  opt.dts = parse_list("dt", "integrator.dt", vm["dt"].as<std::string>());
  opt.tolerances =
      parse_list("tolerances", "integrator.tolerance", vm["tolerances"].as<std::string>());
  opt.transitions = parse_transitions(vm["transitions"].as<std::string>());
  opt.samples = vm["samples"].as<int>();
  opt.sample_spacing = vm["spacing"].as<int>();
  opt.long_events = vm["long-events"].as<std::int64_t>();
  opt.reference_tolerance = real_option(vm, "reference-tolerance", "integrator.tolerance");
  opt.long_reference_tolerance =
      real_option(vm, "long-reference-tolerance", "integrator.tolerance");
  check_accuracy_options(opt);  // before the output folder is touched

  const std::string dir = vm["out"].as<std::string>();
  const bool force = vm.count("force") > 0;
  const OutputFolder out(dir, force, false, "accuracy");
  if (!force && std::filesystem::exists(out.path("accuracy.csv")))
    throw Error("accuracy: " + out.path("accuracy.csv") +
                " already exists; use --force to overwrite it");
  write_file_atomic(out.path("scene.ini"), scene.to_ini(provenance_lines(scene)));

  const bool quiet = vm.count("quiet") > 0;
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

}  // namespace bkq
