// The event-run loop; see event_run.hpp. The loop owns the engine, the run's bookkeeping
// (events done, load and work at the start of recording, wall time over all sessions) and
// the checkpoint files; everything written per event is an observer's.
#include "app/event_run.hpp"

#include <signal.h>

#include <chrono>
#include <cmath>
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
#include "app/wall_clock.hpp"
#include "core/error.hpp"
#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "engine/ofc.hpp"
#include "io/checkpoint.hpp"
#include "io/output.hpp"

namespace bkq {

namespace {

using Clock = WallClock;

// What the loop needs of an engine, so that the chain's event engine and the OFC automaton
// (engine/ofc.hpp) run under the same loop, observers and checkpoints.
class LoopEngine {
 public:
  virtual ~LoopEngine() = default;
  virtual EventRecord next_event() = 0;
  virtual EngineCounters counters() const = 0;
  virtual double load() const = 0;
  virtual int sites() const = 0;
  // Puts the engine's state into a checkpoint (it may be moved there: the engine is not
  // used until take_back() has returned it).
  virtual void lend(Checkpoint& c) = 0;
  virtual void take_back(Checkpoint& c) = 0;
  // A new engine of the same scene from a checkpoint's state, or from the seed.
  virtual std::unique_ptr<LoopEngine> restart(const Checkpoint* from) const = 0;
  // Has the engine keep the slips of each event of magnitude >= min_magnitude
  // (output.event_slip; an engine may keep those of smaller events too) and says where it
  // keeps them.
  virtual SlipSource keep_slips(double min_magnitude) = 0;
};

class ChainLoopEngine : public LoopEngine {
 public:
  // `stepper`: the run's; nullptr: a stepper of the engine's own (a replay: the run's may
  // be mid-event).
  ChainLoopEngine(const Settings& settings, const ChainForces& forces, Stepper* stepper,
                  const Checkpoint* from)
      : settings_(settings),
        forces_(forces),
        own_(stepper ? nullptr : stepper_of(settings.integrator, forces.n())),
        engine_(from ? EventEngine(forces, stepper ? *stepper : *own_, settings.integrator.dt,
                                   from->engine)
                     : EventEngine(forces, stepper ? *stepper : *own_, settings.integrator.dt,
                                   initial_state(forces, settings.run.seed,
                                                 settings.run.initial_disorder, true))) {
    engine_.max_steps_per_event = settings.run.max_steps_per_event;
  }
  EventRecord next_event() override {
    EventRecord e = engine_.next_event();
    if (column_) place_on_column(e);
    return e;
  }
  EngineCounters counters() const override { return engine_.counters(); }
  double load() const override { return engine_.load(); }
  int sites() const override { return engine_.state().n(); }
  // The chain's state is moved, not copied (a copy of a long chain at each checkpoint
  // would be the largest thing the run holds).
  void lend(Checkpoint& c) override { c.engine = engine_.lend_snapshot(); }
  void take_back(Checkpoint& c) override { engine_.take_back(std::move(c.engine)); }
  // A chain: one row of n sites, each block its own index.
  // A lattice's sites (a column's too: the chain's blocks are its rows) split by its width.
  SlipSource keep_slips(double) override {
    engine_.keep_slips(true);
    return {.slips = &engine_.slips(), .width = settings_.lattice.nx, .rows = settings_.lattice.ny};
  }
  std::unique_ptr<LoopEngine> restart(const Checkpoint* from) const override {
    return std::make_unique<ChainLoopEngine>(settings_, forces_, nullptr, from);
  }

 private:
  const Settings& settings_;
  const ChainForces& forces_;
  std::unique_ptr<Stepper> own_;
  EventEngine engine_;
  // A lattice of one column runs as the chain along y; its events are read as rows.
  bool column_ = settings_.lattice.nx == 1 && settings_.lattice.ny > 1;
};

class OfcLoopEngine : public LoopEngine {
 public:
  OfcLoopEngine(const Settings& settings, const Checkpoint* from)
      : settings_(settings),
        engine_(from ? OfcEngine(settings.ofc.lattice, saved(settings, *from))
                     : OfcEngine(settings.ofc.lattice,
                                 ofc_initial_field(settings.ofc.lattice, settings.run.seed))) {}
  // Each toppling releases at least the threshold F_th = 1; the drive stops the trigger one
  // rounding step short of it, so an event's moment is made at least its topplings.
  EventRecord next_event() override {
    EventRecord e = engine_.next_event();
    if (e.moment < static_cast<double>(e.topplings)) {
      e.moment = static_cast<double>(e.topplings);
      e.magnitude = std::log(e.moment);
    }
    return e;
  }
  // steps: topplings (the automaton's unit of work).
  EngineCounters counters() const override {
    EngineCounters c;
    c.events = engine_.counters().events;
    c.steps = engine_.counters().topplings;
    return c;
  }
  double load() const override { return engine_.load(); }
  int sites() const override { return engine_.params().sites(); }
  // The state travels as named states of the checkpoint (io/checkpoint.hpp).
  void lend(Checkpoint& c) override { put_ofc_state(c, engine_.snapshot()); }
  void take_back(Checkpoint&) override {}
  // The automaton's slip is the stress a site released; it also counts topplings.
  SlipSource keep_slips(double min_magnitude) override {
    engine_.keep_slips(true, min_magnitude);
    return {.slips = &engine_.slips(),
            .topplings = &engine_.slip_topplings(),
            .width = engine_.params().nx,
            .rows = engine_.params().ny};
  }
  std::unique_ptr<LoopEngine> restart(const Checkpoint* from) const override {
    return std::make_unique<OfcLoopEngine>(settings_, from);
  }

