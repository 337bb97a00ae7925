// Implementation of `bkquake fit` (see fit.hpp): finds what the input holds, reads it
// through io's readers (catalogue, histogram.csv, sweep.csv), fits and reports.
#include "app/fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <ostream>
#include <system_error>
#include <vector>

#include "app/gr_report.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/b_scan_csv.hpp"
#include "io/catalog_reader.hpp"
#include "io/folder_lock.hpp"
#include "io/histogram_csv.hpp"
#include "io/ini.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/sweep_file.hpp"
#include "stats/event_classes.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/power_law.hpp"

namespace bkq {

namespace fs = std::filesystem;

namespace {

// What the input of `bkquake fit` is.
enum class Input { Catalog, Histogram, Sweep };

struct Resolved {
  Input kind;
  fs::path file;    // the catalogue or histogram.csv (the sweep folder for Sweep)
  fs::path folder;  // where b_scan.csv goes by default
};

// Only the first few bytes of a regular file are looked at: a device or a pipe (/dev/zero)
// is left to the catalogue reader, which refuses it, instead of being read without end.
bool starts_with_histogram_header(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return false;
  std::ifstream in(file, std::ios::binary);
  const std::string& name = histogram_schema().front().name;
  std::string first(name.size(), '\0');
  if (!in || !in.read(first.data(), static_cast<std::streamsize>(first.size()))) return false;
  return first == name;
}

Resolved resolve(const fs::path& input) {
  std::error_code ec;  // a name that cannot be a file (too long, say) does not exist
  if (fs::is_directory(input, ec)) {
    if (fs::exists(input / "sweep.ini") && fs::exists(input / "sweep.csv"))
      return {Input::Sweep, input, input};
    for (const char* name : {"catalog.csv", "catalog.h5"})
      if (fs::exists(input / name)) return {Input::Catalog, input / name, input};
    if (fs::exists(input / "histogram.csv"))
      return {Input::Histogram, input / "histogram.csv", input};
    throw Error("fit: folder '" + input.string() +
                "' holds no catalog.csv, catalog.h5, histogram.csv or sweep.csv (sweep.ini)");
  }
  if (!fs::exists(input, ec)) throw Error("fit: '" + input.string() + "' does not exist");
  const fs::path folder = input.has_parent_path() ? input.parent_path() : fs::path(".");
  if (starts_with_histogram_header(input)) return {Input::Histogram, input, folder};
  return {Input::Catalog, input, folder};
}

// A histogram.csv with its bin width checked against a width the user gave.
MagnitudeHistogram read_histogram(const fs::path& file, const FitRequest& r) {
  MagnitudeHistogram h = read_histogram_csv(file, 0, 0, 0);
  if (r.bin_width_given && std::fabs(h.bin_width() - r.bin_width) > 1e-9 * r.bin_width)
    throw Error("fit: --bin-width " + format_real(r.bin_width) + ": " + file.string() +
                " has bins of width " + format_real(h.bin_width()) +
                "; a histogram's bins are fixed (allowed: its own width)");
  return h;
}

// The folder b_scan.csv goes into, checked and locked (a stale lock of a killed command taken
// over, the lock shared with --json's in the same folder; a run's folder it lies in locked
// too), the temporaries of a write cut short removed. b_scan.csv is a derived output: never over
// the input or a run's own file.
std::vector<std::shared_ptr<FolderLock>> lock_scan_folder(const fs::path& dir,
                                                          const fs::path& input) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error("fit: --out " + dir.string() + ": not a folder; b_scan.csv goes into a folder");
  const auto parent_lock = lock_derived_folder_parent(dir, "fit --scan");
  fs::create_directories(dir, ec);
  if (ec) throw Error("fit: --out " + dir.string() + ": cannot create the folder: " + ec.message());
  const DerivedOutput rule(dir / "b_scan.csv", {input}, "fit --scan");
  auto lock = share_folder_lock(dir, "fit --scan", StaleLock::TakeOver);
  remove_temporaries_of((dir / "b_scan.csv").string());
  return {parent_lock, lock};
}

// An explicit window that holds no whole bin once snapped to the bin edges (the fit takes
// mu_min up and mu_max down to them, stats/gutenberg_richter.cpp) is refused naming both
// options and a window that would do.
void require_window_holds_a_bin(double w, const FitRequest& r) {
  if (!r.mu_min || !r.mu_max) return;
  constexpr double eps = 1e-9;  // the fit's snapping tolerance
  const double lo = std::ceil(*r.mu_min / w - eps), hi = std::floor(*r.mu_max / w + eps);
  if (hi > lo) return;
  char edges[96];
  std::snprintf(edges, sizeof edges, "--mu-min %.10g --mu-max %.10g", lo * w, (lo + 1) * w);
  throw Error("fit: --mu-min " + format_real(*r.mu_min) + " --mu-max " + format_real(*r.mu_max) +
              ": no whole bin of width " + format_real(w) +
              " lies between them (the window runs from bin edge to bin edge, multiples of " +
              format_real(w) + "); allowed: a window of at least one bin, e.g. " + edges);
}

// --blocks against what it may be: at most the largest lattice a run may have, and the
// shape of the scene.ini beside the catalogue when there is one (seismicity refuses the
// same contradiction).
void check_blocks_option(const FitRequest& r, const fs::path& scene,
                         const std::optional<SceneModelInfo>& info) {
  const int nx = *r.blocks, ny = r.rows.value_or(1);
  const std::string given = std::to_string(nx) + (r.rows ? "x" + std::to_string(ny) : "");
  const std::int64_t sites = static_cast<std::int64_t>(nx) * ny;
  if (sites > 100'000'000)
    throw Error("fit: --blocks " + given + ": " + std::to_string(sites) +
                " sites; allowed at most 1e8, the largest lattice a run may have");
  if (!info || !info->blocks) return;
  const int sx = *info->blocks, sy = info->rows.value_or(1);
  if (nx != sx || ny != sy)
    throw Error("fit: --blocks " + given + " contradicts " + scene.string() +
                " (model.blocks = " + std::to_string(sx) + ", model.rows = " + std::to_string(sy) +
                "); allowed: " + std::to_string(sx) + (sy > 1 ? "x" + std::to_string(sy) : "") +
                ", or no --blocks");
}

// A row whose blocks (or rows) lie beyond the chain or lattice the classes are counted on:
// a catalogue beside another run's scene.ini, an edited scene, a wrong --blocks.
void check_extent(const CatalogEvent& e, const CatalogReader& r, int blocks, int rows, bool lattice,
                  const std::string& from) {
  const auto beyond = [&](const char* column, int v, int n, const char* what) {
    if (v < n) return;
    throw Error("fit: " + r.where() + ": " + column + " = " + std::to_string(v) +
                " lies beyond the " + std::to_string(n) + " " + what + " (from " + from +
                "); allowed: 0 .. " + std::to_string(n - 1));
  };
  beyond("last_block", e.last_block, blocks, "blocks along strike");
  if (r.has_trigger()) beyond("trigger", e.trigger, blocks, "blocks along strike");
  if (lattice) {
    beyond("last_row", e.last_row, rows, "rows");
    if (r.has_trigger()) beyond("trigger_row", e.trigger_row, rows, "rows");
  }
}

// Adds a magnitude to the catalogue's histogram; a bin width too fine for the magnitudes'
// range (more bins than a histogram holds) is named as the option it came from.
void add_magnitude(MagnitudeHistogram& h, double mu, const std::vector<double>& so_far,
                   const FitRequest& r, const CatalogReader& reader) {
  try {
    h.add(mu);
  } catch (const Error& x) {
    double lo = mu, hi = mu;
    for (const double m : so_far) lo = std::min(lo, m), hi = std::max(hi, m);
    throw Error("fit: --bin-width " + format_real(r.bin_width) +
                ": too fine for the magnitudes of " + reader.file() + " (mu " + format_real(lo) +
                " .. " + format_real(hi) + " so far: " + x.what() +
                "); allowed: a width in (0, 10] coarse enough for "
                "that range, e.g. the default " +
                format_real(MagnitudeHistogram::kDefaultBinWidth));
  }
}

void write_scan(const MagnitudeHistogram& h, const GrFit& fit, const fs::path& folder,
                const fs::path& input, std::ostream& out) {
  const fs::path dir = folder.empty() ? fs::path(".") : folder;
  const auto scan_lock = lock_scan_folder(dir, input);
  const std::vector<WindowFit> rows = scan_windows(h, fit);
  write_file_atomic((dir / "b_scan.csv").string(), b_scan_csv(rows));
  std::int64_t accepted = 0;
  for (const auto& r : rows) accepted += r.accepted;
  out << "b scan            " << rows.size() << " windows (" << accepted << " accepted) in "
      << (dir / "b_scan.csv").string() << "\n";
}

// The JSON written as a derived output: a temporary renamed over it, so that a kill leaves
// the old file or the new one, and a link at its name is replaced, never written through;
// only a device (/dev/null, /dev/stdout, or a link to one) is written directly.
void write_json(const Json& o, const DerivedOutput& target) {
  const fs::path& at = target.resolved();
  const std::string text = o.str() + "\n";
  std::error_code ec;
  if (fs::exists(at, ec) && !fs::is_regular_file(at, ec)) {
    std::ofstream f(at);
    if (!f) throw Error("fit: --json: cannot open " + target.path() + " for writing");
    f << text;
    if (!f.flush()) throw Error("fit: --json: write to " + target.path() + " failed");
    return;
  }
  try {
    write_file_atomic(at.string(), text);
  } catch (const Error& e) {
    throw Error(std::string("fit: --json: ") + e.what());
  }
}

// The size measures of `fit --measure` (moment: the Gutenberg-Richter fit alone).
bool measure_is_integer(const std::string& m) {
  return m == "blocks" || m == "topplings" || m == "area";
}
void require_catalogue_for(const FitRequest& r) {
  if (r.measure != "moment")
    throw Error("fit: --measure " + r.measure +
                " needs a catalogue (a histogram holds magnitudes only)");
}

void fit_one_histogram(const FitRequest& request, const Resolved& in, std::ostream& out) {
  require_catalogue_for(request);
  // The folder rule (io/run_folder.hpp): --json never over the histogram or a run's files.
  std::unique_ptr<DerivedOutput> json_out;
  if (request.json)
    json_out = std::make_unique<DerivedOutput>(
        *request.json,
        std::vector<fs::path>{in.file, in.folder / "summary.json", in.folder / "scene.ini"},
        "fit --json");
  const MagnitudeHistogram h = read_histogram(in.file, request);
  require_events_to_fit(in.file.string(), h.events());
  require_window_holds_a_bin(h.bin_width(), request);
  const GrFit fit = fit_histogram(h, request.mu_min, request.mu_max);
  out << "histogram         " << in.file.string() << "\n";
  out << gr_fit_table(fit);
  const char* limits =
      "from a histogram: binned estimates only (no unbinned Aki b, no event classes, no other "
      "bin width: a histogram holds only the counts of its own bins)";
  out << "note: " << limits << "\n";
  if (request.scan) write_scan(h, fit, request.out.value_or(in.folder), in.file, out);
  if (request.json) {
    Json o = Json::object();
    o.set("histogram", in.file.string()).set("fit", gr_fit_json(fit)).set("classes_note", limits);
    write_json(o, *json_out);
  }
}

// The chain length (or lattice shape) and boundary for the event classes: scene.ini beside
// the catalogue, overridden by --blocks and --boundary.
struct ClassShape {
  fs::path scene;  // scene.ini beside the catalogue (may not exist)
  std::optional<int> blocks;
  int rows = 1;  // a lattice's rows (event classes by sites and bounding box when above 1)
  std::string boundary = "free";
};
ClassShape class_shape(const FitRequest& request, const fs::path& catalog) {
  ClassShape c;
  c.scene = catalog.parent_path() / "scene.ini";
  std::optional<SceneModelInfo> scene_info;
  if (fs::exists(c.scene)) {
    const SceneModelInfo info = read_scene_model(c.scene);
    scene_info = info;
    c.blocks = info.blocks;
    if (info.rows) c.rows = *info.rows;
    if (info.boundary) c.boundary = *info.boundary;
  }
  if (request.blocks) {
    check_blocks_option(request, c.scene, scene_info);
    c.blocks = request.blocks;
    c.rows = request.rows.value_or(1);
  }
  if (request.boundary) c.boundary = *request.boundary;
  return c;
}

// The state of the run whose own catalogue this is. The catalogue of an interrupted run
// holds the events recorded so far (whole rows, up to its checkpoint or beyond): they are
// fitted, and the report says so. A run's own catalogue is checked against its summary's
// event count. A summary that does not read is named in a warning and the catalogue speaks
// for itself.
struct RunState {
  fs::path dir;
  RunStatus status = RunStatus::None;
  std::optional<double> summary_events;
  std::optional<LockHolder> writer;  // a run writing the folder now: a growing prefix
  bool interrupted = false;
  bool killed = false;  // SIGKILL, a crash: checkpoints and no summary
};
RunState run_state_of(const fs::path& catalog) {
  RunState r;
  r.dir = catalog.parent_path();
  const std::string name = catalog.filename().string();
  const bool own = name == "catalog.csv" || name == "catalog.h5";
  if (own && std::filesystem::exists(r.dir / "summary.json")) {
    try {
      r.status = run_status(r.dir);
      r.summary_events = read_json_number(r.dir / "summary.json", "events");
    } catch (const Error& e) {
      std::fprintf(stderr, "bkquake: warning: %s; the catalogue is fitted without it\n",
                   escape_unprintable(e.what()).c_str());
      r.status = RunStatus::None;
      r.summary_events.reset();
    }
  }
  // A run writing the folder now (its lock held): its catalogue is a prefix that grows.
  r.writer = own ? live_lock_holder(r.dir.empty() ? fs::path(".") : r.dir) : std::nullopt;
  r.interrupted = r.status == RunStatus::Interrupted && !r.writer;
  // A run killed (SIGKILL, a crash) before its first summary leaves only its checkpoints.
  r.killed = own && !r.writer && r.status == RunStatus::None &&
             (std::filesystem::exists(r.dir / "checkpoint.bin") ||
              std::filesystem::exists(r.dir / "checkpoint.prev.bin"));
  return r;
}

// The size measure's column, checked before the catalogue is read through.
void require_measure_column(const CatalogReader& reader, const std::string& measure, int rows) {
  if (measure == "topplings" && !reader.has_topplings())
    throw Error("fit: --measure topplings: " + reader.file() +
                " has no topplings column (an OFC catalogue has)");
  if (measure == "duration" && !reader.has_duration())
    throw Error("fit: --measure duration: " + reader.file() + " has no duration column");
  if ((measure == "blocks" || measure == "area") && !reader.has_extent())
    throw Error("fit: --measure " + measure + ": " + reader.file() + " has no blocks column");
  if (measure == "area" && rows <= 1 && !reader.has_topplings())
    throw Error(
        "fit: --measure area: the area of the slip map is the number of sites of a "
        "lattice or an OFC run; this catalogue is of a chain (use --measure blocks)");
}

// Whether the event classes can be counted, and why not when not.
struct ClassesPlan {
  bool on = false;
  bool lattice = false;
  std::string note;
};
ClassesPlan classes_plan(const ClassShape& shape, const CatalogReader& reader) {
  ClassesPlan c;
  c.lattice = shape.rows > 1;
  c.on = shape.blocks.has_value() && reader.has_extent() && (!c.lattice || reader.has_rows());
  if (!shape.blocks)
    c.note = "event classes skipped: no --blocks and no scene.ini beside the catalogue";
  else if (!reader.has_extent())
    c.note = "event classes skipped: the catalogue lacks blocks/first_block/last_block";
  else if (!c.on)
    c.note = "event classes skipped: a lattice of " + std::to_string(shape.rows) +
             " rows, and the catalogue lacks trigger_row/first_row/last_row";
  return c;
}

// What one pass over the catalogue gathers: the magnitudes (binned and in order), the
// sizes of the measure and the event classes.
struct CatalogueData {
  MagnitudeHistogram hist;
  std::vector<double> magnitudes, sizes;
  EventClassCounts classes;
};
CatalogueData read_catalogue(CatalogReader& reader, const FitRequest& request,
                             const ClassShape& shape, const ClassesPlan& plan) {
  CatalogueData d{MagnitudeHistogram(request.bin_width), {}, {}, {}};
  const std::string& measure = request.measure;
  const Boundary bnd = parse_boundary(shape.boundary);
  CatalogEvent e;
  const std::string blocks_from = request.blocks ? "--blocks" : shape.scene.string();
  while (reader.next(e)) {
    if (plan.on) check_extent(e, reader, *shape.blocks, shape.rows, plan.lattice, blocks_from);
    add_magnitude(d.hist, e.magnitude, d.magnitudes, request, reader);
    d.magnitudes.push_back(e.magnitude);
    if (measure == "blocks" || measure == "area")
      d.sizes.push_back(e.blocks);
    else if (measure == "topplings")
      d.sizes.push_back(static_cast<double>(e.topplings));
    else if (measure == "duration")
      d.sizes.push_back(e.duration);
    if (plan.on)
      d.classes.add(
          plan.lattice ? classify_lattice_event(e.blocks, e.first_block, e.last_block, e.first_row,
                                                e.last_row, *shape.blocks, shape.rows)
                       : classify_event(e.blocks, e.first_block, e.last_block, *shape.blocks, bnd));
  }
  return d;
}

// (Only a finished run's count is final: a resumed run cuts its catalogue back to the
// checkpoint while the summary of its last stop still counts the events past it.)
void require_summary_count(const RunState& run, const CatalogReader& reader) {
  if (!run.summary_events || run.status != RunStatus::Finished) return;
  const auto expected = static_cast<std::int64_t>(*run.summary_events);
  const std::int64_t found = reader.events_read();
  if (found != expected)
    throw Error(reader.file() + ": holds " + std::to_string(found) + " rows, its run's " +
                (run.dir / "summary.json").string() + " counts " + std::to_string(expected) +
                " events: the catalogue is truncated or was changed");
}

// The notes on a run that is not finished, the fit table and the classes.
void print_catalogue_report(std::ostream& out, const fs::path& catalog, const RunState& run,
                            std::int64_t events, const GrFit& fit, const ClassShape& shape,
                            const ClassesPlan& plan, const EventClassCounts& classes) {
  out << "catalogue         " << catalog.string() << "\n";
  if (run.interrupted)
    out << "note: an interrupted run (summary.json: \"status\": \"interrupted\"): these are its "
        << events << " events so far; --resume finishes it\n";
  if (run.writer)
    out << "note: " << run.writer->describe() << " is writing this folder: these are the " << events
        << " events written so far, and more follow until it ends\n";
  if (run.killed)
    out << "note: an interrupted run (checkpoints beside it, no summary.json: killed?): these "
           "are its "
        << events << " events so far; --resume finishes it\n";
  out << gr_fit_table(fit);
  if (plan.on && plan.lattice)
    out << "classes (a lattice of " << *shape.blocks << " x " << shape.rows << " = "
        << static_cast<std::int64_t>(*shape.blocks) * shape.rows
        << " sites; delocalised: at least half the sites, or edge to edge along an axis)\n"
        << class_counts_table(classes);
  else if (plan.on)
    out << "classes (N = " << *shape.blocks << ", " << shape.boundary << " ends)\n"
        << class_counts_table(classes);
  else
    out << "note: " << plan.note << "\n";
}

// The fit --json object of a catalogue.
Json catalogue_fit_json(const fs::path& catalog, const RunState& run, const GrFit& fit,
                        const std::optional<PowerLawFit>& tau, const std::string& measure,
                        const ClassShape& shape, const ClassesPlan& plan,
                        const EventClassCounts& classes) {
  Json o = Json::object();
  o.set("catalog", catalog.string()).set("fit", gr_fit_json(fit));
  if (tau) o.set("tau", power_law_json(*tau, measure));
  if (run.interrupted || run.killed) o.set("run_status", status_text(RunStatus::Interrupted));
  if (run.writer) o.set("run_status", "running");
  if (plan.on) {
    o.set("blocks", static_cast<std::int64_t>(*shape.blocks))
        .set("boundary", shape.boundary)
        .set("classes", class_counts_json(classes));
    if (plan.lattice) o.set("rows", static_cast<std::int64_t>(shape.rows));
  } else
    o.set("classes_note", plan.note);
  return o;
}

void fit_one_catalog(const FitRequest& request, const Resolved& in, std::ostream& out) {
  const fs::path& catalog = in.file;
  const ClassShape shape = class_shape(request, catalog);
  parse_boundary(shape.boundary);  // refused before anything is read
  const RunState run = run_state_of(catalog);

  // The folder rule (io/run_folder.hpp): --json never over the catalogue or a run's files.
  std::unique_ptr<DerivedOutput> json_out;
  if (request.json)
    json_out = std::make_unique<DerivedOutput>(
        *request.json,
        std::vector<std::filesystem::path>{catalog, run.dir / "summary.json", shape.scene},
        "fit --json");

  CatalogReader reader(catalog);
  if (run.writer) reader.set_growing();
  const ClassesPlan plan = classes_plan(shape, reader);
  require_measure_column(reader, request.measure, shape.rows);
  const CatalogueData data = read_catalogue(reader, request, shape, plan);
  require_summary_count(run, reader);
  require_events_to_fit(reader.file(), reader.events_read());
  require_window_holds_a_bin(request.bin_width, request);

  GrFit fit = fit_histogram(data.hist, request.mu_min, request.mu_max);
  add_unbinned(fit, data.magnitudes);
  print_catalogue_report(out, catalog, run, reader.events_read(), fit, shape, plan, data.classes);
  std::optional<PowerLawFit> tau;
  if (request.measure != "moment") {
    PowerLawOptions po;
    po.discrete = measure_is_integer(request.measure);
    po.x_min = request.x_min;
    po.x_max = request.x_max;
    tau = fit_power_law(data.sizes, po);
    out << power_law_table(*tau, request.measure);
  }
  if (request.scan) write_scan(data.hist, fit, request.out.value_or(in.folder), in.file, out);
  if (request.json)
    write_json(
        catalogue_fit_json(catalog, run, fit, tau, request.measure, shape, plan, data.classes),
        *json_out);
}

// Splits a sweep.csv line, keeping double-quoted fields (with "" inside) whole.
std::vector<std::string> split_quoted(const std::string& line) {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        f.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        f.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      f.emplace_back();
    } else if (c != '\r') {
      f.back() += c;
    }
  }
  return f;
}

