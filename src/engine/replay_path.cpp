// The replayed event start (see replay_path.hpp).
#include "engine/replay_path.hpp"

#include <algorithm>
#include <cmath>

namespace bkq {

bool ReplayPath::advance(Relaxation& rx, PathReport& out) {
  if (rx.steps != 0) return false;
  const int j = rx.trigger;
  const ModelParams& p = rx.forces.params();
  const bool periodic = p.boundary == Boundary::Periodic;
  const bool lattice = rx.forces.lattice();
  // Located transitions (the wrapper of a fixed-step scheme): the record is the located
  // stepper's, and a neighbour's failure is left to the general path (lone_slip.hpp).
  const bool located = rx.traits.located_on_fixed_steps;
  // A lattice's general kernel is the chain's equation with more springs: the lone site's
  // slide is recorded per stiffness as a block's is. Long-range chains and dashpots are not.
  if (!rx.replay || rx.pad || (rx.traits.stick_rule != StickRule::Crossing && !located) ||
      (!lattice && periodic && rx.forces.n() == 2) || (rx.forces.general_kernel() && !lattice) ||
      rx.forces.viscous())
    return false;
  const LoneSlip& table = lattice ? lattice_lone_slip(rx, j) : chain_lone_slip(rx, j);
  const auto last = static_cast<std::int64_t>(table.steps.size());
  if (!table.usable || last > rx.max_steps) return false;

  const double* w = rx.st.w.data();
  const double a = rx.anchor(), thr = rx.forces.friction().threshold;
  const bool backslip = rx.forces.friction().backslip;
  const LoneSlip::Step& end = table.steps.back();
  const double scale = std::abs(w[j]) + std::abs(a) + std::max(end.d_max, -end.d_min);
  const LoneSlipTolerance tol = lattice
                                    ? lone_slip_tolerance(p, scale, rx.dt, last, lattice_coupled_)
                                    : lone_slip_tolerance(p, scale, rx.dt, last);
  const double f0 = rx.forces.spring_force(w, j, a);
  bool clear = std::abs(f0 - thr) <= tol.force && table.force_margin > 2.0 * tol.force &&
               table.velocity_margin > 2.0 * tol.velocity;
  // Each partner breaks at the first step n where its force f + k d_n passes the threshold,
  // i.e. where f + k times the running extreme of d does (monotone in n); k is the spring
  // between them. How far past the threshold a partner of force f is after step n (n = 0:
  // the start).
  auto excess = [&](double f, double k, std::int64_t n) {
    const double hi = n == 0 ? 0.0 : table.steps[n - 1].d_max,
                 lo = n == 0 ? 0.0 : table.steps[n - 1].d_min;
    return backslip ? std::max(f + k * hi - thr, -thr - (f + k * lo)) : f + k * hi - thr;
  };
  std::int64_t first_break = last + 1;
  for (std::size_t i = 0; i < partners_.size() && clear; ++i) {
    Partner& q = partners_[i];
    const double f = rx.forces.spring_force(w, q.site, a);
    const auto n = std::partition_point(table.steps.begin(), table.steps.end(),
                                        [&](const LoneSlip::Step& s) {
                                          return excess(f, q.k, &s - table.steps.data() + 1) <= 0.0;
                                        }) -
                   table.steps.begin() + 1;
    q.breaks_at = n;
    first_break = std::min(first_break, n);
    // Both sides of the decision clear of the bound: before step n it holds, after it not.
    clear = excess(f, q.k, n - 1) < -tol.force && (n > last || excess(f, q.k, n) > tol.force);
  }
  if (!clear) {
    ++starts_.declined;
    return false;
  }

  // Located: up to the step before the first failure, which the general path locates.
  const std::int64_t stop = std::min(last, located ? first_break - 1 : first_break);
  if (stop == 0) {
    ++starts_.immediate;
    return false;
  }
  const LoneSlip::Step& s = table.steps[stop - 1];
  rx.st.w[j] += s.d;
  rx.st.wd[j] = s.v;
  rx.st.mobile[j] = s.sliding ? 1.0 : 0.0;
  rx.st.dir[j] = s.dir;
  rx.st.t = s.t;
  rx.dissipated += s.work;
  released_.clear();
  // In site order: the order in which the general path's contact pass releases them.
  for (const Partner& q : partners_)
    if (q.breaks_at == stop && !located) released_.push_back(q.site);
  const int released = static_cast<int>(released_.size());
  out.steps = stop;
  for (const Range& r : rx.active.ranges()) out.block_steps += (r.hi - r.lo) * stop;
  out.sliding_block_steps = s.sliding_steps + released;
  out.sliding = s.sliding + released;
  out.max_speed = s.max_speed;
  out.stick_time = located && s.sliding == 0 ? table.stick_time : rx.stepper.located_stick_time();
  out.released = released_;
  ++starts_.replayed;
  starts_.steps += stop;
  if (out.sliding == 0) ++starts_.finished;
  return true;
}

const LoneSlip& ReplayPath::chain_lone_slip(const Relaxation& rx, int j) {
  const ModelParams& p = rx.forces.params();
  const bool periodic = p.boundary == Boundary::Periodic;
  // The neighbours whose spring force the block's slide changes, in block order (the
  // order in which the general path would release them).
  partners_.clear();
  if (p.has_neighbours()) {
    if (periodic) {
      int left = (j + rx.forces.n() - 1) % rx.forces.n(), right = (j + 1) % rx.forces.n();
      if (left > right) std::swap(left, right);
      partners_.push_back(Partner{left, p.k_c});
      partners_.push_back(Partner{right, p.k_c});
    } else {
      if (j > 0) partners_.push_back(Partner{j - 1, p.k_c});
      if (j + 1 < rx.forces.n()) partners_.push_back(Partner{j + 1, p.k_c});
    }
  }
  const bool at_end = p.has_neighbours() && partners_.size() == 1;
  LoneSlip& table = lone_[at_end];
  if (!lone_built_[at_end]) {
    const double stiffness = p.k_p + (p.has_neighbours() ? (at_end ? 1.0 : 2.0) * p.k_c : 0.0);
    table = integrate_lone_slip(p, stiffness, rx.stepper, rx.dt, rx.max_steps,
                                rx.traits.located_on_fixed_steps);
    lone_built_[at_end] = true;
  }
  return table;
}

const LoneSlip& ReplayPath::lattice_lone_slip(const Relaxation& rx, int j) {
  // The site's partners with the spring to each (two springs to one site, across a narrow
  // periodic lattice, add up), in site order; its stiffness k_p plus those springs, summed
  // in the stencil's order so that sites alike get the same bits and share one record.
  partners_.clear();
  const int nx = rx.forces.nx(), x = j % nx, y = j / nx;
  double coupled = 0;
  for (const LatticeSpring& c : rx.forces.lattice_stencil()) {
    for (const int sign : {-1, 1})
      if (const int i = rx.forces.site(x + sign * c.dx, y + sign * c.dy); i >= 0) {
        partners_.push_back(Partner{i, c.k});
        coupled += c.k;
      }
  }
  std::sort(partners_.begin(), partners_.end(),
            [](const Partner& l, const Partner& r) { return l.site < r.site; });
  std::size_t kept = 0;
  for (std::size_t i = 0; i < partners_.size(); ++i) {
    if (kept > 0 && partners_[kept - 1].site == partners_[i].site)
      partners_[kept - 1].k += partners_[i].k;
    else
      partners_[kept++] = partners_[i];
  }
  partners_.resize(kept);
  const double stiffness = rx.forces.params().k_p + coupled;
  for (const LoneSlip& t : lattice_lone_)
    if (t.stiffness == stiffness) return t;
  if (lattice_lone_.empty()) {
    // The rounding bound's stiffness: an interior site's springs, every spring twice.
    lattice_coupled_ = 0;
    for (const LatticeSpring& c : rx.forces.lattice_stencil()) lattice_coupled_ += 2.0 * c.k;
  }
  lattice_lone_.push_back(integrate_lone_slip(rx.forces.params(), stiffness, rx.stepper, rx.dt,
                                              rx.max_steps, rx.traits.located_on_fixed_steps));
  return lattice_lone_.back();
}

}  // namespace bkq
