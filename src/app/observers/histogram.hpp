// The magnitude histogram of the recorded events and histogram.csv, written when the run
// finishes (with the rates per unit loading per block). Its whole state travels in the
// checkpoint, so a resumed run ends with the histogram of a run that never stopped.
#pragma once

#include <string>

#include "app/observers/observer.hpp"
#include "stats/histogram.hpp"

namespace bkq {

class HistogramWriter : public RunObserver {
 public:
  HistogramWriter(double bin_width, std::string path);
  void on_resume(const Checkpoint& c) override;
  // Events with moment <= 0 have no magnitude and are left out (the summary counts them).
  void on_event(const EventRecord& e) override {
    if (e.moment > 0) hist_.add(e.magnitude);
  }
  void on_checkpoint(Checkpoint& c) override;
  void on_end(const RunEnd& end) override;

  const MagnitudeHistogram& histogram() const { return hist_; }

 private:
  MagnitudeHistogram hist_;
  std::string path_;
};

}  // namespace bkq
