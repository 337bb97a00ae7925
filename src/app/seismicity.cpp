// The seismicity analysis of a catalogue; see seismicity.hpp.
#include "app/seismicity.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <sstream>

#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/catalog_reader.hpp"
#include "io/folder_lock.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/scene_keys.hpp"
#include "io/scene_values.hpp"
#include "io/seismicity_csv.hpp"

namespace bkq {

namespace {

namespace fs = std::filesystem;
using seis::Estimate;

const char* kOutFolder = "seismicity";

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The catalogue of a run folder.
std::optional<fs::path> catalog_in(const fs::path& dir) {
  for (const char* name : {"catalog.csv", "catalog.h5"})
    if (fs::is_regular_file(dir / name)) return dir / name;
  return std::nullopt;
}

// The first "mu_min" of a summary.json (a run's fit_window.mu_min, a merge's mu_min);
// nullopt without the file or the number.
std::optional<double> fit_window_mu_min(const fs::path& summary) {
  if (!fs::is_regular_file(summary)) return std::nullopt;
  const std::string text = slurp(summary);
  const std::string key = "\"mu_min\":";
  const auto at = text.find(key);
  if (at == std::string::npos) return std::nullopt;
  char* end = nullptr;
  const char* from = text.c_str() + at + key.size();
  const double v = std::strtod(from, &end);
  if (end == from || !std::isfinite(v)) return std::nullopt;
  return v;
}

seis::Quake quake_of(const CatalogEvent& e, const CatalogReader& r) {
  seis::Quake q;
  q.event = e.event;
  q.t = e.load;
  q.moment = e.moment;
  q.mu = e.magnitude;
  q.duration = r.has_duration() ? e.duration : 0.0;
  q.trigger = e.trigger;
  if (r.has_rows()) q.trigger_row = e.trigger_row;
  if (r.has_extent()) {
    q.first = e.first_block;
    q.last = e.last_block;
    q.blocks = e.blocks;
  } else {
    q.first = 1;
    q.last = 0;  // unknown
  }
  if (!r.has_trigger() && r.has_extent()) q.trigger = (e.first_block + e.last_block) / 2;
  return q;
}

Json num(double x) {
  return Json::number(x, Json::Real::shortest);
}
Json num_or_null(bool ok, double x) {
  return ok ? num(x) : Json::null();
}

void estimate_pair(Json& o, const std::string& key, const Estimate& e, bool ok) {
  o.set(key, num_or_null(ok, e.value));
  o.set(key + "_err", num_or_null(ok, e.err));
}

Json intervals_json(const seis::Intervals& iv, const seis::WeibullFit& w,
                    const seis::LognormalFit& l) {
  Json o = Json::object();
  o.set("intervals", iv.moments.n());
  o.set("mean", num(iv.moments.mean()));
  o.set("cov", num(iv.moments.cov()));
  o.set("cov_err", num(iv.moments.cov_err()));
  estimate_pair(o, "weibull_k", w.k, w.ok);
  estimate_pair(o, "weibull_lambda", w.lambda, w.ok);
  estimate_pair(o, "lognormal_mu", l.m, l.ok);
  estimate_pair(o, "lognormal_sigma", l.s, l.ok);
  return o;
}

Json omori_json(const seis::OmoriFit& f, std::int64_t sequences, bool after) {
  Json o = Json::object();
  o.set("sequences", sequences);
  o.set("excess", f.excess);
  o.set("likelihood_ratio", num(f.lr));
  o.set("fit_t_max", num(f.t_max));
  if (after) {
    estimate_pair(o, "K", f.K, f.excess);
    estimate_pair(o, "c", f.c, f.excess);
    estimate_pair(o, "p", f.p, f.excess);
    estimate_pair(o, "background", f.background, f.excess);
    o.set("aftershocks", num(f.excess ? f.excess_events : 0.0));
  } else {
    estimate_pair(o, "p_inverse", f.p, f.excess);
    estimate_pair(o, "K", f.K, f.excess);
    estimate_pair(o, "c", f.c, f.excess);
    estimate_pair(o, "background", f.background, f.excess);
    o.set("foreshocks", num(f.excess ? f.excess_events : 0.0));
  }
  if (!f.excess) o.set("background_rate", num(f.background_only));
  if (!f.note.empty()) o.set("note", f.note);
  return o;
}

// Writes the output files into `dir` (which exists).
void write_outputs(const fs::path& dir, const seis::Seismicity& s,
                   const std::vector<std::string>& comments, const std::string& json) {
  auto with = [&](const char* what) {
    std::vector<std::string> c = {what};
    c.insert(c.end(), comments.begin(), comments.end());
    return c;
  };
  write_file_atomic((dir / "interevent.csv").string(),
                    interevent_csv(s, with("waiting times between consecutive events")));
  write_file_atomic((dir / "recurrence.csv").string(),
                    recurrence_csv(s, with("recurrence intervals of mainshocks")));
  write_file_atomic((dir / "omori.csv").string(),
                    omori_csv(s, with("event rates stacked around mainshocks")));
  write_file_atomic((dir / "moment_rate.csv").string(),
                    moment_rate_csv(s, with("moment released per time bin")));
  write_file_atomic((dir / "scaling.csv").string(),
                    scaling_csv(s, with("moment against rupture length and duration")));
  write_file_atomic((dir / "spacetime.csv").string(),
                    spacetime_csv(s, with("seismicity before mainshocks in space and time")));
  write_file_atomic((dir / "seismicity.json").string(), json + "\n");
}

// The files seismicity writes into its folder (write_outputs).
const char* const kOutputFiles[] = {"interevent.csv", "moment_rate.csv", "omori.csv",
                                    "recurrence.csv", "scaling.csv",     "spacetime.csv",
                                    "seismicity.json"};

// seismicity/ is built in .seismicity.new-PID beside it and swapped in; a set it replaces
// waits in .seismicity.old-PID only where the file system cannot swap two folders at once.
const std::string kNewPrefix = std::string(".") + kOutFolder + ".new-";
const std::string kOldPrefix = std::string(".") + kOutFolder + ".old-";

// What a killed seismicity left in `folder` (its lock held): a half-built new set goes; an
// old set left between the two renames of a swap is put back when seismicity/ is missing.
void clean_swap_leftovers(const fs::path& folder) {
  std::error_code ec;
  std::vector<fs::path> fresh, old;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kNewPrefix, 0) == 0) fresh.push_back(entry.path());
    if (name.rfind(kOldPrefix, 0) == 0) old.push_back(entry.path());
  }
  for (const auto& f : fresh) fs::remove_all(f, ec);
  const fs::path final_dir = folder / kOutFolder;
  if (!old.empty() && !fs::exists(final_dir, ec)) {
    fs::rename(old.back(), final_dir, ec);
    if (!ec) old.pop_back();
  }
  for (const auto& f : old) fs::remove_all(f, ec);
}

