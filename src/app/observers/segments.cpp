// Segment statistics of continuous runs; see segments.hpp.
#include "app/observers/segments.hpp"

#include <cmath>

#include "engine/continuous.hpp"
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

SegmentStats::SegmentStats(std::string path, const Settings& settings)
    : path_(std::move(path)),
      dt_(settings.integrator.dt),
      blocks_(settings.output.segment_blocks),
      spans_(segment_spans(settings.drive, settings.run.duration)) {}

void SegmentStats::on_start() {
  if (spans_.empty()) return;
  csv_ = std::make_unique<CsvStream>(path_, segments_header(), false, 1);
  open_segment(0);
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
  summary.set("segments", static_cast<std::int64_t>(rows_.size()));
  summary.set("segment_blocks", blocks_);
}

void attach_segment_stats(Observers& obs, const Settings& settings, const OutputFolder& out) {
  obs.attach<SegmentStats>(out.path("segments.csv"), settings);
}

}  // namespace bkq