 private:
  static OfcSnapshot saved(const Settings& settings, const Checkpoint& c) {
    return find_ofc_state(c, settings.ofc.lattice, "the checkpoint");
  }
  const Settings& settings_;
  OfcEngine engine_;
};

class EventRun {
 public:
  // `stepper`: the chain's (for the accuracy check), nullptr for the automaton.
  EventRun(const RunRequest& req, const Settings& settings, const OutputFolder& out,
           std::unique_ptr<LoopEngine> engine, const Stepper* stepper, const Checkpoint* resumed)
      : req_(req),
        settings_(settings),
        stepper_(stepper),
        out_(out),
        files_(out.dir()),
        scene_ini_(req.scene.to_ini()),
        transient_(settings.run.transient_events),
        events_(settings.run.events),
        engine_(std::move(engine)) {
    if (resumed) {
      prog_ = resumed->progress;
      ++prog_.resumes;
    } else if (transient_ == 0) {
      begin_recording();
    }
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
      if (signals.received()) signals.stopping();
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
      signals.stopping();
      events_end_ = Clock::now();  // the summary's fit at phase_end is not event time
      observers_.phase_end(advance(prog_.events_done));
    }
    signals.stopping();
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
                                       settings_.output.catalog_deflate, catalog_layout(settings_));
    if (settings_.output.event_slip)
      observers_.attach<EventSlipWriter>(out_.path(EventSlipWriter::kFileName),
                                         *settings_.output.event_slip,
                                         engine_->keep_slips(*settings_.output.event_slip));
    const auto& hist =
        observers_.attach<HistogramWriter>(settings_.stats.bin_width, out_.path("histogram.csv"));
    if (stepper_) accuracy_ = &observers_.attach<AccuracyCheck>(settings_, *stepper_);
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
      if (accuracy_) accuracy_->note_event_steps(engine_->counters().steps - steps0);
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
      std::unique_ptr<LoopEngine> replay;
      if (saved_) {
        const Checkpoint last = files_.read();
        replay = engine_->restart(&last);
      } else {
        replay = engine_->restart(nullptr);
      }
      while (replay->counters().events < events_done) replay->next_event();
      save(*replay);
      return "; the state before this event is saved in '" + files_.current() + "'";
    } catch (const Error& e) {
      return std::string("; saving the state before this event failed: ") + e.what();
    }
  }

  void save_engine(bool final = false) { save(*engine_, final); }

  // Writes a checkpoint of `engine` with the run as it stands. The run fills in its own
  // bookkeeping; the observers add theirs (the catalog syncs and records its size, the
  // histogram and the summary's sums their state). The engine lends its state to the
  // checkpoint and takes it back, unchanged.
  void save(LoopEngine& engine, bool final = false) {
    prog_.wall_total = wall_total0_ + seconds_since(session_t0_);
    if (prog_.transient_done == transient_)
      prog_.wall_events = wall_events0_ + seconds_since(recording_t0_);
    Checkpoint c = Checkpoint::of_run(req_.scene.hash(), scene_ini_, settings_.run.seed, prog_);
    engine.lend(c);
    struct GiveBack {
      LoopEngine& engine;
      Checkpoint& c;
      ~GiveBack() { engine.take_back(c); }
    } give_back{engine, c};
    observers_.checkpoint(c);
    files_.save(c, final);
    saved_ = saved_ || !final;
  }

  RunEnd run_end(int signal) const {
    const EngineCounters& c = engine_->counters();
    const EngineCounters& c0 = prog_.counters0;
    RunEnd end;
    end.signal = signal;
    end.events = prog_.events_done;
    end.transient_events = prog_.transient_done;  // all of them unless stopped during them
    end.blocks = engine_->sites();
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
    print_stop_notice(sig,
                      "after " + std::to_string(prog_.events_done) + " of " +
                          std::to_string(events_) + " events (" +
                          std::to_string(prog_.transient_done) + " of " +
                          std::to_string(transient_) + " transient)",
                      files_.current(), out_.path("scene.ini"), out_.dir());
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
    if (accuracy_) accuracy_->verdict();
    return 0;
  }

  const RunRequest& req_;
  const Settings& settings_;
  const Stepper* stepper_;
  const OutputFolder& out_;
  const CheckpointFiles files_;
  const std::string scene_ini_;
  const std::int64_t transient_, events_;

  std::unique_ptr<LoopEngine> engine_;
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
  return EventRun(req, settings, out,
                  std::make_unique<ChainLoopEngine>(settings, forces, &stepper, resumed), &stepper,
                  resumed)
      .run();
}

int run_ofc_events(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                   const Checkpoint* resumed) {
  return EventRun(req, settings, out, std::make_unique<OfcLoopEngine>(settings, resumed), nullptr,
                  resumed)
      .run();
}

}  // namespace bkq
