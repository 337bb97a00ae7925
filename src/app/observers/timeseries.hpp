// The outputs of continuous runs sampled every output.every: timeseries.csv (columns in
// io/timeseries.hpp), blocks.csv (block trajectories, when output.blocks is set) and the
// mean and amplitude of the pad friction in summary.json (Ferre 2018 eqs. 4.1-4.2). Each keeps
// its state in a checkpoint under its own name: the two files how many rows and bytes of
// them it covers (a resumed run cuts them back to that and appends), the statistics their
// sums.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/observers/observer.hpp"
#include "io/output.hpp"

namespace bkq {

// How much of a streamed CSV file a checkpoint covers, kept under the file's name.
struct CsvExtent {
  std::int64_t rows = 0;
  std::uint64_t bytes = 0;
};
void put_csv_extent(Checkpoint& c, const std::string& name, const CsvExtent& e);
// Throws bkq::Error when the checkpoint holds none for `name`.
CsvExtent find_csv_extent(const Checkpoint& c, const std::string& name);

// A CSV file written one row per sample, checkpointed as a CsvExtent under its file name.
class SampledCsv : public RunObserver {
 public:
  // `append`: continue the file of a resumed run (already cut back to its checkpoint).
  SampledCsv(std::string path, bool append) : path_(std::move(path)), append_(append) {}
  void on_resume(const Checkpoint& c) override;
  void on_start() override { csv_ = std::make_unique<CsvStream>(path_, header(), append_); }
  void on_checkpoint(Checkpoint& c) override;
  void on_end(const RunEnd&) override { csv_->close(); }
  // The file name the extent is kept under ("timeseries.csv").
  std::string name() const;

 protected:
  virtual std::string header() const = 0;
  void row(const std::string& line) {
    csv_->row(line);
    ++rows_;
  }

 private:
  std::string path_;
  bool append_;
  std::int64_t rows_ = 0;  // over all sessions
  std::unique_ptr<CsvStream> csv_;
};

class TimeSeriesWriter : public SampledCsv {
 public:
  // status: append the node-status columns (output.status; io/timeseries.hpp).
  TimeSeriesWriter(std::string path, bool append, bool status = false)
      : SampledCsv(std::move(path), append), status_(status) {}
  void on_sample(const Sample& s) override;

 private:
  std::string header() const override;
  bool status_ = false;
};

// Lab-frame displacement and velocity of the blocks first .. first+count-1 at each sample.
class BlockTrajectories : public SampledCsv {
 public:
  BlockTrajectories(std::string path, bool append, int first, int count);
  void on_sample(const Sample& s) override;

 private:
  std::string header() const override;
  int first_;
  std::vector<double> u_, v_;
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
  void on_resume(const Checkpoint& c) override;
  void on_checkpoint(Checkpoint& c) override;
  void add_to_summary(Json& summary) const override;

 private:
  double sum_ = 0, sum_sq_ = 0;
  std::int64_t samples_ = 0;
};

}  // namespace bkq
