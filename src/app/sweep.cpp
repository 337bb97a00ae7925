// The sweep (see sweep.hpp). Every rank reads the sweep file and knows every task (point p,
// replica r: task p * replicas + r); rank 0 alone owns the sweep folder: it takes the lock,
// decides what is left to do, hands the tasks out slowest first, merges a point once its
// replicas are in, and writes point.json, sweep.csv and the progress lines. A replica's
// folder is written only by the rank that runs it.
#include "app/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

#include "app/merge.hpp"
#include "app/run.hpp"
#include "app/sweep_comm.hpp"
#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/checkpoint.hpp"
#include "io/folder_lock.hpp"
#include "io/ini.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/scene_keys.hpp"
#include "io/settings.hpp"
#include "stats/gutenberg_richter.hpp"

namespace bkq {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

std::string padded(std::size_t i, std::size_t count, int min_width) {
  int width = 1;
  for (std::size_t n = count > 0 ? count - 1 : 0; n >= 10; n /= 10) ++width;
  width = std::max(width, min_width);
  std::string s = std::to_string(i);
  return std::string(width > static_cast<int>(s.size()) ? width - s.size() : 0, '0') + s;
}

std::string duration_text(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const long long t = std::llround(s);
  char buf[48];
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%lldh%02lldm", t / 3600, (t / 60) % 60);
  else if (t >= 60)
    std::snprintf(buf, sizeof buf, "%lldm%02llds", t / 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%llds", t);
  return buf;
}

// A CSV field: as it is, or double-quoted (quotes doubled) when it holds , " or a newline.
std::string sweep_csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c == '\n' ? ' ' : c;
  }
  return q + "\"";
}

// A number from a JSON file, empty when absent or unreadable.
std::optional<double> json_number(const fs::path& file, const std::string& key) {
  try {
    return read_json_number(file, key);
  } catch (const Error&) {
    return std::nullopt;
  }
}

// Whether a replica's run finished (summary.json with status finished); an interrupted or
// unreadable summary is not finished: the replica is continued or run again.
bool finished_run(const fs::path& dir) {
  try {
    return run_status(dir) == RunStatus::Finished;
  } catch (const Error&) {
    return false;
  }
}

// The string value of a top-level "key" of a JSON file, for point.json's status and error;
// empty when absent or unreadable.
std::optional<std::string> json_string(const fs::path& file, const std::string& key) {
  try {
    return json_top_level_string(read_text_file(file.string(), "JSON file"), key, file.string());
  } catch (const Error&) {
    return std::nullopt;
  }
}

// What a point came to.
struct PointResult {
  enum class State { Pending, Ok, Failed } state = State::Pending;
  std::string error;
  std::int64_t events = 0;
  std::optional<double> b, b_err, b_sys_err, mu_min, mu_max;
  double seconds = 0;
};

class Sweep {
 public:
  Sweep(const SweepRequest& req, SweepSpec spec)
      : req_(req), spec_(std::move(spec)), points_(spec_.point_count()), out_(req.out_dir) {
    seed_swept_ = std::any_of(spec_.keys.begin(), spec_.keys.end(),
                              [](const SweptKey& k) { return k.key == key::run_seed.name; });
    results_.resize(points_);
    replica_done_.assign(points_, 0);
    replica_error_.resize(points_);
    replica_seconds_.assign(points_, 0.0);
  }

  std::size_t tasks() const { return points_ * spec_.replicas; }
  void set_ranks(int n) { ranks_ = n; }

  fs::path point_dir(std::size_t p) const {
    return out_ / "points" / ("p" + padded(p, points_, 4));
  }
  fs::path replica_dir(std::size_t p, int r) const {
    return point_dir(p) / ("r" + padded(r, spec_.replicas, 2));
  }

