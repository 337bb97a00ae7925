// The outputs of continuous runs sampled every output.every: timeseries.csv (columns in
// io/timeseries.hpp), blocks.csv (block trajectories, when output.blocks is set) and the
// mean and amplitude of the pad friction in summary.json (thesis eqs. 4.1-4.2).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/observers/observer.hpp"
#include "io/output.hpp"

namespace bkq {

class TimeSeriesWriter : public RunObserver {
 public:
  // status: append the node-status columns (output.status).
  explicit TimeSeriesWriter(std::string path, bool status = false)
      : path_(std::move(path)), status_(status) {}
  void on_start() override;
  void on_sample(const Sample& s) override;
  void on_end(const RunEnd&) override;

 private:
  std::string path_;
  bool status_ = false;
  std::unique_ptr<CsvStream> csv_;
};

// Lab-frame displacement of every block at each sample.
class BlockTrajectories : public RunObserver {
 public:
  BlockTrajectories(std::string path, int blocks);
  void on_start() override;
  void on_sample(const Sample& s) override;
  void on_end(const RunEnd&) override;

 private:
  std::string path_;
  std::vector<double> u_;
  std::unique_ptr<CsvStream> csv_;
};

// Mean and amplitude sqrt(2) * RMS deviation of the sampled pad friction.
class PadFrictionStats : public RunObserver {
 public:
  void on_sample(const Sample& s) override {
    const double f = s.values.pad_friction;
    sum_ += f;
    sum_sq_ += f * f;
    ++samples_;
  }
  void add_to_summary(Json& summary) const override;

 private:
  double sum_ = 0, sum_sq_ = 0;
  std::int64_t samples_ = 0;
};

}  // namespace bkq
