// segments.csv (io/segments_csv.hpp): the statistics of each speed segment of a continuous
// run (Ferre 2018 §4.2), streamed per integration step. A segment is the stretch at one
// substrate speed: each step of a steps schedule starts one (the last ends with the run),
// a constant speed is one segment, a ramp has none (the summary says so). Only the
// segment's last half enters (the "input signal", stats/segment_stats.hpp), in
// output.segment_blocks blocks; nothing but per-block moments is kept.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "app/observers/observer.hpp"
#include "io/output.hpp"
#include "io/segments_csv.hpp"
#include "io/settings.hpp"
#include "stats/segment_stats.hpp"

namespace bkq {

class OutputFolder;

// Where the segments of a run lie: [t_start, t_end] and the speed.
struct SegmentSpan {
  double t_start = 0, t_end = 0, speed = 0;
};
// The segments of a continuous run's schedule (empty for a ramp).
std::vector<SegmentSpan> segment_spans(const DriveSettings& drive, double duration);

class SegmentStats : public RunObserver {
 public:
  // Writes to `path` (nothing for a ramp), M of eqs. 4.3-4.4 from output.segment_blocks;
  // `append`: continue the file of a resumed run (cut back to its checkpoint).
  SegmentStats(std::string path, const Settings& settings, bool append = false);
  void on_resume(const Checkpoint& c) override;
  void on_checkpoint(Checkpoint& c) override;
  bool wants_steps() const override { return !spans_.empty(); }
  void on_start() override;
  void on_step(const Step& s) override;
  void on_end(const RunEnd& end) override;
  void add_to_summary(Json& summary) const override;

  // The rows written so far (also for tests and studies run in process).
  const std::vector<SegmentRow>& rows() const { return rows_; }

 private:
  void open_segment(std::size_t k);
  void finish_segment();

  std::string path_;
  double dt_;
  int blocks_;
  std::vector<SegmentSpan> spans_;
  std::size_t current_ = 0;
  StepRange range_;
  std::vector<BlockedMoments> moments_;  // one per signal of kSegmentSignals
  std::vector<SegmentRow> rows_;         // this session's
  std::int64_t rows_before_ = 0;         // written by earlier sessions
  bool append_ = false;
  bool resumed_ = false;
  std::unique_ptr<CsvStream> csv_;
};

// Does this run write segments.csv (not for a ramp)?
bool writes_segments(const Settings& settings);
// A finished continuous run of `before.run.duration` extended to `after.run.duration`
// (longer, every other setting the same): adapts the segment statistics of its final state
// `c` to the longer schedule. A segment both schedules end at the same time keeps its
// state; one the longer schedule ends later starts afresh, which is exact only when its
// input (its last half) begins after the steps already done; otherwise throws bkq::Error
// naming run.duration and the smallest extension allowed, `c` unchanged.
void extend_segment_state(Checkpoint& c, const Settings& before, const Settings& after);
// Attaches SegmentStats writing out/segments.csv (`resumed`: appending to it).
void attach_segment_stats(Observers& obs, const Settings& settings, const OutputFolder& out,
                          bool resumed = false);

}  // namespace bkq
