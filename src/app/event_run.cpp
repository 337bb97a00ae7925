// The event-run loop; see event_run.hpp. The loop owns the engine, the run's bookkeeping
// (events done, load and work at the start of recording, wall time over all sessions) and
// the checkpoint files; everything written per event is an observer's.
#include "app/event_run.hpp"

#include <signal.h>

#include <chrono>
#include <cstdio>
#include <memory>

#include "app/observers/accuracy_check.hpp"
#include "app/observers/catalog.hpp"
#include "app/observers/checkpoint_timer.hpp"
#include "app/observers/event_slip.hpp"
#include "app/observers/histogram.hpp"
#include "app/observers/progress.hpp"
#include "app/observers/summary.hpp"
#include "app/stop_signals.hpp"
#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "io/checkpoint.hpp"
#include "io/output.hpp"

namespace bkq {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

class EventRun {
 public:
  EventRun(const RunRequest& req, const Settings& settings, const OutputFolder& out,
           const ChainForces& forces, Stepper& stepper, const Checkpoint* resumed)
      : req_(req),
        settings_(settings),
        forces_(forces),
        stepper_(stepper),
        out_(out),
        files_(out.dir()),
        scene_ini_(req.scene.to_ini()),
        transient_(settings.run.transient_events),
        events_(settings.run.events) {
    const double dt = settings.integrator.dt;
    if (resumed) {
      engine_ = std::make_unique<EventEngine>(forces, stepper, dt, resumed->engine);
      prog_ = resumed->progress;
      ++prog_.resumes;
    } else {
      engine_ = std::make_unique<EventEngine>(
          forces, stepper, dt,
          initial_state(forces, settings.run.seed, settings.run.initial_disorder, true));
      if (transient_ == 0) begin_recording();
    }
    engine_->max_steps_per_event = settings.run.max_steps_per_event;
    saved_ = resumed != nullptr;
    wall_total0_ = prog_.wall_total;
    wall_events0_ = prog_.wall_events;
    attach_observers(resumed != nullptr);
    if (resumed) observers_.resume(*resumed);
  }

  int run() {
    StopSignals signals;
    observers_.start();
    if (prog_.transient_done < transient_) {
      observers_.phase({"transient events", static_cast<double>(prog_.transient_done),
                        static_cast<double>(transient_)});
      while (prog_.transient_done < transient_ && !signals.received()) {
        next_event();
        if (++prog_.transient_done == transient_) begin_recording();
        observers_.advance(advance(prog_.transient_done));
      }
      observers_.phase_end(advance(prog_.transient_done));
    }
    if (prog_.transient_done == transient_ && !signals.received()) {
      observers_.phase(
          {"events", static_cast<double>(prog_.events_done), static_cast<double>(events_)});
      while (prog_.events_done < events_ && !signals.received()) {
        EventRecord e = next_event();
        e.event = ++prog_.events_done;
        observers_.event(e);
        observers_.advance(advance(prog_.events_done));
      }
      events_end_ = Clock::now();  // the summary's fit at phase_end is not event time
      observers_.phase_end(advance(prog_.events_done));
    }
    if (const int sig = signals.received()) return stop(sig);
    return finish();
  }

 private:
  // The scene's outputs for an event run, in notification order: the histogram before the
  // summary that fits it, the summary (which says how the run ended) after every file.
  void attach_observers(bool resumed) {
    const RunSettings& r = settings_.run;
    if (const char* catalog = catalog_file_name(settings_.output.catalog))
      observers_.attach<CatalogWriter>(settings_.output.catalog, out_.path(catalog), req_.scene,
                                       resumed ? prog_.events_done : -1,
                                       settings_.output.catalog_deflate);
    if (settings_.output.event_slip) {
      engine_->keep_slips(true);
      observers_.attach<EventSlipWriter>(out_.path(EventSlipWriter::kFileName),
                                         *settings_.output.event_slip, *engine_);
    }
    const auto& hist =
        observers_.attach<HistogramWriter>(settings_.stats.bin_width, out_.path("histogram.csv"));
    accuracy_ = &observers_.attach<AccuracyCheck>(settings_, stepper_);
    observers_.attach<EventSummary>(req_.scene, settings_, out_, hist.histogram(), observers_,
                                    stop_requested);
    if (r.checkpoint_events > 0 || r.checkpoint_seconds > 0)
      observers_.attach<CheckpointTimer>([this] { save_engine(); }, r.checkpoint_events,
                                         r.checkpoint_seconds);
    if (!req_.quiet) observers_.attach<ProgressLine>();
    for (RunObserver* o : req_.observers) observers_.attach_ref(*o);
  }

  Advance advance(std::int64_t done) const {
    return {static_cast<double>(done), engine_->counters().events};
  }

  void begin_recording() {
    prog_.load0 = engine_->load();
    prog_.counters0 = engine_->counters();
    recording_t0_ = Clock::now();
  }

  // The engine's next event; a failure in the middle of it (a non-finite state, a runaway)
  // saves the state before the event as the checkpoint, then propagates, saying where.
  EventRecord next_event() {
    const std::int64_t done = engine_->counters().events;
    const std::int64_t steps0 = engine_->counters().steps;
    try {
      EventRecord e = engine_->next_event();
      accuracy_->note_event_steps(engine_->counters().steps - steps0);
      return e;
    } catch (const Error& e) {
      throw Error(e.what() + save_before_failure(done));
    }
  }

