// Implementation of `bkquake fit` (see fit.hpp): wires the catalogue reader, the histogram,
// the fits and the report together.
#include "app/fit.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <ostream>
#include <vector>

#include "app/gr_report.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/catalog_reader.hpp"
#include "io/run_folder.hpp"
#include "stats/event_classes.hpp"
#include "stats/gutenberg_richter.hpp"

namespace bkq {

void fit_catalog(const FitRequest& request, std::ostream& out) {
  const std::filesystem::path& catalog = request.catalog;

  // Chain length and boundary for the event classes.
  std::optional<int> blocks;
  std::string boundary = "free";
  const auto scene = catalog.parent_path() / "scene.ini";
  if (std::filesystem::exists(scene)) {
    const SceneModelInfo info = read_scene_model(scene);
    blocks = info.blocks;
    if (info.boundary) boundary = *info.boundary;
  }
  if (request.blocks) blocks = request.blocks;
  if (request.boundary) boundary = *request.boundary;
  const Boundary bnd = parse_boundary(boundary);

  // The catalogue of an interrupted run holds the events recorded so far (whole rows, up to
  // its checkpoint or beyond): they are fitted, and the report says so. A run's own catalogue
  // is checked against its summary's event count. A summary that does not read is named in a
  // warning and the catalogue speaks for itself.
  const std::filesystem::path dir = catalog.parent_path();
  const std::string name = catalog.filename().string();
  const bool own = name == "catalog.csv" || name == "catalog.h5";
  RunStatus status = RunStatus::None;
  std::optional<double> summary_events;
  if (own && std::filesystem::exists(dir / "summary.json")) {
    try {
      status = run_status(dir);
      summary_events = read_json_number(dir / "summary.json", "events");
    } catch (const Error& e) {
      std::fprintf(stderr, "bkquake: warning: %s; the catalogue is fitted without it\n",
                   escape_unprintable(e.what()).c_str());
      status = RunStatus::None;
      summary_events.reset();
    }
  }
  const bool interrupted = status == RunStatus::Interrupted;
  // A run killed (SIGKILL, a crash) before its first summary leaves only its checkpoints.
  const bool killed = own && status == RunStatus::None &&
                      (std::filesystem::exists(dir / "checkpoint.bin") ||
                       std::filesystem::exists(dir / "checkpoint.prev.bin"));

  // The folder rule (io/run_folder.hpp): --json never over the catalogue or a run's files.
  std::unique_ptr<DerivedOutput> json_out;
  if (request.json)
    json_out = std::make_unique<DerivedOutput>(
        *request.json, std::vector<std::filesystem::path>{catalog, dir / "summary.json", scene},
        "fit --json");

  CatalogReader reader(catalog);
  const bool classes_on = blocks.has_value() && reader.has_extent();
  std::string class_note;
  if (!blocks)
    class_note = "event classes skipped: no --blocks and no scene.ini beside the catalogue";
  else if (!reader.has_extent())
    class_note = "event classes skipped: the catalogue lacks blocks/first_block/last_block";

  MagnitudeHistogram hist(request.bin_width);
  std::vector<double> magnitudes;
  EventClassCounts classes;
  CatalogEvent e;
  while (reader.next(e)) {
    hist.add(e.magnitude);
    magnitudes.push_back(e.magnitude);
    if (classes_on)
      classes.add(classify_event(e.blocks, e.first_block, e.last_block, *blocks, bnd));
  }
  // (Only a finished run's count is final: a resumed run cuts its catalogue back to the
  // checkpoint while the summary of its last stop still counts the events past it.)
  if (summary_events && status == RunStatus::Finished) {
    const auto expected = static_cast<std::int64_t>(*summary_events);
    const std::int64_t found = reader.events_read();
    if (found != expected)
      throw Error(reader.file() + ": holds " + std::to_string(found) + " rows, its run's " +
                  (dir / "summary.json").string() + " counts " + std::to_string(expected) +
                  " events: the catalogue is truncated or was changed");
  }
  require_events_to_fit(reader.file(), reader.events_read());

  GrFit fit = fit_histogram(hist, request.mu_min, request.mu_max);
  add_unbinned(fit, magnitudes);

  out << "catalogue         " << catalog.string() << "\n";
  if (interrupted)
    out << "note: an interrupted run (summary.json: \"status\": \"interrupted\"): these are its "
        << reader.events_read() << " events so far; --resume finishes it\n";
  if (killed)
    out << "note: an interrupted run (checkpoints beside it, no summary.json: killed?): these "
           "are its "
        << reader.events_read() << " events so far; --resume finishes it\n";
  out << gr_fit_table(fit);
  if (classes_on)
    out << "classes (N = " << *blocks << ", " << boundary << " ends)\n"
        << class_counts_table(classes);
  else
    out << "note: " << class_note << "\n";

  if (request.json) {
    Json o = Json::object();
    o.set("catalog", catalog.string()).set("fit", gr_fit_json(fit));
    if (interrupted || killed) o.set("run_status", status_text(RunStatus::Interrupted));
    if (classes_on)
      o.set("blocks", static_cast<std::int64_t>(*blocks))
          .set("boundary", boundary)
          .set("classes", class_counts_json(classes));
    else
      o.set("classes_note", class_note);
    const std::string path = request.json->string();
    std::ofstream f(path);
    if (!f) throw Error("fit: --json: cannot open " + path + " for writing");
    f << o.str() << "\n";
    if (!f) throw Error("fit: --json: write to " + path + " failed");
  }
}

}  // namespace bkq
