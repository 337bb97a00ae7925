// The continuous-run loop; see continuous_run.hpp. The step count is fixed up front, so
// the end time does not depend on the rounding of t += dt; a sample is taken whenever t
// reaches the next multiple of output.every. The loop owns the driver, the run's
// bookkeeping (steps and episodes done, the next sample time, wall time over all
// sessions) and the checkpoint files; everything written is an observer's.
#include "app/continuous_run.hpp"

#include <signal.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/observers/accuracy_check.hpp"
#include "app/observers/catalog.hpp"
#include "app/observers/checkpoint_timer.hpp"
#include "app/observers/energy.hpp"
#include "app/observers/histogram.hpp"
#include "app/observers/progress.hpp"
#include "app/observers/segments.hpp"
#include "app/observers/summary.hpp"
#include "app/observers/timeseries.hpp"
#include "app/stability.hpp"
#include "app/stop_signals.hpp"
#include "app/wall_clock.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/continuous.hpp"
#include "engine/initial_state.hpp"
#include "io/catalog.hpp"
#include "io/checkpoint.hpp"
#include "io/energy_csv.hpp"
#include "io/output.hpp"
#include "io/timeseries.hpp"

namespace bkq {

namespace {

// The run's own named state in a checkpoint: what the driver holds besides the chain
// state (which goes into the checkpoint's engine.state, the steps and episodes done into
// engine.counters) and the next sample time.
constexpr const char* kContinuousStateName = "continuous";

void put_record(StateWriter& w, const EventRecord& e) {
  w.i64(e.event);
  w.f64(e.load);
  w.i64(e.trigger);
  w.i64(e.blocks);
  for (double x : {e.moment, e.magnitude, e.duration, e.max_speed, e.pad_displacement}) w.f64(x);
  w.i64(e.first_block);
  w.i64(e.last_block);
  w.f64(e.energy_residual);
}

EventRecord get_record(StateReader& r) {
  EventRecord e;
  e.event = r.i64();
  e.load = r.f64();
  e.trigger = static_cast<int>(r.i64());
  e.blocks = static_cast<int>(r.i64());
  for (double* x : {&e.moment, &e.magnitude, &e.duration, &e.max_speed, &e.pad_displacement})
    *x = r.f64();
  e.first_block = static_cast<int>(r.i64());
  e.last_block = static_cast<int>(r.i64());
  e.energy_residual = r.f64();
  return e;
}

std::string encode_state(const ContinuousSnapshot& d, double next_out) {
  StateWriter w;
  w.f64(next_out);
  w.i64(d.sliding);
  w.u32(d.in_episode ? 1 : 0);
  w.f64s(d.w_start);
  w.str(std::string(d.slid.begin(), d.slid.end()));
  put_record(w, d.episode);
  w.f64(d.episode_t0);
  w.f64(d.episode_x0);
  w.i64(d.episodes);
  w.f64s(d.stepper);
  for (double x : {d.energy.e0, d.energy.work, d.energy.dissipated}) w.f64(x);
  return std::move(w.bytes());
}

// The driver's snapshot from a checkpoint of a continuous run, and the next sample time.
ContinuousSnapshot decode_state(const Checkpoint& c, double& next_out) {
  const std::string* bytes = c.find(kContinuousStateName);
  if (!bytes)
    throw Error("--resume: the checkpoint holds no continuous-run state (it is an event run's)");
  StateReader r(*bytes, kContinuousStateName);
  ContinuousSnapshot d;
  d.state = c.engine.state;
  next_out = r.f64();
  d.sliding = static_cast<int>(r.i64());
  d.in_episode = r.u32() != 0;
  d.w_start = r.f64s();
  const std::string slid = r.str();
  d.slid.assign(slid.begin(), slid.end());
  d.episode = get_record(r);
  d.episode_t0 = r.f64();
  d.episode_x0 = r.f64();
  d.episodes = r.i64();
  d.stepper = r.f64s();
  for (double* x : {&d.energy.e0, &d.energy.work, &d.energy.dissipated}) *x = r.f64();
  if (!r.done()) throw Error("--resume: the checkpoint's continuous-run state is malformed");
  return d;
}

Sample sample_of(const ContinuousDriver& driver) {
  const ChainState& st = driver.state();
  const SubstrateState sub = driver.substrate();
  return {{st.t, sub.v, sub.s, st.x, st.xd, driver.pad_friction(), driver.sliding()}, driver};
}

class ContinuousRun {
 public:
  ContinuousRun(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                const ChainForces& forces, Stepper& stepper, const Checkpoint* resumed)
      : req_(req),
        settings_(settings),
        stepper_(stepper),
        out_(out),
        files_(out.dir()),
        dt_(settings.integrator.dt),
        duration_(settings.run.duration),
        every_(settings.output.every),
        steps_(continuous_steps(settings)) {
    const Substrate substrate = substrate_of(settings.drive);
    if (resumed) {
      driver_ = std::make_unique<ContinuousDriver>(forces, stepper, substrate,
                                                   decode_state(*resumed, next_out_), dt_);
      done_ = resumed->engine.counters.steps;
      // The checkpoint keeps the next sample's time (k * every, summed); a run stopped just
      // after writing sample k resumes with k + 1.
      next_sample_ = std::llround(next_out_ / every_);
      episodes_ = resumed->engine.counters.events;
      prog_ = resumed->progress;
      ++prog_.resumes;
    } else {
      driver_ = std::make_unique<ContinuousDriver>(
          forces, stepper, substrate,
          settings.run.start.equilibrium
              ? equilibrium_start(forces, settings)
              : initial_state(forces, settings.run.seed, settings.run.initial_disorder, false),
          dt_);
    }
    wall_.set_before(prog_.wall_total);
    attach_observers(resumed != nullptr, forces);
    if (resumed) observers_.resume(*resumed);
  }