// Puts the folder `fresh` in place of `final_dir`: one atomic exchange where the file system
// has it (a kill leaves the old set or the new one), else two renames, whose gap the next
// run repairs (clean_swap_leftovers). The old set is removed once the swap is on disk.
void swap_in(const fs::path& fresh, const fs::path& final_dir) {
  std::error_code ec;
  const fs::path folder = final_dir.parent_path();
  fs::path old;
  if (!fs::exists(final_dir, ec)) {
    rename_file(fresh.string(), final_dir.string());
  } else if (::renameat2(AT_FDCWD, fresh.c_str(), AT_FDCWD, final_dir.c_str(), RENAME_EXCHANGE) ==
             0) {
    old = fresh;  // the exchange left the old set under the new one's name
  } else {
    old = folder / (kOldPrefix + std::to_string(::getpid()));
    rename_file(final_dir.string(), old.string());
    rename_file(fresh.string(), final_dir.string());
  }
  sync_folder(folder.string());
  if (!old.empty()) fs::remove_all(old, ec);
}

// Removes the export temporaries (FILE.tmp-PID) of processes that are gone.
void remove_dead_export_temporaries(const fs::path& file) {
  std::error_code ec;
  const std::string stem = file.filename().string() + ".tmp-";
  std::vector<fs::path> dead;
  for (const auto& entry : fs::directory_iterator(file.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem, 0) != 0 || name.size() == stem.size()) continue;
    const std::string pid = name.substr(stem.size());
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    if (::kill(static_cast<pid_t>(std::stol(pid)), 0) != 0 && errno == ESRCH)
      dead.push_back(entry.path());
  }
  for (const auto& f : dead) fs::remove(f, ec);
}

// The locks and rules of seismicity's outputs, held while it runs.
struct Outputs {
  std::unique_ptr<DerivedOutput> exported;  // --export: the derived-output rule and lock
  std::shared_ptr<FolderLock> parent;       // a run's folder --out lies in
  std::shared_ptr<FolderLock> lock;         // the folder that gets seismicity/, or --out
};

