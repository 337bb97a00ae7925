// The sampled outputs of continuous runs; see timeseries.hpp.
#include "app/observers/timeseries.hpp"

#include <algorithm>
#include <cmath>

#include "engine/continuous.hpp"
#include "io/json.hpp"
#include "io/timeseries.hpp"

namespace bkq {

void TimeSeriesWriter::on_start() {
  csv_ = std::make_unique<CsvStream>(path_, timeseries_header());
}

void TimeSeriesWriter::on_sample(const Sample& s) {
  csv_->row(timeseries_row(s.values));
}

void TimeSeriesWriter::on_end(const RunEnd&) {
  csv_->close();
}

BlockTrajectories::BlockTrajectories(std::string path, int first, int count)
    : path_(std::move(path)),
      first_(first),
      u_(static_cast<std::size_t>(count)),
      v_(static_cast<std::size_t>(count)) {}

void BlockTrajectories::on_start() {
  csv_ = std::make_unique<CsvStream>(path_, blocks_header(first_, static_cast<int>(u_.size())));
}

void BlockTrajectories::on_sample(const Sample& s) {
  // Lab frame: u_j = w_j - s, u_j' = w_j' - v.
  const ChainState& st = s.driver.state();
  for (std::size_t j = 0; j < u_.size(); ++j) {
    const int b = first_ + static_cast<int>(j);
    u_[j] = s.driver.displacement(b);
    v_[j] = st.wd[static_cast<std::size_t>(b)] - s.values.speed;
  }
  csv_->row(blocks_row(s.values.t, u_, v_));
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