  int run() {
    StopSignals signals;
    observers_.start();
    observers_.phase({"time", driver_->state().t, duration_});
    while (true) {
      if (sample_due()) {
        Sample sample = sample_of(*driver_);
        // On the stated grid: sample k is at t = k * output.every exactly (the state's own
        // time, summed step by step, drifts from it by rounding).
        if (steps_per_sample_ > 0) sample.values.t = static_cast<double>(next_sample_) * every_;
        observers_.sample(sample);
        next_out_ += every_;
        ++next_sample_;
      }
      if (done_ == steps_ || signals.received()) break;
      driver_->step();
      ++done_;
      if (auto e = driver_->finished_episode()) {
        ++episodes_;
        // A lattice of one column runs as the chain along y; its episodes are read as rows.
        if (settings_.lattice.nx == 1 && settings_.lattice.ny > 1) place_on_column(*e);
        observers_.event(*e);
      }
      if (!std::isfinite(driver_->state().x) || !std::isfinite(driver_->state().w[0])) {
        std::string msg = "non-finite state at time ";
        msg += format_real(driver_->state().t);
        msg += ": the integration is unstable (reduce integrator.dt)";
        throw Error(msg);
      }
      if (observers_.wants_steps()) observers_.step({done_, *driver_});
      observers_.advance({driver_->state().t, episodes_});
    }
    signals.stopping();
    observers_.phase_end({driver_->state().t, episodes_});
    if (const int sig = signals.received()) return stop(sig);
    // The final state, before the observers close their partial blocks (the last energy
    // window, the last speed segment): a later `--resume --set run.duration=T2` continues
    // from it as an interrupted run continues, those blocks still open. The periodic
    // checkpoints go only once summary.json says the run finished.
    save(true);
    accuracy_->set_run_energy_residual(driver_->energy_balance().residual(driver_->energy()));
    observers_.end(run_end(0));
    files_.remove_interim();
    accuracy_->verdict();
    return 0;
  }

