// From an effective scene to a finished output folder: builds the model, the stepper and
// the driver the scene asks for, streams the outputs, and writes the provenance
// (scene.ini first, summary.json last, so a folder with summary.json is a finished run).
// Event runs also write checkpoints (io/checkpoint.hpp) every run.checkpoint_events events
// or run.checkpoint_seconds seconds, on SIGINT/SIGTERM (then exit 130/143) and before a
// failed event propagates its error; --resume continues from the newest checkpoint after
// checking it against the scene and catalog.csv, so the outputs equal those of a run that
// never stopped, byte for byte.
#include "app/run.hpp"

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/progress.hpp"
#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "engine/continuous.hpp"
#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "integrate/stepper.hpp"
#include "io/catalog.hpp"
#include "io/checkpoint.hpp"
#include "io/histogram_csv.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Json provenance_json(const Scene& scene, const std::string& mode) {
  Json j = Json::object();
  j.set("version", kVersion);
  j.set("git_revision", kGitRevision);
  j.set("seed", static_cast<std::int64_t>(scene.integer("run.seed")));
  j.set("scene", scene.origin);
  j.set("scene_hash", std::to_string(scene.hash()));
  j.set("mode", mode);
  j.set("written", utc_now_iso());
  return j;
}

Substrate substrate_from_scene(const Scene& scene) {
  const std::string& schedule = scene.choice("drive.schedule");
  if (schedule == "steps")
    return Substrate::steps(scene.real("drive.speed"), scene.real("drive.step_increment"),
                            scene.real("drive.step_interval"));
  if (schedule == "ramp")
    return Substrate::ramp(scene.real("drive.ramp_from"), scene.real("drive.ramp_to"),
                           scene.real("drive.ramp_duration"));
  return Substrate::constant(scene.real("drive.speed"));
}

std::unique_ptr<Stepper> stepper_from_scene(const Scene& scene, int n) {
  return make_stepper(scene.choice("integrator.scheme"), n, scene.real("integrator.tolerance"));
}

// SIGINT and SIGTERM during an event run. The first asks the run to stop after the current
// event (checkpoint, flush, exit 128 + signal); a second one exits at once, leaving the
// last checkpoint intact (checkpoints are renamed into place atomically).
volatile std::sig_atomic_t g_stop_signal = 0;

void on_stop_signal(int sig) {
  if (g_stop_signal != 0) ::_exit(128 + sig);
  g_stop_signal = sig;
}

