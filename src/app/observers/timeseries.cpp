// The sampled outputs of continuous runs; see timeseries.hpp.
#include "app/observers/timeseries.hpp"

#include <algorithm>
#include <cmath>

#include "engine/continuous.hpp"
#include "io/json.hpp"
#include "io/timeseries.hpp"

namespace bkq {

void TimeSeriesWriter::on_start() {
  csv_ = std::make_unique<CsvStream>(path_,
                                     timeseries_header() + (status_ ? status_header_suffix() : ""));
}

void TimeSeriesWriter::on_sample(const Sample& s) {
  if (!status_) {
    csv_->row(timeseries_row(s.values));
    return;
  }
  // Node status by the sign of each block's relative velocity (stuck: exactly 0).
  NodeStatus n;
  const ChainState& st = s.driver.state();
  for (int j = 0; j < st.n(); ++j) {
    if (st.mobile[j] == 0.0)
      ++n.stuck;
    else if (st.wd[j] >= 0.0)
      ++n.forward;
    else
      ++n.backward;
  }
  csv_->row(timeseries_row(s.values) + status_row_suffix(n));
}

void TimeSeriesWriter::on_end(const RunEnd&) {
  csv_->close();
}

BlockTrajectories::BlockTrajectories(std::string path, int blocks)
    : path_(std::move(path)), u_(static_cast<std::size_t>(blocks)) {}

void BlockTrajectories::on_start() {
  csv_ = std::make_unique<CsvStream>(path_, blocks_header(static_cast<int>(u_.size())));
}

void BlockTrajectories::on_sample(const Sample& s) {
  for (std::size_t j = 0; j < u_.size(); ++j) u_[j] = s.driver.displacement(static_cast<int>(j));
  csv_->row(blocks_row(s.values.t, u_));
}

void BlockTrajectories::on_end(const RunEnd&) {
  csv_->close();
}

void PadFrictionStats::add_to_summary(Json& summary) const {
  const double mean = samples_ ? sum_ / samples_ : 0.0;
  const double var = samples_ ? std::max(0.0, sum_sq_ / samples_ - mean * mean) : 0.0;
  summary.set("pad_friction_mean", mean);
  summary.set("pad_friction_amplitude", std::sqrt(2.0 * var));
}

}  // namespace bkq