Outputs lock_outputs(const SeismicityRequest& req, const std::string& catalog,
                     const fs::path& folder) {
  Outputs o;
  std::error_code ec;
  const fs::path out_dir = req.out.empty() ? folder : fs::path(req.out);
  if (!req.out.empty()) {
    if (fs::exists(out_dir, ec) && !fs::is_directory(out_dir, ec))
      throw Error("seismicity: --out " + req.out +
                  ": not a folder; expected a folder for seismicity's files");
    o.parent = lock_derived_folder_parent(out_dir, "seismicity");
    fs::create_directories(out_dir, ec);
    if (ec) throw Error("seismicity: --out " + req.out + ": " + ec.message());
  }
  if (!req.export_file.empty()) {
    // Never over its input or a run's own files, and under the lock of a run's folder.
    o.exported = std::make_unique<DerivedOutput>(
        req.export_file,
        std::vector<fs::path>{catalog, folder / "scene.ini", folder / "summary.json"},
        "seismicity --export");
    const fs::path at = o.exported->resolved();
    if (fs::exists(at, ec) && !fs::is_regular_file(at, ec))
      throw Error("seismicity: --export " + req.export_file +
                  ": not a regular file (a device, a pipe or a socket); expected the name of "
                  "a file to write");
    // Nor into what seismicity itself replaces.
    const fs::path into = fs::weakly_canonical(fs::absolute(out_dir), ec);
    const std::string name = at.filename().string();
    bool clash = false;
    if (req.out.empty()) {
      const auto rel = at.lexically_relative(into / kOutFolder);
      clash = !rel.empty() && *rel.begin() != "..";
    } else {
      for (const char* f : kOutputFiles) clash = clash || (at.parent_path() == into && name == f);
    }
    if (clash)
      throw Error("seismicity: --export " + req.export_file + " would be replaced by " +
                  "seismicity's own output in " +
                  (req.out.empty() ? (out_dir / kOutFolder).string() : req.out) +
                  ": choose a file outside it");
    remove_dead_export_temporaries(at);
  }
  o.lock = share_folder_lock(out_dir, "seismicity", StaleLock::TakeOver);
  if (req.out.empty())
    clean_swap_leftovers(out_dir);
  else
    for (const char* f : kOutputFiles) remove_temporaries_of((out_dir / f).string());
  return o;
}

// Refuses a row whose blocks (or rows) lie beyond the chain or lattice the analysis was
// given: a catalogue beside another run's scene.ini, an edited scene, a wrong --blocks. Its
// indices would otherwise fall outside the per-block statistics.
void check_extent(const CatalogEvent& e, const CatalogReader& r, const seis::Geometry& g,
                  const std::string& blocks_from, const std::string& rows_from) {
  const auto beyond = [&](const char* column, int v, int n, const char* what,
                          const std::string& from) {
    if (v < n) return;
    throw Error("seismicity: " + r.where() + ": " + column + " = " + std::to_string(v) +
                " lies beyond the " + std::to_string(n) + " " + what + " (from " + from +
                "); allowed: 0 .. " + std::to_string(n - 1));
  };
  if (r.has_extent()) beyond("last_block", e.last_block, g.nx, "blocks along strike", blocks_from);
  if (r.has_trigger()) beyond("trigger", e.trigger, g.nx, "blocks along strike", blocks_from);
  if (r.has_rows()) {
    beyond("last_row", e.last_row, g.ny, "rows", rows_from);
    beyond("trigger_row", e.trigger_row, g.ny, "rows", rows_from);
  }
}

// The catalogue's export in seismology's conventions, streamed to FILE.tmp and renamed at
// the end.
class ExportFile {
 public:
  ExportFile(const std::string& path, double offset, const std::vector<std::string>& comments)
      : path_(path), tmp_(path + ".tmp-" + std::to_string(::getpid())), offset_(offset) {
    f_ = std::fopen(tmp_.c_str(), "w");
    if (!f_) throw Error("seismicity: --export " + path + ": cannot open for writing");
    std::string head;
    for (const auto& c : comments) head += "# " + c + "\n";
    head += header_of(seismicity_export_schema()) + "\n";
    put(head);
  }
  ~ExportFile() {
    if (f_) {
      std::fclose(f_);
      std::remove(tmp_.c_str());
    }
  }
  void add(const seis::Quake& q) {
    line_ = seismicity_export_row(q, offset_);
    line_ += '\n';
    put(line_);
  }
  void close() {
    const bool ok = std::fflush(f_) == 0 && ::fsync(::fileno(f_)) == 0;
    std::fclose(f_);
    f_ = nullptr;
    if (!ok) throw Error("seismicity: --export " + path_ + ": write failed");
    rename_file(tmp_, path_);
  }

 private:
  void put(const std::string& s) {
    if (std::fwrite(s.data(), 1, s.size(), f_) != s.size())
      throw Error("seismicity: --export " + path_ + ": write failed");
  }
  std::string path_, tmp_;
  double offset_;
  std::FILE* f_ = nullptr;
  std::string line_;
};

}  // namespace

