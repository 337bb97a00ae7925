// Segment statistics of continuous runs; see segments.hpp.
#include "app/observers/segments.hpp"

#include <cmath>

#include "app/observers/timeseries.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/continuous.hpp"
#include "io/checkpoint.hpp"
#include "io/json.hpp"

namespace bkq {

std::vector<SegmentSpan> segment_spans(const DriveSettings& drive, double duration) {
  std::vector<SegmentSpan> spans;
  switch (drive.schedule) {
    case Schedule::Ramp:
      break;
    case Schedule::Constant:
      spans.push_back({0.0, duration, drive.speed});
      break;
    case Schedule::Steps: {
      const double interval = drive.step_interval;
      const double tol = 1e-9 * interval;
      for (std::int64_t k = 0; static_cast<double>(k) * interval < duration - tol; ++k) {
        const double t0 = static_cast<double>(k) * interval;
        const double t1 = std::min(t0 + interval, duration);
        spans.push_back({t0, t1, drive.speed + static_cast<double>(k) * drive.step_increment});
      }
      break;
    }
  }
  return spans;
}

SegmentStats::SegmentStats(std::string path, const Settings& settings, bool append)
    : path_(std::move(path)),
      dt_(settings.integrator.dt),
      blocks_(settings.output.segment_blocks),
      spans_(segment_spans(settings.drive, settings.run.duration)),
      append_(append) {}

namespace {
constexpr const char* kSegmentsFile = "segments.csv";
constexpr const char* kSegmentsState = "segments";
}  // namespace

// The checkpoint holds the file's extent and the open segment: its index and the moments
// of its input so far.
void SegmentStats::on_checkpoint(Checkpoint& c) {
  if (!csv_) return;
  put_csv_extent(c, kSegmentsFile,
                 {rows_before_ + static_cast<std::int64_t>(rows_.size()), csv_->sync()});
  StateWriter w;
  w.i64(static_cast<std::int64_t>(current_));
  w.u64(moments_.size());
  for (const BlockedMoments& m : moments_) w.f64s(m.state());
  c.put(kSegmentsState, std::move(w.bytes()));
}

void SegmentStats::on_resume(const Checkpoint& c) {
  if (spans_.empty()) return;
  rows_before_ = find_csv_extent(c, kSegmentsFile).rows;
  const std::string* bytes = c.find(kSegmentsState);
  if (!bytes) throw Error("--resume: the checkpoint holds no segment statistics");
  StateReader r(*bytes, kSegmentsState);
  const std::int64_t k = r.i64();
  if (k < 0 || k > static_cast<std::int64_t>(spans_.size()))
    throw Error("--resume: the checkpoint's segment index is out of range");
  open_segment(static_cast<std::size_t>(k));
  const std::uint64_t n = r.u64();
  if (n != moments_.size())
    throw Error("--resume: the checkpoint's segment statistics do not fit this scene");
  for (BlockedMoments& m : moments_)
    if (!m.set_state(r.f64s()))
      throw Error("--resume: the checkpoint's segment statistics do not fit this scene");
  if (!r.done()) throw Error("--resume: the checkpoint's segment statistics are malformed");
  resumed_ = true;
}

void SegmentStats::on_start() {
  if (spans_.empty()) return;
  csv_ = std::make_unique<CsvStream>(path_, segments_header(), append_, 1);
  if (!resumed_) open_segment(0);
}

void SegmentStats::open_segment(std::size_t k) {
  current_ = k;
  moments_.clear();
  if (k >= spans_.size()) return;
  range_ = input_steps(spans_[k].t_start, spans_[k].t_end, dt_);
  for (std::size_t s = 0; s < kSegmentSignals.size(); ++s)
    moments_.emplace_back(range_.count(), blocks_);
}

void SegmentStats::finish_segment() {
  const SegmentSpan& span = spans_[current_];
  if (!moments_.empty() && moments_[0].added() > 0) {
    SegmentRow row;
    row.segment = static_cast<std::int64_t>(current_);
    row.t_start = span.t_start;
    row.t_end = span.t_end;
    row.speed = span.speed;
    for (std::size_t s = 0; s < moments_.size(); ++s) row.stats[s] = moments_[s].result();
    csv_->row(segments_row(row));
    rows_.push_back(row);
  }
  open_segment(current_ + 1);
}

void SegmentStats::on_step(const Step& s) {
  while (current_ < spans_.size() && s.index > range_.last) finish_segment();
  if (current_ >= spans_.size() || s.index < range_.first) return;
  const ContinuousDriver& d = s.driver;
  moments_[0].add(d.pad_friction());
  moments_[1].add(d.state().x);
  moments_[2].add(d.state().xd);
}

void SegmentStats::on_end(const RunEnd& end) {
  if (!csv_) return;
  // A finished run has filled its last segment; a stopped one writes no partial segment.
  if (end.signal == 0 && current_ < spans_.size()) finish_segment();
  csv_->close();
}

void SegmentStats::add_to_summary(Json& summary) const {
  if (spans_.empty()) {
    summary.set("segments", "none: a ramp has no speed segments");
    return;
  }
  summary.set("segments", rows_before_ + static_cast<std::int64_t>(rows_.size()));
  summary.set("segment_blocks", blocks_);
}

bool writes_segments(const Settings& settings) {
  return !segment_spans(settings.drive, settings.run.duration).empty();
}

void extend_segment_state(Checkpoint& c, const Settings& before, const Settings& after) {
  if (!writes_segments(after)) return;
  const std::vector<SegmentSpan> old_spans = segment_spans(before.drive, before.run.duration);
  const std::vector<SegmentSpan> spans = segment_spans(after.drive, after.run.duration);
  const std::string* bytes = c.find(kSegmentsState);
  if (!bytes) throw Error("--resume: the finished run's final state holds no segment statistics");
  StateReader r(*bytes, kSegmentsState);
  const std::int64_t k = r.i64();
  const std::uint64_t signals = r.u64();
  if (k < 0 || k >= static_cast<std::int64_t>(spans.size())) return;  // nothing open
  const auto open = static_cast<std::size_t>(k);
  // Ended where the longer schedule ends it too: its moments go on as they are.
  if (open < old_spans.size() && old_spans[open].t_end == spans[open].t_end) return;
  // Ended early by the shorter run: its input is the last half of the longer segment, which
  // must not have begun yet (the steps before the end were not kept).
  const SegmentSpan& span = spans[open];
  const StepRange range = input_steps(span.t_start, span.t_end, after.integrator.dt);
  const double t1 = before.run.duration;
  if (range.first <= c.engine.counters.steps) {
    const double need = 2 * t1 - span.t_start;  // the input's start (its midpoint) after t1
    const bool reachable =
        after.drive.schedule != Schedule::Steps || need < span.t_start + after.drive.step_interval;
    throw Error("--resume: run.duration = " + format_real(after.run.duration) +
                " would average speed segment " + std::to_string(k) +
                " (from t = " + format_real(span.t_start) +
                ") over its last half, which begins before the finished " +
                "run's end (t = " + format_real(t1) + ") whose steps were not kept; allowed: " +
                (reachable ? "more than " + format_real(need) : std::string("none")) +
                " (or start over with --force)");
  }
  StateWriter w;
  w.i64(k);
  w.u64(signals);
  for (std::uint64_t s = 0; s < signals; ++s)
    w.f64s(BlockedMoments(range.count(), after.output.segment_blocks).state());
  c.put(kSegmentsState, std::move(w.bytes()));
}

void attach_segment_stats(Observers& obs, const Settings& settings, const OutputFolder& out,
                          bool resumed) {
  obs.attach<SegmentStats>(out.path(kSegmentsFile), settings, resumed);
}

}  // namespace bkq
