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
  explicit TimeSeriesWriter(std::string path) : path_(std::move(path)) {}
  void on_start() override;
  void on_sample(const Sample& s) override;
  void on_end(const RunEnd&) override;

 private:
  std::string path_;
  std::unique_ptr<CsvStream> csv_;
};

// Lab-frame displacement and velocity of the blocks first .. first+count-1 at each sample.
class BlockTrajectories : public RunObserver {
 public:
  BlockTrajectories(std::string path, int first, int count);
  void on_start() override;
  void on_sample(const Sample& s) override;
  void on_end(const RunEnd&) override;

 private:
  std::string path_;
  int first_;
  std::vector<double> u_, v_;
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