std::vector<std::string> seismicity_inputs(const std::string& input) {
  const fs::path p(input);
  std::error_code ec;
  if (!fs::exists(p, ec)) throw Error("seismicity: " + input + ": no such file or folder");
  if (!fs::is_directory(p, ec)) return {input};
  const fs::path summary = p / "summary.json";
  if (fs::exists(summary) && slurp(summary).find("\"merged_from\"") != std::string::npos)
    throw Error("seismicity: " + input +
                " is a merged folder: merged runs have no single clock (each run's load starts "
                "afresh) and no catalogue; run bkquake seismicity on each run listed under "
                "merged_from in its summary.json");
  if (catalog_in(p)) return {input};
  if (fs::exists(p / "sweep.csv")) {
    // A sweep keeps each replica's run in SWEEP/points/pNNNN/rNN (io/sweep_file.hpp); its
    // catalogue stays there when the sweep file's collect keeps it.
    std::vector<std::string> runs;
    for (const auto& point : fs::directory_iterator(p / "points", ec)) {
      if (!point.is_directory(ec)) continue;
      for (const auto& replica : fs::directory_iterator(point.path(), ec))
        if (replica.is_directory(ec) && catalog_in(replica.path()))
          runs.push_back(replica.path().string());
    }
    std::sort(runs.begin(), runs.end());
    if (runs.empty())
      throw Error("seismicity: sweep folder " + input +
                  " keeps no catalogue in points/*/r*/ (a sweep keeps its replicas' catalogues "
                  "with collect = catalog in its sweep file's [sweep] section)");
    return runs;
  }
  throw Error("seismicity: " + input +
              " holds no catalog.csv or catalog.h5 (a run with output.catalog = none keeps "
              "none)");
}