 private:
  // The scene's outputs for a continuous run, in notification order: the histogram before
  // the summary that fits it, the summary (which says how the run ended) after every file.
  void attach_observers(bool resumed, const ChainForces& forces) {
    const RunSettings& r = settings_.run;
    observers_.attach<TimeSeriesWriter>(out_.path("timeseries.csv"), resumed,
                                        settings_.output.status);
    if (settings_.output.energy)
      observers_.attach<EnergyDiagnostics>(forces, out_.path("energy_samples.csv"),
                                           out_.path("energy.csv"), settings_.output.energy_window,
                                           settings_.output.energy_tol, resumed);
    if (const char* catalog = catalog_file_name(settings_.output.catalog))
      observers_.attach<CatalogWriter>(settings_.output.catalog, out_.path(catalog), req_.scene,
                                       resumed ? prog_.events_done : -1,
                                       settings_.output.catalog_deflate, catalog_layout(settings_));
    if (settings_.output.blocks)
      observers_.attach<BlockTrajectories>(out_.path("blocks.csv"), resumed,
                                           settings_.output.block_first,
                                           settings_.output.block_count);
    observers_.attach<PadFrictionStats>();
    const auto& hist =
        observers_.attach<HistogramWriter>(settings_.stats.bin_width, out_.path("histogram.csv"));
    attach_segment_stats(observers_, settings_, out_, resumed);
    accuracy_ = &observers_.attach<AccuracyCheck>(settings_, stepper_);
    observers_.attach<ContinuousSummary>(req_.scene, settings_, out_, hist.histogram(), observers_);
    if (r.checkpoint_events > 0 || r.checkpoint_seconds > 0)
      observers_.attach<CheckpointTimer>([this] { save(); }, r.checkpoint_events,
                                         r.checkpoint_seconds);
    if (!req_.quiet) observers_.attach<ProgressLine>();
    for (RunObserver* o : req_.observers) observers_.attach_ref(*o);
  }

  // Writes a checkpoint of the run as it stands, between two steps; the observers add
  // their state and sync their files. `final`: the finished run's final state.
  void save(bool final = false) {
    prog_.wall_total = prog_.wall_events = wall_.total();
    prog_.events_done = episodes_;
    prog_.transient_done = 0;
    ContinuousSnapshot d = driver_->snapshot();
    Checkpoint c =
        Checkpoint::of_run(req_.scene.hash(), req_.scene.to_ini(), settings_.run.seed, prog_);
    c.engine.counters.steps = done_;
    c.engine.counters.events = episodes_;
    c.put(kContinuousStateName, encode_state(d, next_out_));
    c.engine.state = std::move(d.state);
    observers_.checkpoint(c);
    files_.save(c, final);
  }

  RunEnd run_end(int signal) const {
    RunEnd end;
    end.signal = signal;
    end.events = episodes_;
    end.steps = done_;  // steps_ unless stopped
    end.blocks = settings_.model.n;
    end.total_load = driver_->substrate().s;
    end.duration = driver_->state().t;
    end.wall_seconds = end.wall_seconds_total = wall_.total();
    end.resumes = prog_.resumes;
    return end;
  }

  int stop(int sig) {
    save();
    accuracy_->set_run_energy_residual(driver_->energy_balance().residual(driver_->energy()));
    observers_.end(run_end(sig));
    print_stop_notice(sig,
                      "at t = " + format_real(driver_->state().t) + " of " +
                          format_real(duration_) + " (" + std::to_string(done_) + " of " +
                          std::to_string(steps_) + " steps)",
                      files_.current(), out_.path("scene.ini"), out_.dir());
    return 128 + sig;
  }

  const RunRequest& req_;
  const Settings& settings_;
  const Stepper& stepper_;
  const OutputFolder& out_;
  const CheckpointFiles files_;
  const double dt_, duration_, every_;
  const std::int64_t steps_;
  // output.every / integrator.dt when it is a whole number (to rounding): samples are taken
  // every that many steps and stamped with their grid time k * every. 0 otherwise: a sample
  // at the first step at or past each k * every, stamped with that step's time.
  const std::int64_t steps_per_sample_ = whole_steps(every_, dt_);

