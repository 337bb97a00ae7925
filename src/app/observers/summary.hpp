// summary.json and the lines printed at the end of a finished run. summary.json is
// written last, so a folder holding one is a finished run. It carries the provenance, the
// run's own figures, and then whatever the other observers add (add_to_summary).
#pragma once

#include <cstdint>

#include "app/observers/observer.hpp"
#include "io/settings.hpp"

namespace bkq {

class OutputFolder;
class MagnitudeHistogram;
class Scene;

// Event runs: counts, load, moment sum, work, wall time and the Gutenberg-Richter fit of
// the histogram (attached before this observer, so it is complete at on_end).
class EventSummary : public RunObserver {
 public:
  EventSummary(const Scene& scene, const Settings& settings, const OutputFolder& out,
               const MagnitudeHistogram& hist, const Observers& all);
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
