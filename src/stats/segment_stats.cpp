// Streamed segment statistics; see segment_stats.hpp.
#include "stats/segment_stats.hpp"

#include <algorithm>
#include <cmath>

namespace bkq {

BlockedMoments::BlockedMoments(std::int64_t n, int blocks) : n_(std::max<std::int64_t>(n, 0)) {
  const std::int64_t m = std::clamp<std::int64_t>(std::min<std::int64_t>(blocks, n_), 1, 1 << 30);
  parts_.resize(static_cast<std::size_t>(m));
  block_size_ = std::max<std::int64_t>(n_ / m, 1);
}

void BlockedMoments::add(double x) {
  const auto last = static_cast<std::int64_t>(parts_.size()) - 1;
  Part& p = parts_[static_cast<std::size_t>(std::min(added_ / block_size_, last))];
  ++p.n;
  const double d = x - p.mean;
  p.mean += d / static_cast<double>(p.n);
  p.m2 += d * (x - p.mean);
  ++added_;
}

std::vector<double> BlockedMoments::state() const {
  std::vector<double> s{static_cast<double>(added_)};
  for (const Part& p : parts_) s.insert(s.end(), {static_cast<double>(p.n), p.mean, p.m2});
  return s;
}

bool BlockedMoments::set_state(const std::vector<double>& s) {
  if (s.size() != 1 + 3 * parts_.size()) return false;
  added_ = static_cast<std::int64_t>(s[0]);
  for (std::size_t i = 0; i < parts_.size(); ++i)
    parts_[i] = {static_cast<std::int64_t>(s[1 + 3 * i]), s[2 + 3 * i], s[3 + 3 * i]};
  return added_ >= 0 && added_ <= n_;
}

SegmentStat BlockedMoments::result() const {
  // Whole input: the blocks combined exactly.
  Part all;
  for (const Part& p : parts_) {
    if (p.n == 0) continue;
    const auto n = static_cast<double>(all.n + p.n);
    const double d = p.mean - all.mean;
    all.m2 += p.m2 + d * d * static_cast<double>(all.n) * static_cast<double>(p.n) / n;
    all.mean += d * static_cast<double>(p.n) / n;
    all.n += p.n;
  }
  SegmentStat s;
  if (all.n == 0) return s;
  auto amplitude = [](const Part& p) { return std::sqrt(2.0 * p.m2 / static_cast<double>(p.n)); };
  s.mean = all.mean;
  s.amp = amplitude(all);
  double var_mean = 0, var_amp = 0;
  int m = 0;
  for (const Part& p : parts_) {
    if (p.n == 0) continue;
    ++m;
    var_mean += (p.mean - s.mean) * (p.mean - s.mean);
    var_amp += (amplitude(p) - s.amp) * (amplitude(p) - s.amp);
  }
  // eq. 4.3 (normalised by M) and eq. 4.4.
  s.mean_err = std::sqrt(var_mean / m) / std::sqrt(static_cast<double>(m));
  s.amp_err = std::sqrt(var_amp / m) / std::sqrt(static_cast<double>(m));
  return s;
}

StepRange input_steps(double t_start, double t_end, double dt) {
  const double tol = 1e-9 * dt;
  const double mid = t_start + 0.5 * (t_end - t_start);
  StepRange r;
  r.first = static_cast<std::int64_t>(std::floor((mid + tol) / dt)) + 1;
  r.last = static_cast<std::int64_t>(std::floor((t_end + tol) / dt));
  // Guard the floors against rounding of i dt itself.
  while (r.first > 1 && static_cast<double>(r.first - 1) * dt > mid + tol) --r.first;
  while (static_cast<double>(r.first) * dt <= mid + tol) ++r.first;
  while (static_cast<double>(r.last + 1) * dt <= t_end + tol) ++r.last;
  while (r.last >= 1 && static_cast<double>(r.last) * dt > t_end + tol) --r.last;
  return r;
}

}  // namespace bkq