// Installs the handlers for its lifetime and restores the previous ones after.
class StopSignals {
 public:
  StopSignals() {
    g_stop_signal = 0;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // a write or fsync under way completes instead of failing with EINTR
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopSignals() {
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int received() const { return g_stop_signal; }

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

// An event-driven run, fresh or continued from a checkpoint: transient events, recorded
// events (catalog rows, histogram), periodic checkpoints, and the outputs at the end.
class EventRun {
 public:
  EventRun(const RunRequest& req, const OutputFolder& out, const ChainForces& forces,
           Stepper& stepper, double dt, const Checkpoint* resumed)
      : req_(req),
        scene_(req.scene),
        forces_(forces),
        dt_(dt),
        out_(out),
        files_(out.dir()),
        scene_ini_(req.scene.to_ini()),
        transient_(scene_.integer("run.transient_events")),
        events_(scene_.integer("run.events")),
        every_events_(scene_.integer("run.checkpoint_events")),
        every_seconds_(scene_.real("run.checkpoint_seconds")),
        hist_(scene_.real("stats.bin_width")) {
    if (resumed) {
      engine_ = std::make_unique<EventEngine>(forces, stepper, dt, resumed->engine);
      hist_ = MagnitudeHistogram::from_state(resumed->histogram);
      prog_ = resumed->progress;
      ++prog_.resumes;
    } else {
      engine_ = std::make_unique<EventEngine>(
          forces, stepper, dt,
          initial_state(forces, seed(), scene_.real("run.initial_disorder"), true));
      if (transient_ == 0) begin_recording();
    }
    engine_->max_steps_per_event = scene_.integer("run.max_steps_per_event");
    last_saved_ = engine_->snapshot();
    wall_total0_ = prog_.wall_total;
    wall_events0_ = prog_.wall_events;
    catalog_ =
        std::make_unique<CsvStream>(out.path("catalog.csv"), catalog_header(), resumed != nullptr);
  }

  // Returns the exit status: 0 when finished, 128 + signal when stopped by one.
  int run() {
    StopSignals signals;
    last_checkpoint_ = Clock::now();
    if (prog_.transient_done < transient_) {
      const std::int64_t start = prog_.transient_done;
      Progress progress(req_.quiet, "transient events", static_cast<double>(transient_ - start));
      while (prog_.transient_done < transient_ && !signals.received()) {
        next_event();
        if (++prog_.transient_done == transient_) begin_recording();
        progress.update(static_cast<double>(prog_.transient_done - start));
        checkpoint_if_due();
      }
      progress.finish(static_cast<double>(prog_.transient_done - start));
    }
    if (prog_.transient_done == transient_ && !signals.received()) {
      const std::int64_t start = prog_.events_done;
      Progress progress(req_.quiet, "events", static_cast<double>(events_ - start));
      while (prog_.events_done < events_ && !signals.received()) {
        EventRecord e = next_event();
        e.event = ++prog_.events_done;
        catalog_->row(catalog_row(e));
        prog_.moment_sum += e.moment;
        if (e.moment > 0) {
          hist_.add(e.magnitude);
        } else {
          ++prog_.nonpositive;
        }
        progress.update(static_cast<double>(prog_.events_done - start));
        checkpoint_if_due();
      }
      progress.finish(static_cast<double>(prog_.events_done - start));
    }
    if (const int sig = signals.received()) return stop(sig);
    return finish();
  }

 private:
  std::uint64_t seed() const { return static_cast<std::uint64_t>(scene_.integer("run.seed")); }

  void begin_recording() {
    prog_.load0 = engine_->load();
    prog_.counters0 = engine_->counters();
    recording_t0_ = Clock::now();
  }

  // The engine's next event; a failure in the middle of it (a non-finite state, a runaway)
  // saves the state before the event as the checkpoint, then propagates, saying where.
  EventRecord next_event() {
    const std::int64_t done = engine_->counters().events;
    try {
      return engine_->next_event();
    } catch (const Error& e) {
      throw Error(e.what() + save_before_failure(done));
    }
  }

  // The failed engine is unusable and copying the state before every event would cost a
  // few per cent, so the state before the failed event is recomputed once from the last
  // checkpoint (or the start): an engine continued from a snapshot repeats the same events
  // bit for bit. That costs at most one checkpoint interval. Returns the note for the error.
  std::string save_before_failure(std::int64_t events_done) {
    try {
      const std::unique_ptr<Stepper> stepper = stepper_from_scene(scene_, forces_.n());
      EventEngine replay(forces_, *stepper, dt_, last_saved_);
      replay.max_steps_per_event = engine_->max_steps_per_event;
      while (replay.counters().events < events_done) replay.next_event();
      save(replay.snapshot());
      return "; the state before this event is saved in '" + files_.current() + "'";
    } catch (const Error& e) {
      return std::string("; saving the state before this event failed: ") + e.what();
    }
  }

  void checkpoint_if_due() {
    const bool by_count = every_events_ > 0 && engine_->counters().events % every_events_ == 0;
    const bool by_time = every_seconds_ > 0 && seconds_since(last_checkpoint_) >= every_seconds_;
    if (by_count || by_time) save(engine_->snapshot());
  }

  // Writes a checkpoint of `engine` with the run as it stands; catalog.csv is synced first,
  // so the checkpoint never counts rows that are not on disk.
  void save(const EngineSnapshot& engine) {
    prog_.catalog_bytes = catalog_->sync();
    prog_.wall_total = wall_total0_ + seconds_since(session_t0_);
    if (prog_.transient_done == transient_)
      prog_.wall_events = wall_events0_ + seconds_since(recording_t0_);
    files_.write(Checkpoint{kVersion, kGitRevision, scene_.hash(), scene_ini_, seed(), prog_,
                            engine, hist_.state()});
    last_saved_ = engine;
    last_checkpoint_ = Clock::now();
  }

  int stop(int sig) {
    save(engine_->snapshot());
    catalog_->close();
    std::fprintf(stderr,
                 "bkquake: stopped by %s after %lld of %lld events (%lld of %lld transient); "
                 "checkpoint in '%s'; "
                 "to continue: bkquake run %s --out %s --resume\n",
                 sig == SIGINT ? "SIGINT" : "SIGTERM", static_cast<long long>(prog_.events_done),
                 static_cast<long long>(events_), static_cast<long long>(prog_.transient_done),
                 static_cast<long long>(transient_), files_.current().c_str(),
                 out_.path("scene.ini").c_str(), out_.dir().c_str());
    return 128 + sig;
  }

  int finish() {
    catalog_->close();
    const double wall = wall_events0_ + seconds_since(recording_t0_);
    const double wall_total = wall_total0_ + seconds_since(session_t0_);
    const int n = engine_->state().n();
    const double total_load = engine_->load() - prog_.load0;
    hist_.set_loading(total_load, n);
    write_file_atomic(out_.path("histogram.csv"), histogram_csv(hist_));

    const EngineCounters& c = engine_->counters();
    const EngineCounters& c0 = prog_.counters0;
    Json summary = provenance_json(scene_, "events");
    summary.set("events", events_);
    summary.set("transient_events", transient_);
    summary.set("blocks", n);
    summary.set("total_load", total_load);
    summary.set("moment_sum", prog_.moment_sum);
    summary.set("nonpositive_moments", prog_.nonpositive);
    summary.set("bin_width", hist_.bin_width());
    summary.set("wall_seconds", wall);
    summary.set("wall_seconds_total", wall_total);
    summary.set("events_per_second", wall > 0 ? events_ / wall : 0.0);
    summary.set("resumes", prog_.resumes);
    Json work = Json::object();
    work.set("steps", c.steps - c0.steps);
    work.set("block_steps", c.block_steps - c0.block_steps);
    work.set("sliding_block_steps", c.sliding_block_steps - c0.sliding_block_steps);
    summary.set("work", std::move(work));

    std::string fit_line = "b: not fitted (fewer than 2 events)";
    if (hist_.events() >= 2) {
      try {
        std::optional<double> mu_min = scene_.real_or_auto("stats.mu_min");
        std::optional<double> mu_max = scene_.real_or_auto("stats.mu_max");
        const GrFit fit = fit_histogram(hist_, mu_min, mu_max);
        summary.set("b_mle", fit.b_mle);
        summary.set("b_mle_err", fit.b_mle_err);
        summary.set("b_lsq", fit.b_lsq);
        summary.set("b_lsq_err", fit.b_lsq_err);
        Json window = Json::object();
        window.set("mu_min", fit.mu_min);
        window.set("mu_max", fit.mu_max);
        window.set("automatic", fit.window_auto);
        window.set("events", fit.n_in_window);
        window.set("ks_distance", fit.ks_distance);
        summary.set("fit_window", std::move(window));
        char line[200];
        std::snprintf(line, sizeof line,
                      "b = %.3f ± %.3f (binned MLE) on mu in [%.2f, %.2f], %lld events", fit.b_mle,
                      fit.b_mle_err, fit.mu_min, fit.mu_max,
                      static_cast<long long>(fit.n_in_window));
        fit_line = line;
      } catch (const Error& err) {
        fit_line = std::string("b: not fitted (") + err.what() + ")";
        summary.set("fit_error", err.what());
      }
    }
    write_file_atomic(out_.path("summary.json"), summary.str() + "\n");
    // summary.json marks the run finished; its checkpoints have served.
    files_.remove();

    std::printf("bkquake %s: %lld events (after %lld transient) in %.3g s, %.4g events/s\n",
                kVersion, static_cast<long long>(events_), static_cast<long long>(transient_), wall,
                wall > 0 ? events_ / wall : 0.0);
    std::printf("  total substrate displacement %.6g, magnitudes %.3g..%.3g\n", total_load,
                hist_.min_mu(), hist_.max_mu());
    std::printf("  %s\n  outputs in %s/\n", fit_line.c_str(), out_.dir().c_str());
    return 0;
  }

  const RunRequest& req_;
  const Scene& scene_;
  const ChainForces& forces_;
  const double dt_;
  const OutputFolder& out_;
  const CheckpointFiles files_;
  const std::string scene_ini_;
  const std::int64_t transient_, events_, every_events_;
  const double every_seconds_;

  std::unique_ptr<EventEngine> engine_;
  EngineSnapshot last_saved_;  // the engine at the last checkpoint, or at the start
  MagnitudeHistogram hist_;
  RunProgress prog_;
  std::unique_ptr<CsvStream> catalog_;

  // Wall time: this session's clocks on top of what earlier sessions (before a resume) spent.
  Clock::time_point session_t0_ = Clock::now(), recording_t0_ = session_t0_,
                    last_checkpoint_ = session_t0_;
  double wall_total0_ = 0, wall_events0_ = 0;
};

int run_continuous(const RunRequest& req, const OutputFolder& out, const ChainForces& forces,
                   Stepper& stepper, double dt) {
  const Scene& scene = req.scene;
  const ModelParams& p = forces.params();
  ContinuousDriver driver(
      forces, stepper, substrate_from_scene(scene),
      initial_state(forces, static_cast<std::uint64_t>(scene.integer("run.seed")),
                    scene.real("run.initial_disorder"), false),
      dt);
  const double duration = scene.real("run.duration");
  const double every = scene.real("output.every");
  const bool blocks = scene.flag("output.blocks");

  CsvStream series(out.path("timeseries.csv"),
                   "t,speed,substrate,pad_x,pad_v,pad_friction,sliding");
  CsvStream catalog(out.path("catalog.csv"), catalog_header());
  std::unique_ptr<CsvStream> trajectories;
  if (blocks) {
    std::string header = "t";
    for (int j = 0; j < p.n; ++j) {
      header += ",u";
      header += std::to_string(j);
    }
    trajectories = std::make_unique<CsvStream>(out.path("blocks.csv"), header);
  }
  auto sample = [&] {
    const ChainState& st = driver.state();
    const SubstrateState sub = driver.substrate();
    std::string row;
    for (double v : {st.t, sub.v, sub.s, st.x, st.xd, driver.pad_friction()}) {
      row += format_real(v);
      row += ',';
    }
    row += std::to_string(driver.sliding());
    series.row(row);
    if (trajectories) {
      row = format_real(st.t);
      for (int j = 0; j < p.n; ++j) {
        row += ',';
        row += format_real(driver.displacement(j));
      }
      trajectories->row(row);
    }
  };

  // Step count fixed up front so the end time does not depend on rounding of t += dt.
  const auto steps = static_cast<std::int64_t>(std::llround(std::ceil(duration / dt - 1e-9)));
  const auto t0 = Clock::now();
  Progress progress(req.quiet, "time", duration);
  double next_out = 0;
  std::int64_t episodes = 0;
  double friction_sum = 0, friction_sq = 0;
  std::int64_t samples = 0;
  for (std::int64_t i = 0; i <= steps; ++i) {
    if (driver.state().t >= next_out - 1e-9 * dt) {
      sample();
      const double f = driver.pad_friction();
      friction_sum += f;
      friction_sq += f * f;
      ++samples;
      next_out += every;
    }
    if (i == steps) break;
    driver.step();
    if (auto e = driver.finished_episode()) {
      ++episodes;
      catalog.row(catalog_row(*e));
    }
    if (!std::isfinite(driver.state().x) || !std::isfinite(driver.state().w[0])) {
      std::string msg = "non-finite state at time ";
      msg += format_real(driver.state().t);
      msg += ": the integration is unstable (reduce integrator.dt)";
      throw Error(msg);
    }
    progress.update(driver.state().t);
  }
  progress.finish(driver.state().t);
  series.close();
  catalog.close();
  if (trajectories) trajectories->close();
  const double wall = seconds_since(t0);

  Json summary = provenance_json(scene, "continuous");
  summary.set("duration", driver.state().t);
  summary.set("steps", steps);
  summary.set("blocks", p.n);
  summary.set("events", episodes);
  summary.set("total_load", driver.substrate().s);
  summary.set("wall_seconds", wall);
  summary.set("block_steps_per_second", wall > 0 ? static_cast<double>(steps) * p.n / wall : 0.0);
  const double mean = samples ? friction_sum / samples : 0.0;
  const double var = samples ? std::max(0.0, friction_sq / samples - mean * mean) : 0.0;
  summary.set("pad_friction_mean", mean);
  summary.set("pad_friction_amplitude", std::sqrt(2.0 * var));
  write_file_atomic(out.path("summary.json"), summary.str() + "\n");
  std::printf("bkquake %s: continuous run to t = %.6g (%lld steps) in %.3g s; %lld slip episodes\n",
              kVersion, driver.state().t, static_cast<long long>(steps), wall,
              static_cast<long long>(episodes));
  std::printf("  outputs in %s/\n", out.dir().c_str());
  return 0;
}

}  // namespace

int run_scene(const RunRequest& req) {
  const Scene& scene = req.scene;
  const ModelParams p = model_from_scene(scene);
  const ChainForces forces(p);
  const std::unique_ptr<Stepper> stepper = stepper_from_scene(scene, p.n);
  const double dt = scene.real("integrator.dt");
  check_time_step(*stepper, p, dt);
  const bool events = scene.choice("drive.mode") == "events";
  if (req.resume && !events)
    throw Error(
        "--resume: continuous runs (drive.mode = continuous) write no checkpoints yet; rerun "
        "without --resume");
  if (events) EventEngine::check_model(p);

  const OutputFolder out(req.out_dir, req.force, req.resume);
  const CheckpointFiles checkpoints(out.dir());
  if (req.resume) {
    if (std::filesystem::exists(out.path("summary.json")))
      throw Error("--resume: output folder '" + out.dir() +
                  "' holds a finished run (summary.json): nothing to continue; use --force to run "
                  "it again");
    // Everything is checked before anything is changed: a refused resume leaves the folder as it
    // was.
    std::string from;
    const Checkpoint saved = checkpoints.read(&from);
    check_checkpoint_matches(saved, scene, from);
    const std::string catalog = out.path("catalog.csv");
    check_csv_prefix(catalog, catalog_header(), saved.progress.events_done,
                     saved.progress.catalog_bytes);
    if (saved.git_revision != kGitRevision)
      std::fprintf(stderr,
                   "bkquake: warning: the checkpoint was written by git revision %s, this is %s; "
                   "the continuation "
                   "is exact only if the engine did not change in between\n",
                   saved.git_revision.c_str(), kGitRevision);
    // Rows written after the checkpoint are computed again, so they go.
    std::error_code ec;
    std::filesystem::resize_file(catalog, saved.progress.catalog_bytes, ec);
    if (ec) throw Error("cannot truncate '" + catalog + "' to its checkpoint: " + ec.message());
    std::printf(
        "bkquake: resuming '%s' from %s: %lld of %lld events done (%lld of %lld transient)\n",
        out.dir().c_str(), from.c_str(), static_cast<long long>(saved.progress.events_done),
        static_cast<long long>(scene.integer("run.events")),
        static_cast<long long>(saved.progress.transient_done),
        static_cast<long long>(scene.integer("run.transient_events")));
    std::fflush(stdout);
    return EventRun(req, out, forces, *stepper, dt, &saved).run();
  }

  if (checkpoints.exist() && !req.force)
    throw Error("output folder '" + out.dir() + "' holds an interrupted run (" +
                checkpoints.current() + "); use --resume to continue it or --force to start over");
  // A folder with summary.json is a finished run; overwriting one starts by unmarking it.
  if (req.force) {
    std::filesystem::remove(out.path("summary.json"));
    checkpoints.remove();
  }
  std::vector<std::string> header = provenance_lines(scene);
  write_file_atomic(out.path("scene.ini"), scene.to_ini(header));
  if (!events) return run_continuous(req, out, forces, *stepper, dt);
  return EventRun(req, out, forces, *stepper, dt, nullptr).run();
}

}  // namespace bkq