// A field as sweep.csv writes it: double-quoted (with "" inside) only when it holds a comma,
// a quote or a line break.
std::string csv_quoted(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q(1, '"');
  for (char c : s) {
    q.push_back(c);
    if (c == '"') q.push_back('"');
  }
  q.push_back('"');
  return q;
}

// tau of a sweep point: the size measure (the request's, else topplings for an OFC
// catalogue, blocks for a lattice's; none for a chain) over its replicas' catalogues, in
// replica order. Empty measure: none applies.
struct PointTau {
  std::string measure;
  std::optional<PowerLawFit> fit;
  std::string error;
};
PointTau point_tau(const FitRequest& request, const fs::path& point) {
  PointTau t;
  std::vector<fs::path> catalogues;
  std::error_code ec;
  if (fs::is_directory(point, ec))
    for (const auto& entry : fs::directory_iterator(point, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.size() < 2 || name[0] != 'r' ||
          name.find_first_not_of("0123456789", 1) != std::string::npos)
        continue;
      for (const char* file : {"catalog.csv", "catalog.h5"})
        if (fs::exists(entry.path() / file)) {
          catalogues.push_back(entry.path() / file);
          break;
        }
    }
  std::sort(catalogues.begin(), catalogues.end());
  if (catalogues.empty()) {
    if (request.measure != "moment") {
      t.measure = request.measure;
      t.error = "no replica catalogue in " + point.string();
    }
    return t;
  }
  try {
    std::vector<double> sizes;
    for (const fs::path& file : catalogues) {
      CatalogReader reader(file);
      if (t.measure.empty()) {
        if (request.measure != "moment")
          t.measure = request.measure;
        else if (reader.has_topplings())
          t.measure = "topplings";
        else if (fs::exists(file.parent_path() / "scene.ini") &&
                 read_scene_model(file.parent_path() / "scene.ini").rows.value_or(1) > 1)
          t.measure = "blocks";
        else
          return t;  // a chain: no tau unless asked for
      }
      if (t.measure == "topplings" && !reader.has_topplings())
        throw Error(file.string() + " has no topplings column (an OFC catalogue has)");
      if (t.measure == "duration" && !reader.has_duration())
        throw Error(file.string() + " has no duration column");
      if ((t.measure == "blocks" || t.measure == "area") && !reader.has_extent())
        throw Error(file.string() + " has no blocks column");
      CatalogEvent e;
      while (reader.next(e))
        sizes.push_back(t.measure == "topplings"  ? static_cast<double>(e.topplings)
                        : t.measure == "duration" ? e.duration
                                                  : static_cast<double>(e.blocks));
    }
    PowerLawOptions po;
    po.discrete = measure_is_integer(t.measure);
    po.x_min = request.x_min;
    po.x_max = request.x_max;
    t.fit = fit_power_law(sizes, po);
    if (!t.fit->ok) {
      t.error = t.fit->no_fit_reason;
      t.fit.reset();
    }
  } catch (const Error& e) {
    t.error = e.what();
    t.fit.reset();
  }
  return t;
}

