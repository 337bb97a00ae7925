// What a run tells the outputs that watch it. A run (app/event_run, app/continuous_run)
// only drives the engine and notifies its observers; every output (catalog, histogram,
// time series, summary, progress line, checkpoint timing) is a RunObserver attached
// according to the scene. A new output is a new observer plus one attach line in the run's
// attach function; the loops stay as they are. Observers are notified per event, per
// sample and per phase, never from inside the engine, and they never steer the physics.
//
// Order of notifications:
//   on_resume (resumed event runs only)  on_start
//   for each phase: on_phase, then per event / step: on_event (recorded events and slip
//   episodes), on_sample (continuous runs), on_step (continuous runs, observers that want
//   it), on_advance; then on_phase_end
//   on_checkpoint (whenever a checkpoint is written)   on_end (finished or stopped)
// Observers are notified in the order they were attached.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "engine/event_record.hpp"
#include "io/timeseries.hpp"

namespace bkq {

class ContinuousDriver;
class Json;
struct Checkpoint;

// A phase of a run: the transient and the recorded events of an event run (counted in
// events), the whole of a continuous run (counted in simulated time).
struct Phase {
  const char* what;  // "transient events", "events", "time"
  double start;      // where this session starts it (a resumed run starts midway)
  double total;
};

// How far the current phase has come, after an event or a time step.
struct Advance {
  double done;          // in the phase's units
  std::int64_t events;  // events the engine has finished, transient ones included
};

// A sample of a continuous run, every output.every of simulated time.
struct Sample {
  TimeSeriesRow values;
  const ContinuousDriver& driver;  // for what the row does not hold (block displacements)
};

// One integration step of a continuous run, for observers that want every step
// (wants_steps()); runs with none of them pay nothing.
struct Step {
  std::int64_t index;              // steps done, 1, 2, ...: the nominal time is index * dt
  const ContinuousDriver& driver;  // the state after the step
};

// The end of a run, finished or stopped by a signal.
struct RunEnd {
  int signal = 0;                     // 0: finished; SIGINT or SIGTERM: stopped after a checkpoint
  std::int64_t events = 0;            // recorded events done, or slip episodes
  std::int64_t transient_events = 0;  // event runs
  std::int64_t steps = 0;             // continuous runs: time steps
  int blocks = 0;
  double total_load = 0;          // substrate displacement over the recorded part of the run
  double duration = 0;            // continuous runs: simulated time reached
  double wall_seconds = 0;        // recorded events (all sessions), or the whole continuous run
  double wall_seconds_total = 0;  // event runs: the whole run, all sessions
  std::int64_t resumes = 0;
  std::int64_t steps_recorded = 0, block_steps = 0, sliding_block_steps = 0;  // engine work
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // A resumed run restores the observer's state from the checkpoint it saved: a new
  // observer reads its own named state (find_state, or Checkpoint::find and StateReader).
  virtual void on_resume(const Checkpoint&) {}
  // The run is set up (fresh or resumed) and about to simulate: open files here.
  virtual void on_start() {}
  virtual void on_phase(const Phase&) {}
  // A recorded event (event runs) or a finished slip episode (continuous runs).
  virtual void on_event(const EventRecord&) {}
  virtual void on_sample(const Sample&) {}
  // Every integration step of a continuous run; called only when wants_steps() is true.
  virtual bool wants_steps() const { return false; }
  virtual void on_step(const Step&) {}
  virtual void on_advance(const Advance&) {}
  virtual void on_phase_end(const Advance&) {}
  // A checkpoint is being written: put this observer's state into it (a new observer
  // under its own name: put_state, or Checkpoint::put with a StateWriter) and make the files it
  // writes consistent with it.
  virtual void on_checkpoint(Checkpoint&) {}
  virtual void on_end(const RunEnd&) {}
  // Fields this observer adds to summary.json (after the run's own fields).
  virtual void add_to_summary(Json&) const {}
};

// The observers of one run, in attachment order. Owns the ones it creates; others (a
// study's or a test's) are attached by reference and must outlive the run.
class Observers {
 public:
  template <class T, class... Args>
  T& attach(Args&&... args) {
    auto owned = std::make_unique<T>(std::forward<Args>(args)...);
    T& ref = *owned;
    owned_.push_back(std::move(owned));
    list_.push_back(&ref);
    if (ref.wants_steps()) steppers_.push_back(&ref);
    return ref;
  }
  void attach_ref(RunObserver& o) {
    list_.push_back(&o);
    if (o.wants_steps()) steppers_.push_back(&o);
  }
  // Stops notifying `o` (the run keeps it alive if it owns it).
  void detach(const RunObserver& o) {
    std::erase(list_, &o);
    std::erase(steppers_, &o);
  }

  std::size_t size() const { return list_.size(); }
  const std::vector<RunObserver*>& all() const { return list_; }

  void resume(const Checkpoint& c) const {
    for (RunObserver* o : list_) o->on_resume(c);
  }
  void start() const {
    for (RunObserver* o : list_) o->on_start();
  }
  void phase(const Phase& p) const {
    for (RunObserver* o : list_) o->on_phase(p);
  }
  void event(const EventRecord& e) const {
    for (RunObserver* o : list_) o->on_event(e);
  }
  void sample(const Sample& s) const {
    for (RunObserver* o : list_) o->on_sample(s);
  }
  bool wants_steps() const { return !steppers_.empty(); }
  void step(const Step& s) const {
    for (RunObserver* o : steppers_) o->on_step(s);
  }
  void advance(const Advance& a) const {
    for (RunObserver* o : list_) o->on_advance(a);
  }
  void phase_end(const Advance& a) const {
    for (RunObserver* o : list_) o->on_phase_end(a);
  }
  void checkpoint(Checkpoint& c) const {
    for (RunObserver* o : list_) o->on_checkpoint(c);
  }
  void end(const RunEnd& e) const {
    for (RunObserver* o : list_) o->on_end(e);
  }
  void add_to_summary(Json& summary) const {
    for (const RunObserver* o : list_) o->add_to_summary(summary);
  }

 private:
  std::vector<std::unique_ptr<RunObserver>> owned_;
  std::vector<RunObserver*> list_;
  std::vector<RunObserver*> steppers_;  // those of list_ that want every step
};

}  // namespace bkq
