// `bkquake merge RUN_DIR... --out DIR`: merges the magnitude histograms of several runs of
// the same scene exactly (counts add; loading adds) and writes DIR/histogram.csv and
// DIR/summary.json with the Gutenberg-Richter fit of the merged histogram. Runs with
// different bin widths or chain lengths are refused.
#include <boost/program_options.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "app/gr_report.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/histogram_csv.hpp"
#include "io/run_folder.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace {
double required(const fs::path& summary, const std::string& key) {
  const auto v = read_json_number(summary, key);
  if (!v) throw Error(summary.string() + ": missing \"" + key + "\"");
  return *v;
}
}  // namespace

int cmd_merge(const std::vector<std::string>& args) {
  po::options_description opts(
      "bkquake merge RUN_DIR... --out DIR\n"
      "Merges the histograms of runs of the same scene and fits the result");
  opts.add_options()("help,h", "show this help")("out", po::value<std::string>(),
                                                 "output folder (created if missing)");
  po::options_description hidden;
  hidden.add_options()("runs", po::value<std::vector<std::string>>());
  po::options_description all;
  all.add(opts).add(hidden);
  po::positional_options_description pos;
  pos.add("runs", -1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(all).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    throw Error(std::string("merge: ") + e.what());
  }
  if (vm.count("help")) {
    std::cout << opts << "\n";
    return 0;
  }
  if (!vm.count("runs")) throw Error("merge: no RUN_DIR given (see bkquake merge --help)");
  if (!vm.count("out")) throw Error("merge: --out DIR is required");
  const auto runs = vm["runs"].as<std::vector<std::string>>();
  const fs::path out = vm["out"].as<std::string>();

  std::optional<MagnitudeHistogram> merged;
  for (const auto& run : runs) {
    const fs::path dir = run;
    const fs::path summary = dir / "summary.json";
    const double w = required(summary, "bin_width");
    const double blocks = required(summary, "blocks");
    const double load = required(summary, "total_load");
    if (!(blocks >= 1) || blocks != static_cast<double>(static_cast<int>(blocks)))
      throw Error(summary.string() + ": \"blocks\": expected a positive integer");
    MagnitudeHistogram h =
        read_histogram_csv(dir / "histogram.csv", load, static_cast<int>(blocks), w);
    if (const auto ev = read_json_number(summary, "events");
        ev && *ev != static_cast<double>(h.events()))
      throw Error(dir.string() + ": histogram.csv holds " + std::to_string(h.events()) +
                  " events, summary.json says " + std::to_string(static_cast<std::int64_t>(*ev)));
    if (!merged) {
      merged = std::move(h);
      continue;
    }
    if (merged->bin_width() != h.bin_width())
      throw Error("merge: " + run + " has bin width " + std::to_string(h.bin_width()) +
                  ", the first run " + std::to_string(merged->bin_width()));
    if (merged->blocks() != h.blocks())
      throw Error("merge: " + run + " has N = " + std::to_string(h.blocks()) +
                  ", the first run N = " + std::to_string(merged->blocks()));
    merged->merge(h);
  }

  fs::create_directories(out);
  write_histogram_csv(*merged, out / "histogram.csv");
  JsonObject s;
  s.add("events", merged->events())
      .add("blocks", static_cast<std::int64_t>(merged->blocks()))
      .add("total_load", merged->total_load())
      .add("bin_width", merged->bin_width())
      .add("merged_from", runs);
  if (merged->events() >= 2) {
    const GrFit fit = fit_histogram(*merged, std::nullopt, std::nullopt);
    s.add("b_mle", fit.b_mle)
        .add("b_mle_err", fit.b_mle_err)
        .add("mu_min", fit.mu_min)
        .add("mu_max", fit.mu_max)
        .add("fit", gr_fit_json(fit));
    std::cout << "merged " << runs.size() << " runs into " << out.string() << "\n"
              << gr_fit_table(fit);
  } else {
    std::cout << "merged " << runs.size() << " runs into " << out.string()
              << "; fewer than 2 events, no fit\n";
  }
  std::ofstream f(out / "summary.json");
  if (!f) throw Error((out / "summary.json").string() + ": cannot open for writing");
  f << s.str() << "\n";
  return 0;
}

}  // namespace bkq