  static std::int64_t whole_steps(double every, double dt) {
    const double m = every / dt;
    const double r = std::round(m);
    return r >= 1 && std::fabs(m - r) <= 1e-9 * r ? static_cast<std::int64_t>(r) : 0;
  }
  bool sample_due() const {
    if (steps_per_sample_ > 0) return done_ >= next_sample_ * steps_per_sample_;
    return driver_->state().t >= next_out_ - 1e-9 * dt_;
  }

  std::unique_ptr<ContinuousDriver> driver_;
  AccuracyCheck* accuracy_ = nullptr;     // one of the observers
  std::int64_t done_ = 0, episodes_ = 0;  // steps and finished episodes, all sessions
  double next_out_ = 0;                   // time of the next sample
  std::int64_t next_sample_ = 0;          // index k of the next sample (on the grid)
  RunProgress prog_;  // wall time and resumes; catalog_bytes and the moment sums are the observers'
  Observers observers_;
  RunWall wall_;
};

// Cuts `path` back to the `bytes` its checkpoint covers (rows written after it are
// computed again).
void cut_back(const std::string& path, std::uint64_t bytes) {
  std::error_code ec;
  std::filesystem::resize_file(path, bytes, ec);
  if (ec) throw Error("cannot truncate '" + path + "' to its checkpoint: " + ec.message());
}

}  // namespace

std::int64_t continuous_steps(const Settings& settings) {
  return static_cast<std::int64_t>(
      std::llround(std::ceil(settings.run.duration / settings.integrator.dt - 1e-9)));
}

int run_continuous(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                   const ChainForces& forces, Stepper& stepper) {
  return ContinuousRun(req, settings, out, forces, stepper, nullptr).run();
}

int resume_continuous(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                      const ChainForces& forces, Stepper& stepper, const Checkpoint& saved,
                      const std::string& from, const std::function<void()>& adopt) {
  // Everything is checked before anything is changed (the catalog was checked by the
  // caller): the run reads every state from the checkpoint without touching a file, then
  // each sampled file is checked against its extent.
  ContinuousRun run(req, settings, out, forces, stepper, &saved);
  struct File {
    std::string path, header;
    CsvExtent extent;
  };
  std::vector<File> files;
  files.push_back({out.path("timeseries.csv"),
                   timeseries_header() + (settings.output.status ? status_header_suffix() : ""),
                   find_csv_extent(saved, "timeseries.csv")});
  if (settings.output.blocks)
    files.push_back({out.path("blocks.csv"),
                     blocks_header(settings.output.block_first, settings.output.block_count),
                     find_csv_extent(saved, "blocks.csv")});
  if (writes_segments(settings))
    files.push_back(
        {out.path("segments.csv"), segments_header(), find_csv_extent(saved, "segments.csv")});
  if (settings.output.energy)
    for (const auto& [name, schema] : {std::pair{"energy_samples.csv", energy_samples_schema()},
                                       std::pair{"energy.csv", energy_schema()}})
      files.push_back({out.path(name), header_of(schema), find_csv_extent(saved, name)});
  for (const File& f : files) check_csv_prefix(f.path, f.header, f.extent.rows, f.extent.bytes);
  if (adopt) adopt();
  for (const File& f : files) cut_back(f.path, f.extent.bytes);
  if (settings.output.catalog == CatalogFormat::Csv)  // catalog.h5: cut back when opened
    cut_back(out.path("catalog.csv"), saved.progress.catalog_bytes);
  std::printf("bkquake: resuming '%s' from %s at t = %s of %s (%lld slip episodes so far)\n",
              out.dir().c_str(), from.c_str(), format_real(saved.engine.state.t).c_str(),
              format_real(settings.run.duration).c_str(),
              static_cast<long long>(saved.progress.events_done));
  std::fflush(stdout);
  return run.run();
}

}  // namespace bkq