  // The failed engine is unusable and copying the state before every event would cost a
  // few per cent, so the state before the failed event is recomputed once from the last
  // checkpoint, read back from its file, or the start: an engine continued from a snapshot
  // repeats the same events bit for bit. That costs at most one checkpoint interval; no
  // copy of the chain is kept for it. Returns the note for the error.
  std::string save_before_failure(std::int64_t events_done) {
    try {
      const std::unique_ptr<Stepper> stepper = stepper_of(settings_.integrator, forces_.n());
      const double dt = settings_.integrator.dt;
      const bool seeded = !saved_;
      EventEngine replay = seeded ? EventEngine(forces_, *stepper, dt,
                                                initial_state(forces_, settings_.run.seed,
                                                              settings_.run.initial_disorder, true))
                                  : EventEngine(forces_, *stepper, dt, files_.read().engine);
      replay.max_steps_per_event = engine_->max_steps_per_event;
      while (replay.counters().events < events_done) replay.next_event();
      EngineSnapshot before = replay.snapshot();
      save(before);
      return "; the state before this event is saved in '" + files_.current() + "'";
    } catch (const Error& e) {
      return std::string("; saving the state before this event failed: ") + e.what();
    }
  }

  // A checkpoint of the running engine, its state lent rather than copied (a copy of a
  // long chain at each checkpoint would be the largest thing the run holds).
  void save_engine(bool final = false) {
    EngineSnapshot lent = engine_->lend_snapshot();
    struct GiveBack {
      EventEngine& engine;
      EngineSnapshot& lent;
      ~GiveBack() { engine.take_back(std::move(lent)); }
    } give_back{*engine_, lent};
    save(lent, final);
  }

  // Writes a checkpoint of `engine` with the run as it stands. The run fills in its own
  // bookkeeping; the observers add theirs (the catalog syncs and records its size, the
  // histogram and the summary's sums their state). The snapshot moves into the checkpoint
  // and back, unchanged.
  void save(EngineSnapshot& engine, bool final = false) {
    prog_.wall_total = wall_total0_ + seconds_since(session_t0_);
    if (prog_.transient_done == transient_)
      prog_.wall_events = wall_events0_ + seconds_since(recording_t0_);
    Checkpoint c;
    c.version = kVersion;
    c.git_revision = kGitRevision;
    c.scene_hash = req_.scene.hash();
    c.scene_ini = scene_ini_;
    c.seed = settings_.run.seed;
    c.progress = prog_;
    c.engine = std::move(engine);
    struct MoveBack {
      EngineSnapshot& to;
      EngineSnapshot& from;
      ~MoveBack() { to = std::move(from); }
    } move_back{engine, c.engine};
    observers_.checkpoint(c);
    if (final) {
      files_.write_final(c);
      return;
    }
    files_.write(c);
    saved_ = true;
  }

  RunEnd run_end(int signal) const {
    const EngineCounters& c = engine_->counters();
    const EngineCounters& c0 = prog_.counters0;
    RunEnd end;
    end.signal = signal;
    end.events = prog_.events_done;
    end.transient_events = prog_.transient_done;  // all of them unless stopped during them
    end.blocks = engine_->state().n();
    end.wall_seconds_total = wall_total0_ + seconds_since(session_t0_);
    end.resumes = prog_.resumes;
    if (prog_.transient_done < transient_) return end;  // recording has not begun
    end.total_load = engine_->load() - prog_.load0;
    end.wall_seconds =
        wall_events0_ +
        std::chrono::duration<double>(
            (events_end_ == Clock::time_point{} ? Clock::now() : events_end_) - recording_t0_)
            .count();
    end.steps_recorded = c.steps - c0.steps;
    end.block_steps = c.block_steps - c0.block_steps;
    end.sliding_block_steps = c.sliding_block_steps - c0.sliding_block_steps;
    return end;
  }

  int stop(int sig) {
    save_engine();
    observers_.end(run_end(sig));
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
    // The final state, before the observers close their files: a later `--resume --set
    // run.events=N2` continues from it exactly as an interrupted run continues. The
    // periodic checkpoints go only once summary.json says the run finished, so a kill in
    // between still leaves a resumable run.
    save_engine(true);
    observers_.end(run_end(0));
    files_.remove_interim();
    accuracy_->verdict();
    return 0;
  }

  const RunRequest& req_;
  const Settings& settings_;
  const ChainForces& forces_;
  const Stepper& stepper_;
  const OutputFolder& out_;
  const CheckpointFiles files_;
  const std::string scene_ini_;
  const std::int64_t transient_, events_;

  std::unique_ptr<EventEngine> engine_;
  AccuracyCheck* accuracy_ = nullptr;  // one of the observers
  bool saved_ = false;                 // a checkpoint file holds the state (else the seed does)
  // The run's own part of the checkpoint; catalog_bytes, moment_sum and nonpositive are the
  // observers' (filled in by them at each checkpoint, read back by them on resume).
  RunProgress prog_;
  Observers observers_;

  // Wall time: this session's clocks on top of what earlier sessions (before a resume) spent.
  Clock::time_point session_t0_ = Clock::now(), recording_t0_ = session_t0_;
  Clock::time_point events_end_{};  // when the events loop ended, once it has
  double wall_total0_ = 0, wall_events0_ = 0;
};

}  // namespace

int run_events(const RunRequest& req, const Settings& settings, const OutputFolder& out,
               const ChainForces& forces, Stepper& stepper, const Checkpoint* resumed) {
  return EventRun(req, settings, out, forces, stepper, resumed).run();
}

}  // namespace bkq