  // Rank 0, before anything runs: the lock, the folder's state, sweep.ini; returns the
  // tasks left in the order they are handed out.
  std::vector<int> prepare() {
    fs::create_directories(out_);
    // The folder's lock (io/folder_lock): a second sweep on it is refused; --resume takes
    // over the lock of a killed sweep of this host.
    lock_ = std::make_unique<FolderLock>(
        out_.string(), "sweep",
        req_.resume || req_.force ? StaleLock::TakeOver : StaleLock::Refuse);
    const fs::path ini = out_ / "sweep.ini";
    const std::string plan = plan_text();
    if (req_.force) {  // the folder rule's --force: what an earlier sweep wrote goes
      std::error_code ec;
      for (const char* name : {"points", "sweep.csv", "sweep.ini"}) fs::remove_all(out_ / name, ec);
    } else if (!req_.resume && !fs::exists(ini)) {
      // The folder rule: a new sweep starts in a new or empty folder (hidden files and the
      // lock do not count).
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(out_)) {
        const std::string name = e.path().filename().string();
        if (!name.empty() && name[0] != '.' && name != FolderLock::kFileName) found.push_back(name);
      }
      if (!found.empty())
        throw Error("output folder '" + out_.string() + "' already holds files (" +
                    quote_printable(found.front()) + (found.size() > 1 ? ", ..." : "") +
                    "); choose a new or empty folder, or use --force to write over them");
    }
    if (fs::exists(ini)) {
      if (!req_.resume)
        throw Error("output folder '" + out_.string() +
                    "' holds a sweep (sweep.ini); use --resume to finish it, --force to run it "
                    "again from the start, or another --out");
      const std::string old = read_text_file(ini.string(), "sweep file");
      if (plan_of(old) != plan_of(plan) && !extends(old))
        throw Error("--resume: '" + ini.string() +
                    "' describes another sweep (other points, scenes or replicas); resume with "
                    "the same sweep file and --set options, or with a larger run.events or "
                    "run.duration alone to extend it");
    } else if (req_.resume) {
      throw Error("--resume: output folder '" + out_.string() +
                  "' holds no sweep (no sweep.ini): nothing to continue");
    }
    if (req_.resume) remove_temporaries();
    write_file_atomic(ini.string(), provenance() + plan);

