// Implementation of `bkquake fit` (see fit.hpp): finds what the input holds, reads it
// through io's readers (catalogue, histogram.csv, sweep.csv), fits and reports.
#include "app/fit.hpp"

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
  if (fs::is_directory(input)) {
    if (fs::exists(input / "sweep.ini") && fs::exists(input / "sweep.csv"))
      return {Input::Sweep, input, input};
    for (const char* name : {"catalog.csv", "catalog.h5"})
      if (fs::exists(input / name)) return {Input::Catalog, input / name, input};
    if (fs::exists(input / "histogram.csv"))
      return {Input::Histogram, input / "histogram.csv", input};
    throw Error("fit: folder '" + input.string() +
                "' holds no catalog.csv, catalog.h5, histogram.csv or sweep.csv (sweep.ini)");
  }
  if (!fs::exists(input)) throw Error("fit: '" + input.string() + "' does not exist");
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

void write_scan(const MagnitudeHistogram& h, const GrFit& fit, const fs::path& folder,
                std::ostream& out) {
  const fs::path dir = folder.empty() ? fs::path(".") : folder;
  fs::create_directories(dir);
  const FolderLock lock(dir.string(), "fit", StaleLock::Refuse);
  const std::vector<WindowFit> rows = scan_windows(h, fit);
  write_file_atomic((dir / "b_scan.csv").string(), b_scan_csv(rows));
  std::int64_t accepted = 0;
  for (const auto& r : rows) accepted += r.accepted;
  out << "b scan            " << rows.size() << " windows (" << accepted << " accepted) in "
      << (dir / "b_scan.csv").string() << "\n";
}

void write_json(const Json& o, const fs::path& file) {
  const std::string path = file.string();
  std::ofstream f(path);
  if (!f) throw Error("fit: --json: cannot open " + path + " for writing");
  f << o.str() << "\n";
  if (!f) throw Error("fit: --json: write to " + path + " failed");
}

// The size measures of `fit --measure` (moment: the Gutenberg-Richter fit alone).
bool measure_is_integer(const std::string& m) {
  return m == "blocks" || m == "topplings" || m == "area";
}
void require_catalogue_for(const FitRequest& r) {
  if (r.measure != "moment")
    throw Error("fit: --measure " + r.measure +
                " needs a catalogue (a histogram or a sweep holds magnitudes only)");
}

void fit_one_histogram(const FitRequest& request, const Resolved& in, std::ostream& out) {
  require_catalogue_for(request);
  const MagnitudeHistogram h = read_histogram(in.file, request);
  require_events_to_fit(in.file.string(), h.events());
  const GrFit fit = fit_histogram(h, request.mu_min, request.mu_max);
  out << "histogram         " << in.file.string() << "\n";
  out << gr_fit_table(fit);
  const char* limits =
      "from a histogram: binned estimates only (no unbinned Aki b, no event classes, no other "
      "bin width: a histogram holds only the counts of its own bins)";
  out << "note: " << limits << "\n";
  if (request.scan) write_scan(h, fit, request.out.value_or(in.folder), out);
  if (request.json) {
    Json o = Json::object();
    o.set("histogram", in.file.string()).set("fit", gr_fit_json(fit)).set("classes_note", limits);
    write_json(o, *request.json);
  }
}

