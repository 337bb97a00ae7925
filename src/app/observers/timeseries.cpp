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
  StateWriter w;
  w.i64(e.rows);
  w.u64(e.bytes);
  c.put(name, std::move(w.bytes()));
}

CsvExtent find_csv_extent(const Checkpoint& c, const std::string& name) {
  const std::string* bytes = c.find(name);
  if (!bytes) throw Error("the checkpoint does not cover '" + name + "'");
  StateReader r(*bytes, name);
  CsvExtent e;
  e.rows = r.i64();
  e.bytes = r.u64();
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
  row(timeseries_row(s.values));
}

std::string TimeSeriesWriter::header() const {
  return timeseries_header();
}

BlockTrajectories::BlockTrajectories(std::string path, bool append, int blocks)
    : SampledCsv(std::move(path), append), u_(static_cast<std::size_t>(blocks)) {}

void BlockTrajectories::on_sample(const Sample& s) {
  for (std::size_t j = 0; j < u_.size(); ++j) u_[j] = s.driver.displacement(static_cast<int>(j));
  row(blocks_row(s.values.t, u_));
}

std::string BlockTrajectories::header() const {
  return blocks_header(static_cast<int>(u_.size()));
}

void PadFrictionStats::on_resume(const Checkpoint& c) {
  const std::string* bytes = c.find("pad_friction");
  if (!bytes) throw Error("the checkpoint holds no pad friction statistics");
  StateReader r(*bytes, "pad_friction");
  sum_ = r.f64();
  sum_sq_ = r.f64();
  samples_ = r.i64();
}

void PadFrictionStats::on_checkpoint(Checkpoint& c) {
  StateWriter w;
  w.f64(sum_);
  w.f64(sum_sq_);
  w.i64(samples_);
  c.put("pad_friction", std::move(w.bytes()));
}

void PadFrictionStats::add_to_summary(Json& summary) const {
  const double mean = samples_ ? sum_ / samples_ : 0.0;
  const double var = samples_ ? std::max(0.0, sum_sq_ / samples_ - mean * mean) : 0.0;
  summary.set("pad_friction_mean", mean);
  summary.set("pad_friction_amplitude", std::sqrt(2.0 * var));
}

}  // namespace bkq
