// Energy diagnostics; see energy.hpp.
#include "app/observers/energy.hpp"

#include <cmath>

#include "app/observers/timeseries.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/continuous.hpp"
#include "io/checkpoint.hpp"
#include "io/energy_csv.hpp"
#include "io/json.hpp"
#include "model/equilibrium.hpp"

namespace bkq {

WindowedMeans::Row WindowedMeans::row(long k, const Acc& a) const {
  Row r;
  r.t = k * half_;
  r.samples = a.n;
  r.energy = a.e / a.n;
  r.rate = a.n_rate ? a.rate / a.n_rate : std::nan("");
  r.braking = a.brake / a.n;
  return r;
}

std::vector<WindowedMeans::Row> WindowedMeans::add(double t, double energy, double braking) {
  // Window k covers [(k - 1) h, (k + 1) h], h = half a window; k >= 1 (complete windows).
  const double eps = 1e-9 * half_;
  const long lo = std::max(1L, static_cast<long>(std::ceil((t - eps) / half_ - 1.0)));
  const long hi = static_cast<long>(std::floor((t + eps) / half_ + 1.0));
  const bool has_rate = prev_t_ && t > *prev_t_;
  const double rate = has_rate ? (energy - *prev_e_) / (t - *prev_t_) : 0.0;
  for (long k = lo; k <= hi; ++k) {
    Acc& a = open_[k];
    ++a.n;
    a.e += energy;
    a.brake += braking;
    if (has_rate) {
      ++a.n_rate;
      a.rate += rate;
    }
  }
  prev_t_ = t;
  prev_e_ = energy;
  std::vector<Row> done;
  while (!open_.empty() && (open_.begin()->first + 1) * half_ < t - eps) {
    done.push_back(row(open_.begin()->first, open_.begin()->second));
    open_.erase(open_.begin());
  }
  return done;
}

std::vector<WindowedMeans::Row> WindowedMeans::finish(double t_end) {
  std::vector<Row> done;
  for (const auto& [k, a] : open_)
    if ((k + 1) * half_ <= t_end + 1e-9 * half_) done.push_back(row(k, a));
  open_.clear();
  return done;
}

// Layout: has a previous sample, its t and E, the number of open windows, then k, n,
// n_rate, e, rate, brake of each.
std::vector<double> WindowedMeans::state() const {
  std::vector<double> s = {prev_t_ ? 1.0 : 0.0, prev_t_.value_or(0.0), prev_e_.value_or(0.0),
                           static_cast<double>(open_.size())};
  for (const auto& [k, a] : open_)
    s.insert(s.end(), {static_cast<double>(k), static_cast<double>(a.n),
                       static_cast<double>(a.n_rate), a.e, a.rate, a.brake});
  return s;
}

void WindowedMeans::restore(const std::vector<double>& s) {
  if (s.size() < 4 || s.size() != 4 + 6 * static_cast<std::size_t>(s[3]))
    throw Error("--resume: the checkpoint's energy windows are malformed");
  prev_t_.reset();
  prev_e_.reset();
  if (s[0] != 0.0) {
    prev_t_ = s[1];
    prev_e_ = s[2];
  }
  open_.clear();
  for (std::size_t i = 4; i < s.size(); i += 6)
    open_[static_cast<long>(s[i])] =
        Acc{static_cast<int>(s[i + 1]), static_cast<int>(s[i + 2]), s[i + 3], s[i + 4], s[i + 5]};
}

std::optional<double> settle_time(const std::vector<WindowedMeans::Row>& rows, double tol) {
  std::optional<double> t;
  for (auto it = rows.rbegin(); it != rows.rend(); ++it) {
    if (!(std::abs(it->tau()) <= tol)) break;
    t = it->t;
  }
  return t;
}

EnergyDiagnostics::EnergyDiagnostics(const ChainForces& forces, std::string samples_path,
                                     std::string windows_path, double window, double tol,
                                     bool append)
    : forces_(forces),
      samples_path_(std::move(samples_path)),
      windows_path_(std::move(windows_path)),
      tol_(tol),
      append_(append),
      means_(window) {
  delta_.resize(forces.n());
}

namespace {
constexpr const char* kEnergyStateName = "energy";
}  // namespace

void EnergyDiagnostics::on_resume(const Checkpoint& c) {
  std::vector<double> windows, rows;
  if (!find_state(c, kEnergyStateName, windows, rows, t_last_))
    throw Error("--resume: the checkpoint holds no energy diagnostics (output.energy)");
  means_.restore(windows);
  if (rows.size() % 5 != 0) throw Error("--resume: the checkpoint's energy rows are malformed");
  rows_.clear();
  for (std::size_t i = 0; i < rows.size(); i += 5)
    rows_.push_back(
        {rows[i], static_cast<int>(rows[i + 1]), rows[i + 2], rows[i + 3], rows[i + 4]});
  sample_rows_ = find_csv_extent(c, "energy_samples.csv").rows;
}

// Files synced first, so a checkpoint never counts rows that are not on disk.
void EnergyDiagnostics::on_checkpoint(Checkpoint& c) {
  put_csv_extent(c, "energy_samples.csv", {sample_rows_, samples_->sync()});
  put_csv_extent(c, "energy.csv", {static_cast<std::int64_t>(rows_.size()), windows_->sync()});
  std::vector<double> rows;
  for (const auto& r : rows_)
    rows.insert(rows.end(), {r.t, static_cast<double>(r.samples), r.energy, r.rate, r.braking});
  put_state(c, kEnergyStateName, means_.state(), rows, t_last_);
}

void EnergyDiagnostics::on_start() {
  samples_ =
      std::make_unique<CsvStream>(samples_path_, header_of(energy_samples_schema()), append_);
  windows_ = std::make_unique<CsvStream>(windows_path_, header_of(energy_schema()), append_);
}

double EnergyDiagnostics::energy(const ChainState& st, const SubstrateState& sub) {
  const ModelParams& p = forces_.params();
  if (sub.v != eq_speed_) {
    // The reference state at this speed: steady sliding, or the zero position without it.
    const SlidingEquilibrium eq = sliding_equilibrium(p, sub.v);
    eq_u_ = eq.exists() ? eq.u : std::vector<double>(p.n, 0.0);
    eq_x_ = eq.exists() ? eq.x : 0.0;
    eq_speed_ = sub.v;
  }
  for (int j = 0; j < p.n; ++j) delta_.w[j] = st.w[j] - sub.s - eq_u_[j];
  delta_.s = 0;
  delta_.x = st.x - eq_x_;
  return forces_.spring_energy(delta_) + forces_.kinetic_energy(st, sub.v);
}

void EnergyDiagnostics::on_sample(const Sample& s) {
  const ChainState& st = s.driver.state();
  const ModelParams& p = forces_.params();
  const double e = energy(st, s.driver.substrate());
  const double nb = p.pad_moves() ? p.k_p0 * st.x + p.c_p * st.xd : 0.0;
  samples_->row(format_real(st.t) + "," + format_real(e) + "," + format_real(nb));
  ++sample_rows_;
  write(means_.add(st.t, e, nb));
  t_last_ = st.t;
}

void EnergyDiagnostics::write(const std::vector<WindowedMeans::Row>& rows) {
  for (const auto& r : rows) {
    windows_->row(format_real(r.t) + "," + std::to_string(r.samples) + "," + format_real(r.energy) +
                  "," + format_real(r.rate) + "," + format_real(r.tau()) + "," +
                  format_real(r.braking));
    rows_.push_back(r);
  }
}

void EnergyDiagnostics::on_end(const RunEnd&) {
  write(means_.finish(t_last_));
  samples_->close();
  windows_->close();
}

void EnergyDiagnostics::add_to_summary(Json& summary) const {
  const auto t = settle_time(rows_, tol_);
  summary.set("energy_settle_time", t ? Json::number(*t) : Json::null());
  summary.set("energy_windows", static_cast<std::int64_t>(rows_.size()));
}

}  // namespace bkq