void fit_one_catalog(const FitRequest& request, const Resolved& in, std::ostream& out) {
  const fs::path& catalog = in.file;
  // Chain length and boundary for the event classes.
  std::optional<int> blocks;
  int rows = 1;  // a lattice's rows (event classes by sites and bounding box when above 1)
  std::string boundary = "free";
  const auto scene = catalog.parent_path() / "scene.ini";
  if (fs::exists(scene)) {
    const SceneModelInfo info = read_scene_model(scene);
    blocks = info.blocks;
    if (info.rows) rows = *info.rows;
    if (info.boundary) boundary = *info.boundary;
  }
  if (request.blocks) {
    blocks = request.blocks;
    rows = request.rows.value_or(1);
  }
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
  const bool lattice = rows > 1;
  const bool classes_on =
      blocks.has_value() && reader.has_extent() && (!lattice || reader.has_rows());
  std::string class_note;
  if (!blocks)
    class_note = "event classes skipped: no --blocks and no scene.ini beside the catalogue";
  else if (!reader.has_extent())
    class_note = "event classes skipped: the catalogue lacks blocks/first_block/last_block";
  else if (!classes_on)
    class_note = "event classes skipped: a lattice of " + std::to_string(rows) +
                 " rows, and the catalogue lacks trigger_row/first_row/last_row";

  // The size measure's column (checked before the catalogue is read through).
  const std::string& measure = request.measure;
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
  MagnitudeHistogram hist(request.bin_width);
  std::vector<double> magnitudes, sizes;
  EventClassCounts classes;
  CatalogEvent e;
  while (reader.next(e)) {
    hist.add(e.magnitude);
    magnitudes.push_back(e.magnitude);
    if (measure == "blocks" || measure == "area")
      sizes.push_back(e.blocks);
    else if (measure == "topplings")
      sizes.push_back(static_cast<double>(e.topplings));
    else if (measure == "duration")
      sizes.push_back(e.duration);
    if (classes_on)
      classes.add(lattice ? classify_lattice_event(e.blocks, e.first_block, e.last_block,
                                                   e.first_row, e.last_row, *blocks, rows)
                          : classify_event(e.blocks, e.first_block, e.last_block, *blocks, bnd));
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
  if (classes_on && lattice)
    out << "classes (a lattice of " << *blocks << " x " << rows << " = "
        << static_cast<std::int64_t>(*blocks) * rows
        << " sites; delocalised: at least half the sites, or edge to edge along an axis)\n"
        << class_counts_table(classes);
  else if (classes_on)
    out << "classes (N = " << *blocks << ", " << boundary << " ends)\n"
        << class_counts_table(classes);
  else
    out << "note: " << class_note << "\n";
  std::optional<PowerLawFit> tau;
  if (measure != "moment") {
    PowerLawOptions po;
    po.discrete = measure_is_integer(measure);
    tau = fit_power_law(sizes, po);
    out << power_law_table(*tau, measure);
  }
  if (request.scan) write_scan(hist, fit, request.out.value_or(in.folder), out);

  if (request.json) {
    Json o = Json::object();
    o.set("catalog", catalog.string()).set("fit", gr_fit_json(fit));
    if (tau) o.set("tau", power_law_json(*tau, measure));
    if (interrupted || killed) o.set("run_status", status_text(RunStatus::Interrupted));
    if (classes_on) {
      o.set("blocks", static_cast<std::int64_t>(*blocks))
          .set("boundary", boundary)
          .set("classes", class_counts_json(classes));
      if (lattice) o.set("rows", static_cast<std::int64_t>(rows));
    } else
      o.set("classes_note", class_note);
    write_json(o, *request.json);
  }
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

// Each point of a sweep folder refitted from its merged histogram.csv into sweep_fit.csv.
void refit_sweep(const FitRequest& request, const fs::path& dir, std::ostream& out) {
  require_catalogue_for(request);
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

  const FolderLock lock(dir.string(), "fit", StaleLock::Refuse);
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
        fit = fit_histogram(h, request.mu_min, request.mu_max);
        if (!fit.b_ok) error = fit.no_b_reason;
        ++fitted;
      } catch (const Error& e) {
        error = e.what();
      }
    }
    const bool b = fit.b_ok;
    const bool window = fit.n_total >= 2;
    for (const std::string& field :
         {std::to_string(events), b ? num(fit.b_mle) : std::string(),
          b ? num(fit.b_mle_err) : std::string(), b ? num(fit.b_mle_sys_err) : std::string(),
          b ? num(b_moment_magnitude(fit.b_mle)) : std::string(),
          window ? num(fit.mu_min) : std::string(), window ? num(fit.mu_max) : std::string(),
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
