// summary.json and the lines printed at the end of a finished run. summary.json is
// written last, so a folder holding one is a finished run. It carries the provenance, the
// run's own figures, and then whatever the other observers add (add_to_summary).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "app/observers/observer.hpp"
#include "io/settings.hpp"
#include "stats/gutenberg_richter.hpp"

namespace bkq {

class OutputFolder;
class MagnitudeHistogram;
class Scene;

// Event runs: counts, load, moment sum, work, wall time and the Gutenberg-Richter fit of
// the histogram (attached before this observer, so it is complete at on_end). The fit is
// made when the events phase ends complete, before on_end, so that a run asked to stop
// during it (stop_requested turns true) can still checkpoint: the fit then stops and the
// run stops as after any event; a resumed run fits again.
class EventSummary : public RunObserver {
 public:
  EventSummary(const Scene& scene, const Settings& settings, const OutputFolder& out,
               const MagnitudeHistogram& hist, const Observers& all,
               std::function<bool()> stop_requested = {});
  void on_phase(const Phase& p) override;
  void on_phase_end(const Advance& a) override;
  void on_resume(const Checkpoint& c) override;
  void on_event(const EventRecord& e) override {
    moment_sum_ += e.moment;
    if (!(e.moment > 0)) ++nonpositive_;
  }
  void on_checkpoint(Checkpoint& c) override;
  void on_end(const RunEnd& end) override;

 private:
  const Scene& scene_;
  const Settings& settings_;
  const OutputFolder& out_;
  const MagnitudeHistogram& hist_;
  const Observers& all_;
  const std::function<bool()> stop_requested_;
  double events_total_ = -1;  // of the events phase, once it has begun
  std::optional<GrFit> fit_;
  std::string fit_error_;
  double moment_sum_ = 0;
  std::int64_t nonpositive_ = 0;
};

// Continuous runs: simulated time, steps, slip episodes, load and speed.
class ContinuousSummary : public RunObserver {
 public:
  ContinuousSummary(const Scene& scene, const Settings& settings, const OutputFolder& out,
                    const Observers& all);
  void on_end(const RunEnd& end) override;

 private:
  const Scene& scene_;
  const Settings& settings_;
  const OutputFolder& out_;
  const Observers& all_;
};

}  // namespace bkq
