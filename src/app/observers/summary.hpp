// summary.json and the lines printed at the end of a finished run. summary.json is
// written last, when the run ends: "status": "finished", or "interrupted" when a signal
// stopped it (after its checkpoint; the figures are those reached so far, and there is no
// fit). It carries the provenance, the status, the run's own figures, and then whatever the
// other observers add (add_to_summary). A resumed run removes the interrupted summary when
// it starts and writes its own at its end, equal to an uninterrupted run's but for the wall
// times and "resumes".
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/observers/observer.hpp"
#include "io/settings.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/power_law.hpp"

namespace bkq {

class OutputFolder;
class MagnitudeHistogram;
class Scene;

// What both summaries report about the events (recorded events, or the slip episodes of
// a continuous run): their moment sum, the count with moment <= 0, and the
// Gutenberg-Richter fit of the histogram (attached before the summary, so it is complete
// at on_end). The sums travel in the checkpoint. The fit of an event run is made when its
// events phase ends complete, before on_end, so that a run asked to stop during it
// (stop_requested turns true) can still checkpoint: the fit then stops and the run stops as
// after any event; a resumed run fits again. Other runs fit at on_end.
class SummaryOfEvents : public RunObserver {
 public:
  SummaryOfEvents(const Scene& scene, const Settings& settings, const OutputFolder& out,
                  const MagnitudeHistogram& hist, const Observers& all,
                  std::function<bool()> stop_requested = {});
  void on_start() override;
  void on_phase(const Phase& p) override;
  void on_phase_end(const Advance& a) override;
  void on_resume(const Checkpoint& c) override;
  void on_event(const EventRecord& e) override {
    moment_sum_ += e.moment;
    if (!(e.moment > 0)) ++nonpositive_;
  }
  void on_checkpoint(Checkpoint& c) override;

 protected:
  // Sets moment_sum, nonpositive_moments and bin_width.
  void add_moments(Json& summary) const;
  // Sets the fit's fields (or fit_error; an interrupted run: no fit); returns the line
  // printed about it.
  std::string add_fit(Json& summary, const RunEnd& end);
  // An OFC run's or a lattice's "tau" (or null and "tau_error").
  void add_tau(Json& summary) const;
  static constexpr const char* kInterruptedFit =
      "no fit: interrupted (the resumed run fits when it finishes)";
  void fit();

  const Scene& scene_;
  const Settings& settings_;
  const OutputFolder& out_;
  const MagnitudeHistogram& hist_;
  const Observers& all_;
  double moment_sum_ = 0;
  std::int64_t nonpositive_ = 0;
  std::function<bool()> stop_requested_;
  double events_total_ = -1;  // the events phase's length, once it has begun
  bool fitted_ = false;
  std::optional<GrFit> fit_;
  std::string fit_error_;
  static constexpr std::int64_t kMaxOrderedEvents = 20'000'000;
  // The recorded events in their order, read back from the run's catalogue when the fit is
  // made (the same for a resumed run as for one run straight through): magnitudes for b's
  // block-bootstrap error, sizes for tau (topplings for OFC, blocks for a lattice). Empty,
  // with the reason, when the run writes no catalogue or it does not read.
  struct Ordered {
    std::vector<double> mu, size;
    std::string note;  // why there are none
  };
  Ordered read_ordered() const;
  std::optional<PowerLawFit> tau_;
  std::string tau_measure_, tau_error_;
};

// Event runs: counts, load, moment sum, work, wall time and the fit.
class EventSummary : public SummaryOfEvents {
 public:
  using SummaryOfEvents::SummaryOfEvents;
  void on_end(const RunEnd& end) override;
};

// Continuous runs: simulated time, steps, slip episodes, load, speed, moment sum and the
// fit of the episodes, so the two modes compare directly.
class ContinuousSummary : public SummaryOfEvents {
 public:
  using SummaryOfEvents::SummaryOfEvents;
  void on_end(const RunEnd& end) override;
};

}  // namespace bkq
