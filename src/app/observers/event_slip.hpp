// event_slip.csv (output.event_slip = MU, event runs): for every recorded event with
// mu >= MU, the slip of each block (a lattice's site) that slipped, one row per site, in
// site order (schema in io/seismicity_csv.hpp). Engines report an event's slips as (flat
// site index j, slip) with j = x + width * y, x along strike and y across; the writer splits
// j into the block (x) and, on a lattice of more than one row, the row (y) column, so a
// chain, the OFC automaton and any lattice engine share it. The automaton's slip is the
// stress a site released, and it also reports how many times each site toppled (a
// `topplings` column). Resumable like the catalogue: a checkpoint syncs the file and
// records its size, and a resumed run cuts the file back to that size before it continues,
// so a run stopped and resumed writes the bytes of one that never stopped.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/observers/observer.hpp"

namespace bkq {

class CsvStream;

// Where the writer reads each event's slips: vectors the engine refills after every event
// (and that outlive the writer).
struct SlipSource {
  // (flat site index j = x + width * y, slip), ascending in j.
  const std::vector<std::pair<int, double>>* slips = nullptr;
  // How many times each of those sites toppled, parallel to *slips (the OFC automaton);
  // nullptr: the engine counts none, and the file has no topplings column.
  const std::vector<int>* topplings = nullptr;
  int width = 1;  // sites along strike (model.blocks)
  int rows = 1;   // model.rows: more than one adds the row column
};

class EventSlipWriter : public RunObserver {
 public:
  static constexpr const char* kFileName = "event_slip.csv";
  EventSlipWriter(std::string path, double mu_min, SlipSource source);
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
  SlipSource source_;
  bool resumed_ = false;
  std::unique_ptr<CsvStream> file_;
};

}  // namespace bkq