// Each point of a sweep folder refitted from its merged histogram.csv into sweep_fit.csv,
// with tau from its replicas' catalogues.
void refit_sweep(const FitRequest& request, const fs::path& dir, std::ostream& out) {
  if (request.scan)
    throw Error("fit: --scan applies to one run, catalogue or histogram, not a sweep");
  const std::string csv_path = (dir / "sweep.csv").string();
  const std::string text = read_text_file(csv_path, "sweep.csv");
  std::vector<std::vector<std::string>> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::string line = text.substr(start, end == std::string::npos ? end : end - start);
    if (!line.empty()) lines.push_back(split_quoted(line));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (lines.empty() || lines[0].empty() || lines[0][0] != sweep_col::point)
    throw Error("fit: " + csv_path + ": expected a header line starting with 'point'");
  const std::vector<std::string>& header = lines[0];
  std::size_t keys_end = 1;  // the swept keys sit between point and status
  while (keys_end < header.size() && header[keys_end] != "status") ++keys_end;
  if (keys_end == header.size()) throw Error("fit: " + csv_path + ": missing column 'status'");

  // The point folders by number (their names are zero-padded to the sweep's width).
  std::map<long, fs::path> folders;
  if (fs::is_directory(dir / "points"))
    for (const auto& entry : fs::directory_iterator(dir / "points")) {
      const std::string name = entry.path().filename().string();
      if (name.size() > 1 && name[0] == 'p' &&
          name.find_first_not_of("0123456789", 1) == std::string::npos)
        folders[std::stol(name.substr(1))] = entry.path();
    }

  // Under the sweep folder's lock (a stale one, of a killed command, taken over), the
  // temporaries of a write cut short removed.
  const auto lock = share_folder_lock(dir, "fit", StaleLock::TakeOver);
  remove_temporaries_of((dir / "sweep_fit.csv").string());
  std::string csv;
  {
    std::vector<std::string> h;
    for (const auto& c : sweep_fit_schema()) {
      h.push_back(c.name);
      if (c.name == std::string(sweep_col::point))
        for (std::size_t k = 1; k < keys_end; ++k) h.push_back(header[k]);
    }
    for (std::size_t i = 0; i < h.size(); ++i) csv += (i ? "," : "") + h[i];
    csv += "\n";
  }
  const auto num = [](double x) { return std::isfinite(x) ? format_real(x) : std::string(); };
  std::size_t fitted = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string>& row = lines[i];
    if (row.size() < keys_end)
      throw Error("fit: " + csv_path + ": line " + std::to_string(i + 1) + " is short");
    std::string line = row[0];
    for (std::size_t k = 1; k < keys_end; ++k) {
      line.push_back(',');
      line.append(csv_quoted(row[k]));
    }
    std::string error;
    std::int64_t events = 0;
    GrFit fit;
    fit.b_ok = false;
    const auto folder = folders.find(std::stol(row[0]));
    if (folder == folders.end() || !fs::exists(folder->second / "histogram.csv")) {
      error =
          "no merged histogram.csv for this point (pending, failed, or continuous without "
          "episodes)";
    } else {
      try {
        const MagnitudeHistogram h = read_histogram(folder->second / "histogram.csv", request);
        events = h.events();
        require_events_to_fit((folder->second / "histogram.csv").string(), h.events());
        require_window_holds_a_bin(h.bin_width(), request);
        fit = fit_histogram(h, request.mu_min, request.mu_max);
        if (!fit.b_ok) error = fit.no_b_reason;
        ++fitted;
      } catch (const Error& e) {
        error = e.what();
      }
    }
    const bool b = fit.b_ok;
    const bool window = fit.n_total >= 2;
    const PointTau tau = folder == folders.end() ? PointTau{} : point_tau(request, folder->second);
    const PowerLawFit* pl = tau.fit ? &*tau.fit : nullptr;
    for (const std::string& field :
         {std::to_string(events), b ? num(fit.b_mle) : std::string(),
          b ? num(fit.b_mle_err) : std::string(), b ? num(fit.b_mle_sys_err) : std::string(),
          b ? num(b_moment_magnitude(fit.b_mle)) : std::string(),
          window ? num(fit.mu_min) : std::string(), window ? num(fit.mu_max) : std::string(),
          tau.measure, pl ? num(pl->alpha) : std::string(),
          pl ? num(pl->alpha_boot_err) : std::string(), pl ? num(pl->x_min) : std::string(),
          pl ? num(pl->x_max) : std::string(), pl ? num(pl->p) : std::string(),
          tau.error.empty() ? std::string() : csv_quoted(tau.error),
          error.empty() ? std::string() : csv_quoted(error)}) {
      line.push_back(',');
      line.append(field);
    }
    csv += line + "\n";
  }
  write_file_atomic((dir / "sweep_fit.csv").string(), csv);
  out << "refitted " << fitted << " of " << lines.size() - 1 << " points of " << dir.string()
      << " on the window " << (request.mu_min ? format_real(*request.mu_min) : "auto") << " .. "
      << (request.mu_max ? format_real(*request.mu_max) : "auto") << " into "
      << (dir / "sweep_fit.csv").string() << "\n";
}

}  // namespace

void fit_catalog(const FitRequest& request, std::ostream& out) {
  const Resolved in = resolve(request.catalog);
  switch (in.kind) {
    case Input::Sweep:
      return refit_sweep(request, in.file, out);
    case Input::Histogram:
      return fit_one_histogram(request, in, out);
    case Input::Catalog:
      return fit_one_catalog(request, in, out);
  }
}

}  // namespace bkq
