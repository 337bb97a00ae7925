// Energy diagnostics of continuous runs (output.energy; Sinou, Chiello & Charroyer 2019
// §4.3.2-4.3.3). At every sample: the mechanical energy of blocks and pad measured from
// the sliding equilibrium at the current speed, E = 1/2 du^T K du + 1/2 u'^T M u'
// (energy_samples.csv, with the braking force N_b = k_p0 x + c_p x'); over windows of
// output.energy_window with 50 % overlap (centres at multiples of half a window, complete
// windows only) the means of E, of E_t = dE/dt between samples and of N_b, and
// tau_E = mean(E_t)/mean(E) (energy.csv). The settle time — the first window centre
// after which |tau_E| <= output.energy_tol in every window — goes into summary.json
// (null if never). Costs O(N) per sample, nothing when off. Resumable: the open windows,
// the finished rows (for the settle time) and both files' extents go into the checkpoint
// under "energy" and the files' names.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/observers/observer.hpp"
#include "io/output.hpp"
#include "model/chain.hpp"

namespace bkq {

// The windowed means (streamed): feed samples in time order.
class WindowedMeans {
 public:
  struct Row {
    double t = 0;
    int samples = 0;
    double energy = 0, rate = 0, braking = 0;
    double tau() const { return rate / energy; }
  };
  explicit WindowedMeans(double window) : half_(0.5 * window) {}
  // Adds one sample; returns the windows completed by it (their end lies before t).
  std::vector<Row> add(double t, double energy, double braking);
  // The windows that end by t_end (complete), at the end of the run.
  std::vector<Row> finish(double t_end);
  // Everything add() carries (the open windows, the previous sample) as plain numbers, and
  // back; restore throws bkq::Error on numbers of another shape.
  std::vector<double> state() const;
  void restore(const std::vector<double>& s);

 private:
  struct Acc {
    int n = 0, n_rate = 0;
    double e = 0, rate = 0, brake = 0;
  };
  Row row(long k, const Acc& a) const;
  double half_;
  std::map<long, Acc> open_;
  std::optional<double> prev_t_, prev_e_;
};

// The first window centre from which on |tau| <= tol in every window; nullopt if none.
std::optional<double> settle_time(const std::vector<WindowedMeans::Row>& rows, double tol);

class EnergyDiagnostics : public RunObserver {
 public:
  // `append`: continue the files of a resumed run (already cut back to its checkpoint).
  EnergyDiagnostics(const ChainForces& forces, std::string samples_path, std::string windows_path,
                    double window, double tol, bool append = false);
  void on_resume(const Checkpoint& c) override;
  void on_checkpoint(Checkpoint& c) override;
  void on_start() override;
  void on_sample(const Sample& s) override;
  void on_end(const RunEnd& end) override;
  void add_to_summary(Json& summary) const override;

 private:
  void write(const std::vector<WindowedMeans::Row>& rows);
  double energy(const ChainState& st, const SubstrateState& sub);

  const ChainForces& forces_;
  std::string samples_path_, windows_path_;
  double tol_;
  bool append_;
  std::int64_t sample_rows_ = 0;  // rows of energy_samples.csv, all sessions
  WindowedMeans means_;
  std::vector<WindowedMeans::Row> rows_;
  std::unique_ptr<CsvStream> samples_, windows_;
  double eq_speed_ = -1;
  std::vector<double> eq_u_;
  double eq_x_ = 0;
  ChainState delta_;
  double t_last_ = 0;
};

}  // namespace bkq
