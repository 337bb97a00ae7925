// `bkquake fit CATALOG.csv`: reads an event catalogue, fits the Gutenberg-Richter law
// (binned and unbinned maximum likelihood, least squares, KS window, two power laws,
// large-event excess; see stats/gutenberg_richter.hpp) and counts the event classes.
// Prints a short table; --json also writes the same as JSON. Thin: it only wires the
// catalogue reader, the histogram and the fits together.
#include <boost/program_options.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "app/gr_report.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/catalog_reader.hpp"
#include "io/run_folder.hpp"
#include "stats/event_classes.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {

namespace po = boost::program_options;

int cmd_fit(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake fit CATALOG.csv [options]\n"
      "Fits R(mu) = A exp(-b mu), mu = ln(moment), to an event catalogue");
  // clang-format off
  opts.add_options()
    ("help,h", "show this help")
    ("mu-min", po::value<double>(), "lower end of the fit window (default: chosen by the "
                                    "Kolmogorov-Smirnov scan of Clauset et al. 2009)")
    ("mu-max", po::value<double>(), "upper end of the fit window; truncates the likelihood "
                                    "(default: the largest populated bin, untruncated)")
    ("bin-width", po::value<double>()->default_value(MagnitudeHistogram::kDefaultBinWidth),
                  "magnitude bin width, > 0")
    ("blocks", po::value<int>(), "chain length N for the event classes (default: scene.ini "
                                 "beside the catalogue)")
    ("boundary", po::value<std::string>(), "free | periodic (default: scene.ini, else free)")
    ("json", po::value<std::string>(), "also write the result as JSON to this file");
  // clang-format on
  po::options_description hidden;
  hidden.add_options()("catalog", po::value<std::string>());
  po::options_description all;
  all.add(opts).add(hidden);
  po::positional_options_description pos;
  pos.add("catalog", 1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(all).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    throw Error(std::string("fit: ") + e.what());
  }
  if (vm.count("help")) {
    std::cout << opts << "\n";
    return 0;
  }
  if (!vm.count("catalog")) throw Error("fit: missing CATALOG.csv (see bkquake fit --help)");
  const std::filesystem::path catalog = vm["catalog"].as<std::string>();
  const double w = vm["bin-width"].as<double>();
  if (!(w > 0)) throw Error("fit: --bin-width: expected a value > 0, got " + std::to_string(w));
  std::optional<double> mu_min, mu_max;
  if (vm.count("mu-min")) mu_min = vm["mu-min"].as<double>();
  if (vm.count("mu-max")) mu_max = vm["mu-max"].as<double>();
  if (mu_min && mu_max && !(*mu_max > *mu_min))
    throw Error("fit: --mu-max must be greater than --mu-min");

  // Chain length and boundary for the event classes.
  std::optional<int> blocks;
  std::string boundary = "free";
  std::string class_note;
  const auto scene = catalog.parent_path() / "scene.ini";
  if (std::filesystem::exists(scene)) {
    const SceneModelInfo info = read_scene_model(scene);
    blocks = info.blocks;
    if (info.boundary) boundary = *info.boundary;
  }
  if (vm.count("blocks")) {
    blocks = vm["blocks"].as<int>();
    if (*blocks < 1)
      throw Error("fit: --blocks: expected a positive integer, got " + std::to_string(*blocks));
  }
  if (vm.count("boundary")) boundary = vm["boundary"].as<std::string>();
  const Boundary bnd = parse_boundary(boundary);

  CatalogReader reader(catalog);
  const bool classes_on = blocks.has_value() && reader.has_extent();
  if (!blocks)
    class_note = "event classes skipped: no --blocks and no scene.ini beside the catalogue";
  else if (!reader.has_extent())
    class_note = "event classes skipped: the catalogue lacks blocks/first_block/last_block";

  MagnitudeHistogram hist(w);
  std::vector<double> magnitudes;
  EventClassCounts classes;
  CatalogEvent e;
  while (reader.next(e)) {
    hist.add(e.magnitude);
    magnitudes.push_back(e.magnitude);
    if (classes_on)
      classes.add(classify_event(e.blocks, e.first_block, e.last_block, *blocks, bnd));
  }
  require_events_to_fit(reader.file(), reader.events_read());

  GrFit fit = fit_histogram(hist, mu_min, mu_max);
  add_unbinned(fit, magnitudes);

  std::cout << "catalogue         " << catalog.string() << "\n" << gr_fit_table(fit);
  if (classes_on)
    std::cout << "classes (N = " << *blocks << ", " << boundary << " ends)\n"
              << class_counts_table(classes);
  else
    std::cout << "note: " << class_note << "\n";

  if (vm.count("json")) {
    JsonObject o;
    o.add("catalog", catalog.string()).add("fit", gr_fit_json(fit));
    if (classes_on)
      o.add("blocks", static_cast<std::int64_t>(*blocks))
          .add("boundary", boundary)
          .add("classes", class_counts_json(classes));
    else
      o.add("classes_note", class_note);
    const std::string out = vm["json"].as<std::string>();
    std::ofstream f(out);
    if (!f) throw Error("fit: --json: cannot open " + out + " for writing");
    f << o.str() << "\n";
    if (!f) throw Error("fit: --json: write to " + out + " failed");
  }
  return 0;
}

}  // namespace bkq
