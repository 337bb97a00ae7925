// Implementation of `bkquake fit` (see fit.hpp): wires the catalogue reader, the histogram,
// the fits and the report together.
#include "app/fit.hpp"

#include <cstdint>
#include <fstream>
#include <ostream>
#include <vector>

#include "app/gr_report.hpp"
#include "core/error.hpp"
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
  // its checkpoint or beyond): they are fitted, and the report says so. A summary that does
  // not read leaves the catalogue to speak for itself.
  bool interrupted = false;
  try {
    interrupted = run_status(catalog.parent_path()) == RunStatus::Interrupted;
  } catch (const Error&) {
  }

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
  require_events_to_fit(reader.file(), reader.events_read());

  GrFit fit = fit_histogram(hist, request.mu_min, request.mu_max);
  add_unbinned(fit, magnitudes);

  out << "catalogue         " << catalog.string() << "\n";
  if (interrupted)
    out << "note: an interrupted run (summary.json: \"status\": \"interrupted\"): these are its "
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
    if (interrupted) o.set("run_status", status_text(RunStatus::Interrupted));
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