    std::vector<int> order;
    for (std::size_t p = 0; p < points_; ++p) {
      // A point with a replica shorter than the point now asks, or one whose extension was
      // interrupted (a checkpoint), is merged again once the replica is done.
      bool grown = false;
      for (int r = 0; req_.resume && r < spec_.replicas; ++r)
        grown = grown || shorter(p, r) || CheckpointFiles(replica_dir(p, r).string()).exist();
      if (req_.resume && !grown && load_point(p)) continue;
      for (int r = 0; r < spec_.replicas; ++r) {
        if (req_.resume && finished_run(replica_dir(p, r)) && !shorter(p, r)) {
          note_replica(p, TaskResult{task_of(p, r), 0, replica_seconds(p, r, 0), ""});
          continue;
        }
        order.push_back(task_of(p, r));
      }
      if (replica_done_[p] == spec_.replicas) finish_point(p);
    }
    // Slowest first where the cost is predictable (events x blocks, or steps x blocks);
    // equal costs keep the file's order.
    std::vector<double> costs(points_);
    for (std::size_t p = 0; p < points_; ++p) costs[p] = cost(p);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return costs[static_cast<std::size_t>(a / spec_.replicas)] >
             costs[static_cast<std::size_t>(b / spec_.replicas)];
    });
    left_ = order.size();
    skipped_ = tasks() - order.size();
    write_csv();
    return order;
  }

  // Any rank: runs one replica into its folder.
  TaskResult run_task(int task) const {
    const std::size_t p = static_cast<std::size_t>(task) / spec_.replicas;
    const int r = task % spec_.replicas;
    const auto t0 = Clock::now();
    TaskResult res{task, 0, 0, ""};
    try {
      Scene scene = spec_.point(p).scene;
      const auto seed = sweep_seed(scene_values(scene).run.seed, seed_swept_, p, spec_.replicas, r);
      scene.set(key::run_seed, std::to_string(seed), "sweep");
      scene.origin =
          spec_.origin + ", point " + std::to_string(p) + ", replica " + std::to_string(r);
      scene.validate();
      RunRequest run;
      run.scene = scene;
      run.out_dir = replica_dir(p, r).string();
      run.quiet = true;
      const CheckpointFiles files(run.out_dir);
      // An interrupted replica continues from its checkpoint; a finished one is handed out
      // only to be extended (shorter than its point now asks), from its final state.
      if (files.exist() || (finished_run(run.out_dir) && files.final_exists()))
        run.resume = true;
      else
        run.force = true;  // nothing to continue: start the replica over
      const int rc = run_scene(run);
      if (rc != 0) {
        res.status = rc;
        res.error = "stopped by a signal (exit " + std::to_string(rc) + ")";
      }
      if (!spec_.keep_catalog && rc == 0) fs::remove(replica_dir(p, r) / "catalog.csv");
    } catch (const std::exception& e) {
      res.status = 1;
      res.error = e.what();
    }
    const double measured = std::chrono::duration<double>(Clock::now() - t0).count();
    res.seconds = res.status == 0 ? replica_seconds(p, r, measured) : measured;
    return res;
  }

  // Rank 0: a replica's result came in. Returns false to stop handing out tasks.
  bool on_result(const TaskResult& r) {
    const std::size_t p = static_cast<std::size_t>(r.task) / spec_.replicas;
    --left_;
    if (r.status >= 128) {
      interrupted_ = r.status;
      std::fprintf(stderr, "bkquake: sweep: point %zu replica %d %s; the sweep stops\n", p,
                   r.task % spec_.replicas, r.error.c_str());
      return false;
    }
    note_replica(p, r);
    if (replica_done_[p] == spec_.replicas) {
      finish_point(p);
      // At most once a second (each write is synced to disk), and always at the end.
      if (Clock::now() - last_csv_ >= std::chrono::seconds(1)) write_csv();
    }
    progress(false);
    return true;
  }

  // Rank 0, at the end: sweep.csv, the failures, the exit status.
  int finish(const DispatchStats& stats, const std::string& ranks, int size) {
    write_csv();
    if (interrupted_)
      std::fprintf(stderr,
                   "bkquake: sweep: stopped; the same command with --resume continues it\n");
    else
      progress(true);
    int failed = 0;
    for (std::size_t p = 0; p < points_; ++p)
      if (results_[p].state == PointResult::State::Failed) {
        ++failed;
        std::fprintf(stderr, "bkquake: sweep: point %zu (%s) failed: %s\n", p,
                     point_label(p).c_str(), results_[p].error.c_str());
      }
    std::printf(
        "bkquake %s sweep: %zu points x %d replicas on %s in %.3g s; %d failed; sweep.csv in "
        "%s/\n",
        kVersion, points_, spec_.replicas, ranks.c_str(), stats.dispatch_seconds, failed,
        out_.string().c_str());
    if (size > 1)
      std::printf(
          "  dispatcher: %lld messages for %d tasks run by other ranks (2 per task + 2 per "
          "rank to start and stop), idle at the end %.3g rank-seconds\n",
          stats.messages, stats.remote_tasks, stats.idle_at_end_seconds);
    std::fflush(stdout);
    if (interrupted_) return interrupted_;
    return failed ? kExitSweepFailures : 0;
  }

 private:
  // A sweep killed while writing a file atomically leaves its temporary (io/output.hpp,
  // is_write_temporary) beside it; the file itself is either old or new, so the temporary goes.
  void remove_temporaries() const {
    std::vector<fs::path> stale;
    for (const auto& e : fs::recursive_directory_iterator(out_))
      if (e.is_regular_file() && is_write_temporary(e.path().filename().string()))
        stale.push_back(e.path());
    for (const auto& f : stale) fs::remove(f);
  }

  int task_of(std::size_t p, int r) const { return static_cast<int>(p) * spec_.replicas + r; }

  double cost(std::size_t p) const {
    const Scene s = spec_.point(p).scene;
    // A lattice's cost grows with its sites, blocks times rows.
    const SceneValues v = scene_values(s);
    const double blocks = static_cast<double>(v.model.blocks) * static_cast<double>(v.model.rows);
    if (v.drive.mode == DriveMode::Events)
      return blocks * static_cast<double>(v.run.events + v.run.transient_events);
    return blocks * v.run.duration / v.integrator.dt;
  }

  double replica_seconds(std::size_t p, int r, double fallback) const {
    const fs::path s = replica_dir(p, r) / "summary.json";
    if (auto v = json_number(s, "wall_seconds_total")) return *v;
    if (auto v = json_number(s, "wall_seconds")) return *v;
    return fallback;
  }

  void note_replica(std::size_t p, const TaskResult& r) {
    ++replica_done_[p];
    replica_seconds_[p] += r.seconds;
    if (r.status != 0 && replica_error_[p].empty())
      replica_error_[p] = "replica " + std::to_string(r.task % spec_.replicas) + ": " + r.error;
  }

  std::string point_label(std::size_t p) const {
    std::string s;
    for (const auto& [k, v] : spec_.point_values(p)) s += (s.empty() ? "" : ", ") + k + " = " + v;
    return s;
  }

  // A point whose every replica is in: merge (event runs) and point.json.
  void finish_point(std::size_t p) {
    PointResult& res = results_[p];
    res.seconds = replica_seconds_[p];
    res.error = replica_error_[p];
    res.state = res.error.empty() ? PointResult::State::Ok : PointResult::State::Failed;
    const Scene scene = spec_.point(p).scene;
    // Event runs, and continuous runs with slip episodes, write histogram.csv: merged.
    if (res.state == PointResult::State::Ok && fs::exists(replica_dir(p, 0) / "histogram.csv")) {
      try {
        MergeRequest m;
        for (int r = 0; r < spec_.replicas; ++r) m.runs.push_back(replica_dir(p, r).string());
        m.out = point_dir(p);
        m.force = true;  // a merge cut short by a kill is done again
        const StatsSettings stats = scene_values(scene).stats;
        m.mu_min = stats.mu_min;
        m.mu_max = stats.mu_max;
        std::ostringstream ignored;
        merge_runs(m, ignored);
        const fs::path s = point_dir(p) / "summary.json";
        res.events = static_cast<std::int64_t>(json_number(s, "events").value_or(0));
        res.b = json_number(s, "b_mle");
        res.b_err = json_number(s, "b_mle_err");
        res.b_sys_err = json_number(s, "b_mle_sys_err");
        res.mu_min = json_number(s, "mu_min");
        res.mu_max = json_number(s, "mu_max");
        if (!spec_.keep_histogram)
          for (int r = 0; r < spec_.replicas; ++r) fs::remove(replica_dir(p, r) / "histogram.csv");
      } catch (const std::exception& e) {
        res.state = PointResult::State::Failed;
        res.error = std::string("merge: ") + e.what();
      }
    } else if (res.state == PointResult::State::Ok) {
      for (int r = 0; r < spec_.replicas; ++r)
        res.events += static_cast<std::int64_t>(
            json_number(replica_dir(p, r) / "summary.json", "events").value_or(0));
    }
    Json j = Json::object();
    j.set("point", static_cast<std::int64_t>(p));
    j.set("status", res.state == PointResult::State::Ok ? "ok" : "failed");
    Json values = Json::object();
    for (const auto& [k, v] : spec_.point_values(p)) values.set(k, v);
    j.set("values", std::move(values));
    j.set("replicas", spec_.replicas);
    j.set("events", res.events);
    j.set("b", Json::number(res.b.value_or(NAN)));
    j.set("b_err", Json::number(res.b_err.value_or(NAN)));
    j.set("b_sys_err", Json::number(res.b_sys_err.value_or(NAN)));
    j.set("mu_min", Json::number(res.mu_min.value_or(NAN)));
    j.set("mu_max", Json::number(res.mu_max.value_or(NAN)));
    j.set("run_seconds", res.seconds);
    j.set("error", res.error);
    fs::create_directories(point_dir(p));
    write_file_atomic((point_dir(p) / "point.json").string(), j.str() + "\n");
  }

  // --resume: a point finished before (point.json says ok) is taken as it is.
  bool load_point(std::size_t p) {
    const fs::path f = point_dir(p) / "point.json";
    if (json_string(f, "status").value_or("") != "ok") return false;
    PointResult& res = results_[p];
    res.state = PointResult::State::Ok;
    res.events = static_cast<std::int64_t>(json_number(f, "events").value_or(0));
    res.b = json_number(f, "b");
    res.b_err = json_number(f, "b_err");
    res.b_sys_err = json_number(f, "b_sys_err");
    res.mu_min = json_number(f, "mu_min");
    res.mu_max = json_number(f, "mu_max");
    res.seconds = json_number(f, "run_seconds").value_or(0);
    replica_done_[p] = spec_.replicas;
    return true;
  }

  void write_csv() {
    last_csv_ = Clock::now();
    std::vector<std::string> header;
    for (const auto& c : sweep_csv_schema()) {
      header.push_back(c.name);
      if (c.name == std::string(sweep_col::point))
        for (const auto& k : spec_.keys) header.push_back(k.key);
    }
    std::ostringstream out;
    auto row = [&out](const std::vector<std::string>& fields) {
      for (std::size_t i = 0; i < fields.size(); ++i) out << (i ? "," : "") << fields[i];
      out << '\n';
    };
    row(header);
    auto num = [](const std::optional<double>& x) { return x ? format_real(*x) : std::string(); };
    for (std::size_t p = 0; p < points_; ++p) {
      const PointResult& r = results_[p];
      const bool have = r.state != PointResult::State::Pending;
      std::vector<std::string> f{std::to_string(p)};
      for (const auto& [k, v] : spec_.point_values(p)) f.push_back(sweep_csv_field(v));
      f.push_back(r.state == PointResult::State::Ok       ? "ok"
                  : r.state == PointResult::State::Failed ? "failed"
                                                          : "pending");
      f.push_back(have ? std::to_string(spec_.replicas) : "");
      f.push_back(have ? std::to_string(r.events) : "");
      f.push_back(num(r.b));
      f.push_back(num(r.b_err));
      f.push_back(num(r.b_sys_err));
      f.push_back(num(r.b ? std::optional<double>(b_moment_magnitude(*r.b)) : std::nullopt));
      f.push_back(num(r.mu_min));
      f.push_back(num(r.mu_max));
      f.push_back(have ? format_real(r.seconds) : "");
      f.push_back(sweep_csv_field(r.error));
      row(f);
    }
    write_file_atomic((out_ / "sweep.csv").string(), out.str());
  }

  void progress(bool final) {
    const auto now = Clock::now();
    if (!final && (left_ == 0 || now - last_progress_ < std::chrono::seconds(1))) return;
    last_progress_ = now;
    std::size_t done = 0, failed = 0;
    for (const auto& r : results_) {
      done += r.state != PointResult::State::Pending;
      failed += r.state == PointResult::State::Failed;
    }
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const std::size_t ran = tasks() - skipped_ - left_;
    // Every rank is busy while tasks remain (the hand-out is dynamic), so the ETA is the
    // time per task so far times the tasks left.
    const double eta = ran > 0 ? elapsed / static_cast<double>(ran) * left_ : NAN;
    const std::size_t running = std::min(left_, static_cast<std::size_t>(ranks_));
    std::fprintf(stderr,
                 "sweep: points %zu/%zu done (%zu failed); replicas %zu done, %zu running, %zu "
                 "left; elapsed %s, ETA %s\n",
                 done, points_, failed, tasks() - left_, running, left_ - running,
                 duration_text(elapsed).c_str(), left_ == 0 ? "0s" : duration_text(eta).c_str());
    std::fflush(stderr);
  }

  std::string provenance() const {
    std::string s = "# bkquake " + std::string(kVersion) + " (git " + kGitRevision +
                    ") sweep, written " + utc_now_iso() + "\n";
    return s;
  }

  // The sweep as run: the file and the overrides, then the points' effective values (what
  // --resume compares).
  std::string plan_text() const {
    std::string s = "# sweep file " + spec_.origin + "\n";
    for (const auto& o : req_.overrides) s += "# --set " + o + "\n";
    s += spec_.text;
    if (!s.empty() && s.back() != '\n') s += '\n';
    s += "# points: " + std::to_string(points_) + " x " + std::to_string(spec_.replicas) +
         " replicas\n";
    for (std::size_t p = 0; p < points_; ++p) s += point_line(p, spec_.point(p).scene);
    return s;
  }
  std::string point_line(std::size_t p, const Scene& scene) const {
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(scene.hash()));
    return "# point " + std::to_string(p) + ": " + point_label(p) + " (scene hash " + hash + ")\n";
  }

  // The key that says how long a point's runs are.
  static Key length_key(const Scene& scene) {
    return scene_values(scene).drive.mode == DriveMode::Events ? key::run_events
                                                               : key::run_duration;
  }
  // The run length a replica was made for (its scene.ini), none when it has no readable one.
  std::optional<std::string> replica_length(std::size_t p, int r) const {
    const fs::path ini = replica_dir(p, r) / "scene.ini";
    try {
      if (!fs::exists(ini)) return std::nullopt;
      const Scene s = Scene::from_text(read_text_file(ini.string(), "scene file"), ini.string());
      return s.text(length_key(s));
    } catch (const Error&) {
      return std::nullopt;
    }
  }
  // Was replica r of point p made shorter than the point now asks (to be extended)?
  bool shorter(std::size_t p, int r) const {
    const Scene scene = spec_.point(p).scene;
    const auto length = replica_length(p, r);
    return length && *length != scene.text(length_key(scene));
  }
  // --resume with a plan that differs from `old` only in the points' run.events or
  // run.duration: true when every point's scene, with its replicas' length put back, is
  // the one `old` planned. A length that shrank, or replicas whose catalogues were not
  // collected (their runs cannot continue), is refused in one line.
  bool extends(const std::string& old) const {
    std::istringstream in(plan_of(old));
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line + "\n");
    std::istringstream now(plan_of(plan_text()));
    std::string head;
    std::getline(now, head);  // "# points: P x R replicas"
    if (lines.size() != points_ + 1 || lines[0] != head + "\n") return false;
    bool grows = false;
    for (std::size_t p = 0; p < points_; ++p) {
      const Scene scene = spec_.point(p).scene;
      const std::string key = length_key(scene);
      std::optional<std::string> length;
      for (int r = 0; !length && r < spec_.replicas; ++r) length = replica_length(p, r);
      Scene before = scene;
      if (length) before.set(key, *length, "the sweep as run before");
      if (lines[p + 1] != point_line(p, before)) return false;
      if (!length || *length == scene.text(key)) continue;
      const SceneValues now = scene_values(scene), then = scene_values(before);
      const bool longer = now.drive.mode == DriveMode::Events
                              ? now.run.events > then.run.events
                              : now.run.duration > then.run.duration;
      if (!longer)
        throw Error("--resume: point " + std::to_string(p) + " (" + point_label(p) + "): " + key +
                    " = " + scene.text(key) + " would not extend its replicas' " + *length +
                    " (allowed: more than " + *length + ")");
      if (!spec_.keep_catalog && settings_from_scene(scene).output.catalog == CatalogFormat::Csv)
        throw Error("--resume: " + std::string(key) + " = " + scene.text(key) +
                    ": the replicas' catalogues were not collected (sweep.collect), so their "
                    "runs cannot be extended; allowed: the sweep's own " +
                    key + " = " + *length + ", or --force to run it again");
      grows = true;
    }
    return grows;
  }
  // The lines of a plan that must match for --resume: the point lines.
  static std::string plan_of(const std::string& text) {
    std::string out, line;
    std::istringstream in(text);
    while (std::getline(in, line))
      if (line.rfind("# point", 0) == 0) out += line + "\n";
    return out;
  }

  const SweepRequest& req_;
  SweepSpec spec_;
  std::size_t points_ = 0;  // spec_.point_count(): points are made on demand
  fs::path out_;
  bool seed_swept_ = false;
  std::unique_ptr<FolderLock> lock_;
  std::vector<PointResult> results_;
  std::vector<int> replica_done_;
  std::vector<std::string> replica_error_;
  std::vector<double> replica_seconds_;
  std::size_t left_ = 0, skipped_ = 0;
  int interrupted_ = 0;  // the exit status of a replica stopped by a signal
  int ranks_ = 1;
  Clock::time_point start_ = Clock::now(), last_progress_{}, last_csv_{};
};

}  // namespace

