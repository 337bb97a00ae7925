// event_slip.csv (output.event_slip = MU, event runs): for every recorded event with
// mu >= MU, the slip of each block that slipped, one row per block (event,block,slip; schema
// in io/seismicity_csv.hpp), in block order. Resumable like the catalogue: a checkpoint syncs
// the file and records its size, and a resumed run cuts the file back to that size before it
// continues, so a run stopped and resumed writes the bytes of one that never stopped.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "app/observers/observer.hpp"

namespace bkq {

class CsvStream;
class EventEngine;

class EventSlipWriter : public RunObserver {
 public:
  static constexpr const char* kFileName = "event_slip.csv";
  // `engine` keeps the slips (EventEngine::keep_slips) and outlives the writer.
  EventSlipWriter(std::string path, double mu_min, const EventEngine& engine);
  ~EventSlipWriter() override;
  void on_resume(const Checkpoint& c) override;
  void on_start() override;
  void on_event(const EventRecord& e) override;
  void on_phase_end(const Advance&) override;
  void on_checkpoint(Checkpoint& c) override;
  void on_end(const RunEnd&) override;

 private:
  std::string path_;
  double mu_min_;
  const EventEngine& engine_;
  bool resumed_ = false;
  std::unique_ptr<CsvStream> file_;
};

}  // namespace bkq
