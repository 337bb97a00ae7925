// The histogram observer; see histogram.hpp.
#include "app/observers/histogram.hpp"

#include "io/checkpoint.hpp"
#include "io/histogram_csv.hpp"
#include "io/output.hpp"

namespace bkq {

HistogramWriter::HistogramWriter(double bin_width, std::string path)
    : hist_(bin_width), path_(std::move(path)) {}

void HistogramWriter::on_resume(const Checkpoint& c) {
  hist_ = MagnitudeHistogram::from_state(c.histogram);
}

void HistogramWriter::on_checkpoint(Checkpoint& c) {
  c.histogram = hist_.state();
}

void HistogramWriter::on_end(const RunEnd& end) {
  if (end.signal != 0) return;
  hist_.set_loading(end.total_load, end.blocks);
  write_file_atomic(path_, histogram_csv(hist_));
}

}  // namespace bkq