std::uint64_t sweep_seed(std::uint64_t point_seed, bool seed_swept, std::size_t point, int replicas,
                         int replica) {
  constexpr std::uint64_t kMask = (std::uint64_t{1} << 63) - 1;
  const std::uint64_t offset =
      (seed_swept ? 0 : static_cast<std::uint64_t>(point) * static_cast<std::uint64_t>(replicas)) +
      static_cast<std::uint64_t>(replica);
  return (point_seed + offset) & kMask;
}

int run_sweep(const SweepRequest& req) {
  std::string ranks;
  const std::unique_ptr<SweepComm> comm = make_sweep_comm(ranks);
  Sweep sweep(req, read_sweep_file(req.sweep_file, req.overrides));
  std::vector<int> order;
  std::string error;
  sweep.set_ranks(comm->size());
  if (comm->rank() == 0) {
    try {
      order = sweep.prepare();
    } catch (const Error& e) {
      error = e.what();
    }
  }
  if (!comm->agree(error.empty())) {
    if (comm->rank() == 0) throw Error(error);
    return kExitBadInput;
  }
  if (comm->rank() == 0) {
    std::fprintf(stderr, "sweep: %zu tasks to run on %s\n", order.size(), ranks.c_str());
    std::fflush(stderr);
  }
  const DispatchStats stats = comm->dispatch(
      order, [&](int task) { return sweep.run_task(task); },
      [&](const TaskResult& r) { return sweep.on_result(r); });
  if (comm->rank() != 0) return 0;
  return sweep.finish(stats, ranks, comm->size());
}

}  // namespace bkq
