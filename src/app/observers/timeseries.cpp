// The sampled outputs of continuous runs; see timeseries.hpp.
#include "app/observers/timeseries.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "engine/continuous.hpp"
#include "io/checkpoint.hpp"
#include "io/json.hpp"
#include "io/timeseries.hpp"

namespace bkq {

void put_csv_extent(Checkpoint& c, const std::string& name, const CsvExtent& e) {
  put_state(c, name, e.rows, e.bytes);
}

CsvExtent find_csv_extent(const Checkpoint& c, const std::string& name) {
  CsvExtent e;
  if (!find_state(c, name, e.rows, e.bytes))
    throw Error("the checkpoint does not cover '" + name + "'");
  return e;
}

std::string SampledCsv::name() const {
  return std::filesystem::path(path_).filename().string();
}

void SampledCsv::on_resume(const Checkpoint& c) {
  rows_ = find_csv_extent(c, name()).rows;
}

// Synced first, so a checkpoint never counts rows that are not on disk.
void SampledCsv::on_checkpoint(Checkpoint& c) {
  put_csv_extent(c, name(), {rows_, csv_->sync()});
}

void TimeSeriesWriter::on_sample(const Sample& s) {
  if (!status_) {
    row(timeseries_row(s.values));
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
  row(timeseries_row(s.values) + status_row_suffix(n));
}

std::string TimeSeriesWriter::header() const {
  return timeseries_header() + (status_ ? status_header_suffix() : "");
}

BlockTrajectories::BlockTrajectories(std::string path, bool append, int first, int count)
    : SampledCsv(std::move(path), append),
      first_(first),
      u_(static_cast<std::size_t>(count)),
      v_(static_cast<std::size_t>(count)) {}

void BlockTrajectories::on_sample(const Sample& s) {
  // Lab frame: u_j = w_j - s, u_j' = w_j' - v.
  const ChainState& st = s.driver.state();
  for (std::size_t j = 0; j < u_.size(); ++j) {
    const int b = first_ + static_cast<int>(j);
    u_[j] = s.driver.displacement(b);
    v_[j] = st.wd[static_cast<std::size_t>(b)] - s.values.speed;
  }
  row(blocks_row(s.values.t, u_, v_));
}

std::string BlockTrajectories::header() const {
  return blocks_header(first_, static_cast<int>(u_.size()));
}

void PadFrictionStats::on_resume(const Checkpoint& c) {
  if (!find_state(c, "pad_friction", sum_, sum_sq_, samples_))
    throw Error("the checkpoint holds no pad friction statistics");
}

void PadFrictionStats::on_checkpoint(Checkpoint& c) {
  put_state(c, "pad_friction", sum_, sum_sq_, samples_);
}

void PadFrictionStats::add_to_summary(Json& summary) const {
  const double mean = samples_ ? sum_ / samples_ : 0.0;
  const double var = samples_ ? std::max(0.0, sum_sq_ / samples_ - mean * mean) : 0.0;
  summary.set("pad_friction_mean", mean);
  summary.set("pad_friction_amplitude", std::sqrt(2.0 * var));
}

}  // namespace bkq