namespace {

// What seismicity_of learns before it reads the events: where the catalogue lies, who is
// writing it, the scene beside it, the chain or lattice it covers and the analysis' options.
struct Setup {
  fs::path folder;  // the run folder, or the catalogue's folder
  Outputs outputs;
  std::optional<LockHolder> writer;  // a run writing the catalogue's folder now
  std::optional<Scene> scene;        // the scene beside the catalogue, when there is one
  fs::path scene_ini;
  int blocks = 0;
  seis::Geometry geometry;
  std::string rows_from;  // empty for a chain
  seis::SeismicityOptions opt;
  std::string b_rule;  // how opt.b_mu_min was chosen
  std::vector<std::string> comments;
};

// The catalogue of `req.input` (a run folder or a catalogue file) into rep.catalog; returns
// the folder it lies in.
fs::path locate_catalog(const SeismicityRequest& req, SeismicityReport& rep) {
  const fs::path in(req.input);
  if (fs::is_directory(in)) {
    const auto c = catalog_in(in);
    if (!c) throw Error("seismicity: " + req.input + " holds no catalog.csv or catalog.h5");
    rep.catalog = c->string();
    return in;
  }
  std::error_code ec;
  if (!fs::exists(in, ec)) throw Error("seismicity: " + req.input + ": no such file");
  // A device (/dev/zero) or a pipe reads without end: refused as the catalogue reader does.
  if (!fs::is_regular_file(in, ec))
    throw Error("seismicity: " + req.input +
                ": not a regular file (a device, a pipe or a socket); expected a catalogue "
                "file or a run folder");
  rep.catalog = in.string();
  return in.has_parent_path() ? in.parent_path() : fs::path(".");
}

// The chain's length N: scene.ini's model.blocks, else --blocks, else the catalogue's extent.
int blocks_of(const SeismicityRequest& req, const Setup& su, SeismicityReport& rep) {
  int blocks = 0;
  if (su.scene) {
    blocks = scene_values(*su.scene).model.blocks;
    rep.blocks_from = "scene.ini";
    if (req.blocks && *req.blocks != blocks)
      throw Error("seismicity: --blocks = " + std::to_string(*req.blocks) + " contradicts " +
                  su.scene_ini.string() + " (model.blocks = " + std::to_string(blocks) + ")");
  } else if (req.blocks) {
    blocks = *req.blocks;
    rep.blocks_from = "--blocks";
  } else {
    CatalogReader pre(rep.catalog);
    if (su.writer) pre.set_growing();
    if (!pre.has_extent())
      throw Error("seismicity: " + rep.catalog +
                  " has no first_block/last_block columns and no scene.ini beside it: give "
                  "--blocks N");
    CatalogEvent e;
    while (pre.next(e)) blocks = std::max(blocks, e.last_block + 1);
    rep.blocks_from = "max(last_block) + 1 of the catalogue";
  }
  if (blocks < 1)
    throw Error("seismicity: N = " + std::to_string(blocks) + " (" + rep.blocks_from +
                "): expected at least 1 block");
  return blocks;
}

// A lattice (the catalogue has the row columns): its rows and boundaries from scene.ini,
// else its rows from the catalogue (max(last_row) + 1) and free boundaries. The
// hypocentres' distances are then Euclidean in the plane (stats/seismicity/geometry.hpp).
void find_geometry(Setup& su, const SeismicityReport& rep) {
  su.geometry = seis::Geometry::chain(su.blocks);
  CatalogReader probe(rep.catalog);
  if (su.writer) probe.set_growing();
  if (probe.has_rows()) {
    su.geometry.nx = su.blocks;
    if (su.scene) {
      const ModelKeys model = scene_values(*su.scene).model;
      su.geometry.ny = model.rows;
      su.geometry.periodic_x = model.boundary == Boundary::Periodic;
      su.geometry.periodic_y = model.boundary_y == Boundary::Periodic;
      su.rows_from = "scene.ini";
    } else {
      for (CatalogEvent e; probe.next(e);)
        su.geometry.ny = std::max(su.geometry.ny, e.last_row + 1);
      su.rows_from = "max(last_row) + 1 of the catalogue; boundaries taken as free";
    }
  }
  // The statistics keep a few numbers a site: no more sites than the largest lattice a run
  // may have (an OFC lattice's 1e8), which a damaged catalogue's extent could exceed.
  if (static_cast<std::int64_t>(su.geometry.nx) * su.geometry.ny > 100'000'000)
    throw Error("seismicity: " + std::to_string(su.geometry.nx) + " x " +
                std::to_string(su.geometry.ny) + " sites (blocks from " + rep.blocks_from +
                (su.rows_from.empty() ? "" : ", rows from " + su.rows_from) +
                "): allowed at most 1e8 sites, the largest lattice a run may have");
}

// The analysis' options from the request and the geometry; su.b_rule says where the
// b-values' lower magnitude came from.
void choose_options(const SeismicityRequest& req, Setup& su) {
  seis::SeismicityOptions& opt = su.opt;
  opt.blocks = su.blocks;
  if (su.geometry.lattice()) opt.geometry = su.geometry;
  opt.mainshock.blocks = su.blocks;
  opt.mainshock.mu = req.mainshock_mu;
  if (req.interevent_mu) opt.interevent_mu = *req.interevent_mu;
  // The b-values' lower magnitude: --b-mu-min, else the lower end of the run's own
  // Gutenberg-Richter window (summary.json fit_window.mu_min: above the discrete one- and
  // two-block events), else maximum curvature.
  su.b_rule = "--b-mu-min";
  opt.b_mu_min = req.b_mu_min;
  if (!opt.b_mu_min) {
    if (const auto mu = fit_window_mu_min(su.folder / "summary.json")) {
      opt.b_mu_min = *mu;
      su.b_rule = "the lower end of the run's Gutenberg-Richter window (summary.json mu_min)";
    } else {
      su.b_rule = "maximum curvature (the fullest 0.2 bin of mu; Wiemer & Wyss 2000)";
    }
  }
}

// Refuses a catalogue without the columns the analysis needs.
void check_columns(const CatalogReader& reader, const SeismicityRequest& req,
                   const std::string& catalog) {
  if (!reader.has_load())
    throw Error("seismicity: " + catalog + ": missing column 'load' (the events' time)");
  if (!req.mainshock_mu && !reader.has_extent())
    throw Error("seismicity: " + catalog +
                " has no first_block/last_block columns, so mainshocks cannot be told by their "
                "extent: give --mainshock-mu X");
}

// The first lines of the printout: what is analysed and how.
void log_setup(std::ostream& log, const Setup& su, const SeismicityReport& rep) {
  log << "seismicity of " << rep.catalog << " (N = " << su.blocks << ", from " << rep.blocks_from;
  if (su.geometry.lattice())
    log << "; a lattice of " << su.geometry.ny << " rows, from " << su.rows_from
        << ": distances Euclidean between trigger sites"
        << (su.geometry.periodic_x || su.geometry.periodic_y ? ", wrapped where periodic" : "");
  log << ")\n";
  if (su.writer)
    log << "  note: " << su.writer->describe()
        << " is writing this folder: the events written so far are analysed\n";
  log << "  time: " << rep.clock << "\n  mainshocks: " << su.opt.mainshock.describe() << "\n";
}

// The outputs' comment lines: the input, then the scene's provenance (or the program's).
std::vector<std::string> comments_of(const std::optional<Scene>& scene,
                                     const std::string& catalog) {
  std::vector<std::string> comments;
  if (scene) {
    comments = provenance_lines(*scene);
  } else {
    comments = {std::string("bkquake ") + kVersion + " (git " + kGitRevision + ")",
                "written " + utc_now_iso()};
  }
  comments.insert(comments.begin(), "input " + catalog);
  return comments;
}

// Everything up to the events: the catalogue located, the outputs locked, the scene read,
// the geometry and options chosen, the reader's columns checked.
Setup prepare(const SeismicityRequest& req, SeismicityReport& rep) {
  Setup su;
  su.folder = locate_catalog(req, rep);
  // The outputs' folders are locked before anything is read (a live run's folder is refused
  // at once): the export's (a derived output, io/run_folder.hpp), then the folder that gets
  // seismicity/ (or --out).
  su.outputs = lock_outputs(req, rep.catalog, su.folder);
  // A run writing the catalogue's folder now (seismicity's files going elsewhere): its rows
  // so far are analysed, up to the one being written.
  su.writer = live_lock_holder(su.folder);
  su.scene_ini = su.folder / "scene.ini";
  if (fs::is_regular_file(su.scene_ini)) su.scene = read_run_scene(su.scene_ini);
  const bool continuous = su.scene && scene_values(*su.scene).drive.mode == DriveMode::Continuous;
  rep.clock = continuous ? "load at the start of each slip episode (continuous run: the "
                           "substrate displacement v t at the episode's start)"
                         : "load (substrate displacement at the trigger; event-driven run)";
  su.blocks = blocks_of(req, su, rep);
  find_geometry(su, rep);
  return su;
}

// Every event of `reader` into `s` (and the export), in time order.
void read_events(CatalogReader& reader, const Setup& su, const SeismicityRequest& req,
                 const SeismicityReport& rep, seis::Seismicity& s) {
  std::optional<ExportFile> exporter;
  if (!req.export_file.empty()) {
    std::vector<std::string> c = {
        "catalogue in seismology's conventions: time, Mw = (2/3) log10(moment) + " +
        format_real(req.mw_offset) + ", x = position along strike (trigger block)"};
    c.insert(c.end(), su.comments.begin(), su.comments.end());
    exporter.emplace(su.outputs.exported->resolved().string(), req.mw_offset, c);
  }
  CatalogEvent e;
  double last_t = -INFINITY;
  while (reader.next(e)) {
    check_extent(e, reader, su.geometry, rep.blocks_from, su.rows_from);
    const seis::Quake q = quake_of(e, reader);
    if (q.t < last_t)
      throw Error("seismicity: " + rep.catalog + " event " + std::to_string(e.event) +
                  ": time (load) " + format_real(q.t) + " is before the previous event's " +
                  format_real(last_t) + "; the events must be in time order");
    last_t = q.t;
    s.add(q);
    if (exporter) exporter->add(q);
  }
  if (s.events() < 2)
    throw Error("seismicity: " + rep.catalog + ": need at least 2 events, found " +
                std::to_string(s.events()));
  s.finish();
  if (exporter) exporter->close();
}

// seismicity.json's interevent section: the waiting times' moments, all and by subset.
Json interevent_json(const seis::Seismicity& s) {
  const auto& all = s.interevent().all().moments;
  Json o = Json::object();
  o.set("intervals", all.n());
  o.set("mean", num(all.mean()));
  o.set("cov", num(all.cov()));
  o.set("cov_err", num(all.cov_err()));
  Json subsets = Json::array();
  for (const auto& w : s.interevent().subsets()) {
    Json x = Json::object();
    x.set("subset", w.subset);
    x.set("intervals", w.moments.n());
    x.set("mean", num(w.moments.mean()));
    x.set("cov", num(w.moments.cov()));
    x.set("cov_err", num(w.moments.cov_err()));
    subsets.push(std::move(x));
  }
  o.set("subsets", std::move(subsets));
  return o;
}

// seismicity.json's bath section: Båth's law, the largest aftershock's magnitude gap.
Json bath_json(const seis::Seismicity& s) {
  const auto& b = s.bath();
  Json o = Json::object();
  const bool ok = b.sequences > 0;
  o.set("delta_mu", num_or_null(ok, b.delta_mu));
  o.set("delta_mu_err", num_or_null(ok && std::isfinite(b.delta_mu_err), b.delta_mu_err));
  o.set("delta_mw", num_or_null(ok, b.delta_mw()));
  o.set("delta_mw_err",
        num_or_null(ok && std::isfinite(b.delta_mu_err), b.delta_mu_err / seis::kMuPerMw));
  o.set("sequences", b.sequences);
  o.set("window", num_or_null(ok, b.window));
  o.set("window_rule", b.window_rule);
  o.set("units",
        "delta_mu in mu = ln M; delta_mw in Mw = (2/3) log10 M; delta_mu = 1.5 ln 10 "
        "delta_mw = 3.454 delta_mw");
  return o;
}

// seismicity.json's scaling section: moment against rupture length and duration.
Json scaling_json(const seis::Seismicity& s) {
  Json o = Json::object();
  const seis::LineFit L = s.scaling().length().binned_fit();
  const seis::LineFit T = s.scaling().duration().binned_fit();
  const auto& Le = s.scaling().length().fit;
  const auto& Te = s.scaling().duration().fit;
  o.set("length_exponent", num(L.slope()));
  o.set("length_exponent_err", num(L.slope_err()));
  o.set("length_bins", L.n());
  o.set("duration_exponent", num(T.slope()));
  o.set("duration_exponent_err", num(T.slope_err()));
  o.set("duration_bins", T.n());
  o.set("method",
        "least squares of the log bins' mean ln M on their mean ln L (ln T), one "
        "point a bin of 3 events or more; the *_per_event fits weight every event");
  o.set("length_exponent_per_event", num(Le.slope()));
  o.set("duration_exponent_per_event", num(Te.slope()));
  return o;
}

// seismicity.json's spacetime section: the b-value of all events and the distance rule.
Json spacetime_json(const seis::Seismicity& s, const Setup& su) {
  Json o = Json::object();
  const Estimate b = s.spacetime().all().b(s.b_mu_min());
  o.set("b_mu_min", num(s.b_mu_min()));
  o.set("b_mu_min_rule", su.b_rule);
  o.set("b_all", num(b.value));
  o.set("b_all_err", num(b.err));
  o.set("b_all_note", "Aki's b of every event that is not a mainshock, mu >= b_mu_min");
  o.set("distance_band", static_cast<std::int64_t>(s.spacetime().band_width()));
  if (su.geometry.lattice())
    o.set("distance",
          "Euclidean between trigger sites (x, y) in site spacings, the shorter "
          "way round along a periodic axis");
  o.set("mainshocks", s.spacetime().mainshocks());
  return o;
}

// seismicity.json's provenance section.
Json provenance_json(const Setup& su) {
  Json p = Json::object();
  p.set("version", kVersion);
  p.set("git", kGitRevision);
  p.set("seed", su.scene ? Json::string(su.scene->text(key::run_seed)) : Json::null());
  p.set("scene", su.scene ? Json::string(su.scene->origin) : Json::null());
  p.set("lines", Json::strings(su.comments));
  return p;
}

// seismicity.json's Omori sections: the aftershocks' and the foreshocks' rates.
void set_omori(Json& j, const seis::Seismicity& s) {
  Json om = omori_json(s.aftershocks(), s.omori().after().sequences, true);
  om.set("method",
         "Ogata (1983) maximum likelihood of mu + K/(t + c)^p on the stacked sequences, times "
         "in 10 log bins a decade up to fit_t_max (a tenth of the mean sequence window, short "
         "against the loading cycle), each sequence's window from its mainshock to the next "
         "mainshock (or the catalogue's end); errors from the expected Fisher information; "
         "an excess needs 2 dlnL > 16.27 over the background alone");
  j.set("omori", std::move(om));
  j.set("foreshock", omori_json(s.foreshocks(), s.omori().before().sequences, false));
}

// seismicity.json, whole.
std::string seismicity_json(const seis::Seismicity& s, const Setup& su,
                            const SeismicityReport& rep) {
  Json j = Json::object();
  j.set("input", rep.catalog);
  j.set("clock", rep.clock);
  j.set("events", s.events());
  j.set("blocks", static_cast<std::int64_t>(su.blocks));
  j.set("blocks_from", rep.blocks_from);
  if (su.geometry.lattice()) {
    j.set("rows", static_cast<std::int64_t>(su.geometry.ny));
    j.set("rows_from", su.rows_from);
    j.set("periodic_x", su.geometry.periodic_x);
    j.set("periodic_y", su.geometry.periodic_y);
  }
  Json main = Json::object();
  main.set("rule", su.opt.mainshock.describe());
  main.set("count", s.mainshocks());
  main.set("min_mu", num_or_null(s.mainshocks() > 0, s.min_mainshock_mu()));
  j.set("mainshocks", std::move(main));
  j.set("interevent", interevent_json(s));
  Json rec = intervals_json(s.recurrence().system(), s.weibull(), s.lognormal());
  rec.set("per_block",
          intervals_json(s.recurrence().per_block(), s.block_weibull(), s.block_lognormal()));
  j.set("recurrence", std::move(rec));
  set_omori(j, s);
  j.set("bath", bath_json(s));
  j.set("moment_budget", num(s.moment_rate().budget(su.geometry.sites())));
  j.set("scaling", scaling_json(s));
  j.set("spacetime", spacetime_json(s, su));
  j.set("provenance", provenance_json(su));
  return j.str();
}

// The files, under the lock taken before: seismicity/ replaced as a whole (or --out's
// files). Returns where they went.
std::string write_all(const SeismicityRequest& req, const Setup& su, const seis::Seismicity& s,
                      const std::string& json) {
  if (!req.out.empty()) {
    write_outputs(req.out, s, su.comments, json);
    return req.out;
  }
  const fs::path final_dir = su.folder / kOutFolder;
  const fs::path tmp = su.folder / (kNewPrefix + std::to_string(::getpid()));
  std::error_code ec;
  fs::create_directory(tmp, ec);
  if (ec) throw Error("seismicity: cannot create " + tmp.string() + ": " + ec.message());
  try {
    write_outputs(tmp, s, su.comments, json);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  swap_in(tmp, final_dir);
  return final_dir.string();
}

// The printout's waiting times and mainshock recurrence.
void log_intervals(std::ostream& log, const seis::Seismicity& s) {
  char line[512];
  const auto& ie = s.interevent().all().moments;
  std::snprintf(line, sizeof line,
                "  %lld events, %lld mainshocks (smallest mu %.4g)\n"
                "  waiting times: mean %.6g, COV %.4f +- %.4f (Poisson: 1)\n",
                static_cast<long long>(s.events()), static_cast<long long>(s.mainshocks()),
                s.min_mainshock_mu(), ie.mean(), ie.cov(), ie.cov_err());
  log << line;
  const auto& rs = s.recurrence().system().moments;
  if (rs.n() > 0) {
    std::snprintf(line, sizeof line, "  mainshock recurrence: mean %.6g, COV %.4f", rs.mean(),
                  rs.cov());
    log << line;
    if (s.weibull().ok)
      log << ", Weibull k = " << format_with_error(s.weibull().k.value, s.weibull().k.err);
    log << "\n";
  }
}

// The printout's sequences (aftershocks, foreshocks, Båth), the budget and the files.
void log_sequences(std::ostream& log, const seis::Seismicity& s, int sites,
                   const SeismicityRequest& req, const SeismicityReport& rep) {
  char line[512];
  const auto& af = s.aftershocks();
  if (af.excess)
    log << "  aftershocks: Omori-Utsu p = " << format_with_error(af.p.value, af.p.err)
        << ", c = " << format_real(af.c.value) << ", " << format_real(af.excess_events)
        << " events above the background\n";
  else
    log << "  aftershocks: " << af.note << "\n";
  const auto& fo = s.foreshocks();
  if (fo.excess)
    log << "  foreshocks: inverse Omori p = " << format_with_error(fo.p.value, fo.p.err) << "\n";
  else
    log << "  foreshocks: " << fo.note << "\n";
  if (s.bath().sequences > 0) {
    std::snprintf(line, sizeof line,
                  "  Båth: delta_mu = %.4f (in ln M), delta_Mw = %.4f (in Mw), %lld sequences\n",
                  s.bath().delta_mu, s.bath().delta_mw(),
                  static_cast<long long>(s.bath().sequences));
    log << line;
  }
  std::snprintf(line, sizeof line, "  moment budget %.5f (1 when the chain slips as loaded)\n",
                s.moment_rate().budget(sites));
  log << line << "  written " << rep.out << " in " << format_real(rep.seconds) << " s\n";
  if (!req.export_file.empty()) log << "  exported " << req.export_file << "\n";
}

}  // namespace

SeismicityReport seismicity_of(const SeismicityRequest& req, std::ostream& log) {
  const auto t_start = std::chrono::steady_clock::now();
  SeismicityReport rep;
  Setup su = prepare(req, rep);
  CatalogReader reader(rep.catalog);
  if (su.writer) reader.set_growing();
  check_columns(reader, req, rep.catalog);
  choose_options(req, su);
  log_setup(log, su, rep);
  su.comments = comments_of(su.scene, rep.catalog);

  seis::Seismicity s(su.opt);
  read_events(reader, su, req, rep, s);
  rep.json = seismicity_json(s, su, rep);
  rep.out = write_all(req, su, s, rep.json);
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  log_intervals(log, s);
  log_sequences(log, s, su.geometry.sites(), req, rep);
  return rep;
}

}  // namespace bkq
