// The event-driven engine; see event_engine.hpp for the algorithm and the definition of
// the end of an event.
#include "engine/event_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/contacts.hpp"
#include "integrate/cluster.hpp"
#include "integrate/located.hpp"
#include "model/damped_oscillator.hpp"

namespace bkq {

namespace {
// Ranges are re-fitted to the sliding blocks every this many steps.
constexpr int kShrinkEvery = 16;
// The pad's sum of block positions is re-summed from scratch every this many events.
constexpr int kResumEvery = 1024;
// Stuck blocks covered on each side of a sliding block: those its springs reach (one, or R
// with range coupling); twice that for the adaptive stepper, which locates releases inside
// its step (a block released mid-step reaches as far again). The located wrapper of a
// fixed-step scheme adds the neighbours of a block it releases to its step itself
// (located.hpp).
int margin_for(const ChainForces& forces, const Stepper& stepper) {
  const bool adds_own = dynamic_cast<const LocatedTransitions*>(&stepper) != nullptr;
  return (stepper.stick_rule() == StickRule::Located && !adds_own ? 2 : 1) * forces.reach();
}
}  // namespace

namespace {
// Steppers that place transitions inside their step (theta's projection, the adaptive scheme,
// the located wrapper) read and cover only j +- 1: lattices, couplings beyond the nearest
// neighbours and dashpots need a Crossing scheme (the scene refuses the others; this holds for
// every caller).
void check_stepper(const ChainForces& forces, const Stepper& stepper) {
  if (!forces.general_kernel()) return;
  if (stepper.stick_rule() == StickRule::Crossing &&
      dynamic_cast<const LocatedTransitions*>(&stepper) == nullptr)
    return;
  throw Error("the " + std::string(stepper.name()) +
              " stepper (transitions inside its step) is written for chains of "
              "nearest-neighbour springs without dashpots; this model needs rk2, rk4 or verlet "
              "with transitions at the step");
}
}  // namespace

EventEngine::EventEngine(const ChainForces& forces, Stepper& stepper, double dt, ChainState state)
    : forces_(forces),
      stepper_(stepper),
      dt_(dt),
      st_(std::move(state)),
      pad_(forces.params().pad_moves()),
      n_(forces.n()),
      margin_(margin_for(forces, stepper)) {
  check_model(forces.params());
  check_stepper(forces, stepper);
  allocate_bookkeeping();
  std::fill(st_.mobile.begin(), st_.mobile.end(), 0.0);
  std::fill(st_.wd.begin(), st_.wd.end(), 0.0);
  st_.xd = 0;
  st_.recompute_sum_w();
  if (pad_) st_.x = forces_.pad_equilibrium(st_.sum_w, st_.s);
  rebuild_tree();
}

EventEngine::EventEngine(const ChainForces& forces, Stepper& stepper, double dt,
                         const EngineSnapshot& saved)
    : forces_(forces),
      stepper_(stepper),
      dt_(dt),
      st_(saved.state),
      pad_(forces.params().pad_moves()),
      n_(forces.n()),
      margin_(margin_for(forces, stepper)),
      counters_(saved.counters) {
  check_model(forces.params());
  check_stepper(forces, stepper);
  if (st_.n() != n_)
    throw Error("checkpoint: it holds " + std::to_string(st_.n()) + " blocks, the scene has " +
                std::to_string(n_));
  allocate_bookkeeping();
  rebuild_tree();
}

void EventEngine::allocate_bookkeeping() {
  covered_.assign(n_, 0);
  need_.assign(n_, 0);
  slipped_.assign(n_, 0);
  w_before_.assign(n_, 0.0);
}

void EventEngine::check_model(const ModelParams& p) {
  check_law_drives_events(p);
  // The relaxation's fast paths (the lone slip's closed form, the held-range and cluster
  // kernels) have no block damping, and with the substrate frozen an event has no sliding
  // state for the damping to be measured from: it is a continuous runs' effect.
  if (p.rayleigh_alpha != 0 || p.rayleigh_beta != 0)
    throw Error("model.rayleigh_alpha = " + format_real(p.rayleigh_alpha) +
                ", model.rayleigh_beta = " + format_real(p.rayleigh_beta) +
                ": Rayleigh block damping applies in continuous runs only (drive.mode = "
                "continuous); event runs need both 0");
}

void EventEngine::rebuild_tree() {
  tree_.reset(n_);
  tree_.set_range(0, n_, [&](int j) { return forces_.local_force(st_.w.data(), j); });
}

double EventEngine::worst_stuck_excess() const {
  const double a = anchor(), thr = forces_.friction().threshold;
  double worst = -HUGE_VAL;
  for (int j = 0; j < n_; ++j) {
    if (st_.mobile[j] != 0.0) continue;
    const double f = forces_.spring_force(st_.w.data(), j, a);
    worst = std::max(worst, (forces_.friction().backslip ? std::abs(f) : f) - thr);
  }
  return worst;
}

void EventEngine::add_to_ranges(int k) {
  // Ranges stay sorted and disjoint; adjacent ones merge.
  auto it = std::lower_bound(ranges_.begin(), ranges_.end(), k,
                             [](const Range& r, int v) { return r.hi < v; });
  if (it != ranges_.end() && it->lo <= k && k < it->hi) return;
  if (it != ranges_.end() && it->hi == k) {
    it->hi = k + 1;
    auto next = it + 1;
    if (next != ranges_.end() && next->lo == it->hi) {
      it->hi = next->hi;
      ranges_.erase(next);
    }
    return;
  }
  if (it != ranges_.end() && it->lo == k + 1) {
    it->lo = k;
    return;
  }
  ranges_.insert(it, Range{k, k + 1});
}

void EventEngine::cover(int j) {
  // A sliding block and `margin_` neighbours on each side are integrated (the kernels
  // read j±1; a stepper that locates releases inside its step needs the next block too).
  // On a lattice: the site and its stencil's partners, the sites whose force it changes.
  auto add = [&](int k) {
    if (covered_[k]) return;
    covered_[k] = 1;
    // The tree answers for uncovered blocks while the pad swings; with the pad held it is
    // not asked during the event, and every covered block is put back when uncovered.
    if (pad_) tree_.remove(k);
    add_to_ranges(k);
  };
  if (forces_.lattice()) {
    add(j);
    forces_.for_each_partner(j, add);
    return;
  }
  const bool periodic = forces_.params().boundary == Boundary::Periodic;
  for (int d = -margin_; d <= margin_; ++d) {
    int k = j + d;
    if (k < 0 || k >= n_) {
      if (!periodic) continue;
      k = ((k % n_) + n_) % n_;
    }
    add(k);
  }
}

void EventEngine::note_slipped(int j, double w_at_release) {
  if (slipped_[j]) return;  // only its first release in the event counts
  slipped_[j] = 1;
  slipped_list_.push_back(j);
  w_before_[j] = w_at_release;
}

void EventEngine::release(int j) {
  ++counters_.releases;
  st_.mobile[j] = 1.0;
  st_.wd[j] = 0.0;
  st_.dir[j] = std::copysign(1.0, forces_.holding_force(st_.w.data(), st_.wd.data(), j, anchor()));
  note_slipped(j, st_.w[j]);
  cover(j);
}

void EventEngine::shrink_ranges() {
  const bool periodic = forces_.params().boundary == Boundary::Periodic;
  const bool lattice = forces_.lattice();
  for (const Range& r : ranges_)
    for (int j = r.lo; j < r.hi; ++j) {
      if (st_.mobile[j] == 0.0) continue;
      if (lattice) {
        need_[j] = 1;
        forces_.for_each_partner(j, [&](int k) { need_[k] = 1; });
        continue;
      }
      for (int d = -margin_; d <= margin_; ++d) {
        const int k = j + d;
        if (k >= 0 && k < n_)
          need_[k] = 1;
        else if (periodic)
          need_[((k % n_) + n_) % n_] = 1;
      }
    }
  std::vector<Range> kept;
  kept.reserve(ranges_.size());
  const double* w = st_.w.data();
  auto local_force = [&](int j) { return forces_.local_force(w, j); };
  for (const Range& r : ranges_) {
    // Alternating runs of needed blocks (kept) and the others (uncovered).
    for (int j = r.lo; j < r.hi;) {
      const int start = j;
      const bool needed = need_[j];
      for (; j < r.hi && need_[j] == needed; ++j) need_[j] = 0, covered_[j] = needed;
      if (needed)
        kept.push_back(Range{start, j});
      else
        tree_.set_range(start, j, local_force);
    }
  }
  ranges_.swap(kept);
}

void EventEngine::uncover_all() {
  const double* w = st_.w.data();
  for (const Range& r : ranges_) {
    std::fill(covered_.begin() + r.lo, covered_.begin() + r.hi, 0);
    tree_.set_range(r.lo, r.hi, [&](int j) { return forces_.local_force(w, j); });
  }
  ranges_.clear();
}

bool EventEngine::query_tree_failures() {
  // Stuck, uncovered blocks feel only the pad's motion; ask the tree who broke.
  const double thr = forces_.friction().threshold, kp = forces_.params().k_p;
  const bool backslip = forces_.friction().backslip;
  bool any = false;
  for (;;) {
    const double a = anchor();
    if (tree_.max() + kp * a > thr) {
      release(tree_.argmax());
    } else if (backslip && tree_.min() + kp * a < -thr) {
      release(tree_.argmin());
    } else {
      break;
    }
    ++sliding_;
    any = true;
  }
  return any;
}

bool EventEngine::pad_phase() {
  // Every block is stuck: m_x xi'' + c_p xi' + K xi = 0 about the rest position.
  uncover_all();
  const ModelParams& p = forces_.params();
  const double thr = forces_.friction().threshold;
  const double K = p.k_p0 + p.n * p.k_p;
  const double x_eq = forces_.pad_equilibrium(st_.sum_w, st_.s);
  const DampedOscillator osc(p.m_x, p.c_p, K, st_.x - x_eq, st_.xd);
  // Block j breaks when x crosses hi (or lo, for laws with backslip).
  const double hi = (thr - tree_.max()) / p.k_p - st_.s;
  const double lo = forces_.friction().backslip ? (-thr - tree_.min()) / p.k_p - st_.s : -HUGE_VAL;
  const double margin = std::min(hi - x_eq, x_eq - lo);
  auto breaks = [&](double t) {
    const double x = x_eq + osc.position(t);
    return x > hi || x < lo;
  };
  const double dt = osc.resolution();
  // The pad's energy about its rest position; what it loses here is the damper's work.
  auto pad_energy = [&](double xi, double v) { return 0.5 * (p.m_x * v * v + K * xi * xi); };
  const double e_start = pad_energy(st_.x - x_eq, st_.xd);
  double t = 0;
  // Walk the closed-form solution until its envelope can no longer reach either level.
  for (std::int64_t i = 0; osc.bound_after(t) >= margin && i < 10'000'000; ++i) {
    if (!breaks(t + dt)) {
      t += dt;
      continue;
    }
    double a = t, b = t + dt;
    for (int k = 0; k < 200 && b - a > 1e-13 * (1.0 + b); ++k) {
      const double m = 0.5 * (a + b);
      (breaks(m) ? b : a) = m;
    }
    st_.x = x_eq + osc.position(b);
    st_.xd = osc.velocity(b);
    st_.t += b;
    dissipated_ += e_start - pad_energy(osc.position(b), st_.xd);
    // The located block fails now, even if at b its force rounds to the threshold itself.
    release(st_.x > hi ? tree_.argmax() : tree_.argmin());
    ++sliding_;
    query_tree_failures();
    return true;
  }
  st_.x = x_eq;
  st_.xd = 0;
  dissipated_ += e_start;
  return false;
}

void EventEngine::note_released_in_step() {
  // The stepper's own list first (it knows blocks that broke loose and stuck again inside
  // the step, and where they were), then any block whose flag went from stuck to sliding.
  released_now_.clear();
  for (const Stepper::Release& r : stepper_.releases_in_step()) {
    note_slipped(r.block, r.w);
    released_now_.push_back(r.block);
  }
  for (std::size_t i = 0; i < ranges_.size(); ++i) {
    const double* mobile_old = old_.data(kMobileOld, i);
    const double* w_old = old_.data(kWOld, i);
    for (int j = ranges_[i].lo; j < ranges_[i].hi; ++j)
      if (st_.mobile[j] != 0.0 && mobile_old[j] == 0.0) {
        // Stuck, so unmoved, until it broke loose inside the step. It may have slipped
        // earlier in the event: cover it again all the same.
        note_slipped(j, w_old[j]);
        released_now_.push_back(j);
      }
  }
  counters_.releases += static_cast<std::int64_t>(released_now_.size());
  for (int j : released_now_) cover(j);
}

double EventEngine::stored_energy_change(double x0) const {
  const ModelParams& p = forces_.params();
  const double* w = st_.w.data();
  auto before = [&](int k) { return slipped_[k] ? w_before_[k] : w[k]; };
  const double s = st_.s, x1 = pad_ ? st_.x : 0.0;
  x0 = pad_ ? x0 : 0.0;
  double e_pull = 0, e_bond = 0, sum_slipped = 0;
  const bool periodic = p.boundary == Boundary::Periodic && n_ > 2;
  const bool bonds = p.has_neighbours();
  // The change over the event of (w_a - w_b)^2, for the spring between blocks a and b.
  auto bond = [&](int a, int b) {
    const double d1 = w[a] - w[b], d0 = before(a) - before(b);
    return d1 * d1 - d0 * d0;
  };
  // Each spring once: to the partner ahead (the right, +offset) always, to the one behind
  // only when it did not slip (else it is counted as that block's spring ahead).
  const int nx = forces_.nx();
  for (int j : slipped_list_) {
    const double d1 = w[j] - s - x1, d0 = before(j) - s - x0;
    e_pull += d1 * d1 - d0 * d0;
    sum_slipped += w[j];
    if (forces_.lattice()) {
      const int x = j % nx, y = j / nx;
      for (const LatticeSpring& c : forces_.lattice_stencil()) {
        double e = 0;
        if (const int r = forces_.site(x + c.dx, y + c.dy); r >= 0) e += bond(r, j);
        if (const int l = forces_.site(x - c.dx, y - c.dy); l >= 0 && !slipped_[l]) e += bond(j, l);
        e_bond += c.k * e;
      }
    } else if (forces_.long_range()) {
      for (const CouplingSpring& c : forces_.stencil()) {
        int right = j + c.offset, left = j - c.offset;
        if (periodic) {
          right = right >= n_ ? right - n_ : right;
          left = left < 0 ? left + n_ : left;
        }
        double e = 0;
        if (right < n_) e += bond(right, j);
        if (left >= 0 && !slipped_[left]) e += bond(j, left);
        e_bond += c.k * e;
      }
    } else if (bonds) {
      const int right = j + 1 < n_ ? j + 1 : (periodic ? 0 : -1);
      const int left = j > 0 ? j - 1 : (periodic ? n_ - 1 : -1);
      if (right >= 0) e_bond += bond(right, j);
      if (left >= 0 && !slipped_[left]) e_bond += bond(j, left);
    }
  }
  // With range coupling e_bond already holds each spring's stiffness.
  double de = 0.5 * p.k_p * e_pull +
              (forces_.long_range() || forces_.lattice() ? 0.5 : 0.5 * p.k_c) * e_bond;
  if (pad_) {
    // Blocks that did not slip only see the anchor move from s + x0 to s + x1.
    const double others = static_cast<double>(n_ - static_cast<int>(slipped_list_.size()));
    const double sum_others = st_.sum_w - sum_slipped - others * s;
    de += 0.5 * p.k_p * (x0 - x1) * (2.0 * sum_others - others * (x0 + x1));
    de += 0.5 * p.k_p0 * (x1 * x1 - x0 * x0);
  }
  return de;
}

bool EventEngine::held_ranges() const {
  // The fused held-range pass, the cluster kernels and the lone slip's record read only
  // j +- 1 and have no dashpots: a coupling of longer range or viscous takes the general step.
  if (!held_ranges_path || forces_.general_kernel()) return false;
  for (const Range& r : ranges_)
    if (st_.mobile[r.lo] != 0.0 || st_.mobile[r.hi - 1] != 0.0) return false;
  return true;
}

bool EventEngine::cluster_ready(ClusterRelaxation& r) const {
  // One covered range (so every sliding block is inside it) and at most kMaxCluster
  // blocks between its ends, which are stuck blocks or free chain ends (the stepper
  // refuses the shapes it has no code for: run_cluster).
  if (!cluster_path || stepper_.stick_rule() == StickRule::Projection || ranges_.size() != 1 ||
      forces_.general_kernel())
    return false;
  const Range& range = ranges_.front();
  const bool free_ends = forces_.params().boundary == Boundary::Free && n_ >= 2;
  r.free_left = free_ends && range.lo == 0 && st_.mobile[0] != 0.0;
  r.free_right = free_ends && range.hi == n_ && st_.mobile[n_ - 1] != 0.0;
  r.lo = range.lo - (r.free_left ? 1 : 0);
  r.k = range.hi - range.lo - 2 + (r.free_left ? 1 : 0) + (r.free_right ? 1 : 0);
  if (r.k < 1 || r.k > kMaxCluster) return false;
  return (r.free_left || st_.mobile[range.lo] == 0.0) &&
         (r.free_right || st_.mobile[range.hi - 1] == 0.0);
}

bool EventEngine::relax_cluster(ClusterRelaxation& r, std::int64_t& steps, ContactScan& scan) {
  const int k = r.k;
  r.anchor = anchor();
  r.sub = SubstrateState{st_.s, 0.0, 0.0};
  r.dt = dt_;
  r.half_dt_m = 0.5 * dt_ * forces_.params().m_u;
  // Stop at the step where the general path would give up on the event, and, with more
  // than one interior block, at the next shrink (it may split the range). A lone sliding
  // block keeps its range exactly as the shrink would leave it.
  r.max_steps = max_steps_per_event + 1 - steps;
  if (k > 1) r.max_steps = std::min<std::int64_t>(r.max_steps, kShrinkEvery - steps % kShrinkEvery);
  r.state = &st_;
  r.dissipated = &dissipated_;
  if (!(pad_ ? relax_pad_cluster(r) : stepper_.relax_cluster(forces_, r))) return false;
  // Located: the first step had a transition and was undone; the general path takes it.
  if (r.steps == 0) return false;
  // A shrink due inside a lone block's run changed nothing; the one due after the last
  // step, if any, the caller does.
  steps += r.steps;
  cluster_steps_.all += r.steps;
  if (k > 1) cluster_steps_.multi_block += r.steps;
  if (r.free_left) cluster_steps_.left_end += r.steps;
  if (r.free_right) cluster_steps_.right_end += r.steps;
  counters_.block_steps += (ranges_.front().hi - ranges_.front().lo) * r.steps;
  counters_.sliding_block_steps += r.sliding_block_steps;
  scan.sliding = r.sliding;
  scan.max_speed = r.max_speed;
  released_now_.assign(r.released.begin(), r.released.begin() + r.n_released);
  return true;
}

bool EventEngine::replay_start(int j, std::int64_t& steps, ContactScan& scan) {
  const ModelParams& p = forces_.params();
  const bool periodic = p.boundary == Boundary::Periodic;
  const bool lattice = forces_.lattice();
  // Located transitions (the wrapper of a fixed-step scheme): the record is the located
  // stepper's, and a neighbour's failure is left to the general path (lone_slip.hpp).
  const bool located = dynamic_cast<const LocatedTransitions*>(&stepper_) != nullptr;
  // A lattice's general kernel is the chain's equation with more springs: the lone site's
  // slide is recorded per stiffness as a block's is. Long-range chains and dashpots are not.
  if (!lone_slip_path || pad_ || (stepper_.stick_rule() != StickRule::Crossing && !located) ||
      (!lattice && periodic && n_ == 2) || (forces_.general_kernel() && !lattice) ||
      forces_.viscous())
    return false;
  const LoneSlip& table = lattice ? lattice_lone_slip(j) : chain_lone_slip(j);
  const auto last = static_cast<std::int64_t>(table.steps.size());
  if (!table.usable || last > max_steps_per_event) return false;

  const double* w = st_.w.data();
  const double a = anchor(), thr = forces_.friction().threshold;
  const bool backslip = forces_.friction().backslip;
  const LoneSlip::Step& end = table.steps.back();
  const double scale = std::abs(w[j]) + std::abs(a) + std::max(end.d_max, -end.d_min);
  const LoneSlipTolerance tol = lattice ? lone_slip_tolerance(p, scale, dt_, last, lattice_coupled_)
                                        : lone_slip_tolerance(p, scale, dt_, last);
  const double f0 = forces_.spring_force(w, j, a);
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
    const double f = forces_.spring_force(w, q.site, a);
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
    ++lone_starts_.declined;
    return false;
  }

  // Located: up to the step before the first failure, which the general path locates.
  const std::int64_t stop = std::min(last, located ? first_break - 1 : first_break);
  if (stop == 0) {
    ++lone_starts_.immediate;
    return false;
  }
  const LoneSlip::Step& s = table.steps[stop - 1];
  st_.w[j] += s.d;
  st_.wd[j] = s.v;
  st_.mobile[j] = s.sliding ? 1.0 : 0.0;
  st_.dir[j] = s.dir;
  st_.t = s.t;
  dissipated_ += s.work;
  released_now_.clear();
  // In site order: the order in which the general path's contact pass releases them.
  for (const Partner& q : partners_)
    if (q.breaks_at == stop && !located) released_now_.push_back(q.site);
  if (located && s.sliding == 0) replayed_stick_time_ = table.stick_time;
  const int released = static_cast<int>(released_now_.size());
  steps = stop;
  for (const Range& r : ranges_) counters_.block_steps += (r.hi - r.lo) * stop;
  counters_.sliding_block_steps += s.sliding_steps + released;
  scan.sliding = s.sliding + released;
  scan.max_speed = s.max_speed;
  ++lone_starts_.replayed;
  lone_starts_.steps += stop;
  if (scan.sliding == 0) ++lone_starts_.finished;
  return true;
}

const LoneSlip& EventEngine::chain_lone_slip(int j) {
  const ModelParams& p = forces_.params();
  const bool periodic = p.boundary == Boundary::Periodic;
  // The neighbours whose spring force the block's slide changes, in block order (the
  // order in which the general path would release them).
  partners_.clear();
  if (p.has_neighbours()) {
    if (periodic) {
      int left = (j + n_ - 1) % n_, right = (j + 1) % n_;
      if (left > right) std::swap(left, right);
      partners_.push_back(Partner{left, p.k_c});
      partners_.push_back(Partner{right, p.k_c});
    } else {
      if (j > 0) partners_.push_back(Partner{j - 1, p.k_c});
      if (j + 1 < n_) partners_.push_back(Partner{j + 1, p.k_c});
    }
  }
  const bool at_end = p.has_neighbours() && partners_.size() == 1;
  LoneSlip& table = lone_[at_end];
  if (!lone_built_[at_end]) {
    const double stiffness = p.k_p + (p.has_neighbours() ? (at_end ? 1.0 : 2.0) * p.k_c : 0.0);
    table = integrate_lone_slip(p, stiffness, stepper_.name(), dt_, max_steps_per_event,
                                dynamic_cast<const LocatedTransitions*>(&stepper_) != nullptr);
    lone_built_[at_end] = true;
  }
  return table;
}

const LoneSlip& EventEngine::lattice_lone_slip(int j) {
  // The site's partners with the spring to each (two springs to one site, across a narrow
  // periodic lattice, add up), in site order; its stiffness k_p plus those springs, summed
  // in the stencil's order so that sites alike get the same bits and share one record.
  partners_.clear();
  const int nx = forces_.nx(), x = j % nx, y = j / nx;
  double coupled = 0;
  for (const LatticeSpring& c : forces_.lattice_stencil()) {
    for (const int sign : {-1, 1})
      if (const int i = forces_.site(x + sign * c.dx, y + sign * c.dy); i >= 0) {
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
  const double stiffness = forces_.params().k_p + coupled;
  for (const LoneSlip& t : lattice_lone_)
    if (t.stiffness == stiffness) return t;
  if (lattice_lone_.empty()) {
    // The rounding bound's stiffness: an interior site's springs, every spring twice.
    lattice_coupled_ = 0;
    for (const LatticeSpring& c : forces_.lattice_stencil()) lattice_coupled_ += 2.0 * c.k;
  }
  lattice_lone_.push_back(
      integrate_lone_slip(forces_.params(), stiffness, stepper_.name(), dt_, max_steps_per_event,
                          dynamic_cast<const LocatedTransitions*>(&stepper_) != nullptr));
  return lattice_lone_.back();
}

void EventEngine::check_finite() const {
  for (const Range& r : ranges_)
    for (int j = r.lo; j < r.hi; ++j)
      if (!std::isfinite(st_.w[j]) || !std::isfinite(st_.wd[j])) {
        char msg[300];
        std::snprintf(
            msg, sizeof msg,
            "non-finite state at block %d, time %.9g into event %lld: the integration is unstable "
            "(reduce integrator.dt)",
            j, st_.t, static_cast<long long>(counters_.events + 1));
        throw Error(msg);
      }
}

EventRecord EventEngine::next_event() {
  const ModelParams& p = forces_.params();
  const double thr = forces_.friction().threshold;

  // Load: jump the substrate until the most loaded block sits at the threshold.
  if (pad_ && counters_.events % kResumEvery == 0) st_.recompute_sum_w();
  const int trigger = tree_.argmax();
  const double f_max = tree_.max() + p.k_p * anchor();
  const double ds = std::max(0.0, (thr - f_max) / p.loading_rate());
  st_.s += ds;
  if (pad_) st_.x = forces_.pad_equilibrium(st_.sum_w, st_.s);

  EventRecord e;
  e.event = ++counters_.events;
  e.load = st_.s;
  e.trigger = trigger;
  const double x0 = st_.x;
  st_.t = 0;
  max_speed_ = 0;
  last_stick_time_ = 0;
  replayed_stick_time_ = std::nan("");
  sliding_ = 1;
  release(trigger);

  const Substrate frozen = Substrate::frozen(st_.s);
  const bool crossing = stepper_.stick_rule() == StickRule::Crossing;
  // Located transitions keep the work of each piece of a step between transitions.
  const auto* located = dynamic_cast<const LocatedTransitions*>(&stepper_);
  const double half_dt_m = 0.5 * dt_ * p.m_u, half_dt_cp = 0.5 * dt_ * p.c_p;
  dissipated_ = 0;
  std::int64_t steps = 0;
  for (;;) {
    while (sliding_ > 0) {
      ContactScan scan;
      if (steps == 0 && replay_start(trigger, steps, scan)) {
        // The start of the event, from the lone slip's record; scan describes its last step.
      } else if (ClusterRelaxation cluster;
                 cluster_ready(cluster) && relax_cluster(cluster, steps, scan)) {
        // Ran one or more steps of a cluster; scan describes the last one.
      } else {
        // A stepper that resolves transitions itself covers the blocks it released before
        // the contact pass, which then reads the copies over the grown ranges: for it they
        // cover the whole chain and keep what earlier steps left (as they always did).
        if (crossing)
          old_.fit(ranges_);
        else
          old_.whole(n_);
        for (std::size_t i = 0; i < ranges_.size(); ++i) {
          const Range& r = ranges_[i];
          std::copy(st_.wd.begin() + r.lo, st_.wd.begin() + r.hi, old_.data(kWdOld, i) + r.lo);
          if (!crossing) {
            std::copy(st_.mobile.begin() + r.lo, st_.mobile.begin() + r.hi,
                      old_.data(kMobileOld, i) + r.lo);
            std::copy(st_.w.begin() + r.lo, st_.w.begin() + r.hi, old_.data(kWOld, i) + r.lo);
          }
        }
        const double xd_old = st_.xd;
        // The dashpots' power at the start of the step (trapezoidal rule with the end's).
        const double damper_old = forces_.damper_power(st_.wd.data(), ranges_);
        if (held_ranges()) {
          stepper_.step_held(forces_, frozen, st_, dt_, ranges_);
          if (pad_) ++pad_held_steps_;
        } else {
          stepper_.step(forces_, frozen, st_, dt_, ranges_);
        }
        ++steps;
        if (forces_.viscous())
          dissipated_ += 0.5 * dt_ * (damper_old + forces_.damper_power(st_.wd.data(), ranges_));
        for (const Range& r : ranges_) counters_.block_steps += r.hi - r.lo;
        if (!crossing) note_released_in_step();
        released_now_.clear();
        if (old_.joint()) {
          const double* wd_old = old_.data(kWdOld, 0);
          dissipated_ += located ? located->step_work()
                                 : half_dt_m * dissipated_power(forces_, st_, wd_old, ranges_);
          scan = settle_contacts(forces_, st_, wd_old, anchor(), ranges_, crossing,
                                 [&](int j) { released_now_.push_back(j); });
        } else {
          // Range by range, each with its copy: the sums and the releases in the order of
          // one pass over all ranges.
          double power = 0;
          for (std::size_t i = 0; i < ranges_.size(); ++i)
            power += dissipated_power(forces_, st_, old_.data(kWdOld, i), Ranges(&ranges_[i], 1));
          dissipated_ += located ? located->step_work() : half_dt_m * power;
          for (std::size_t i = 0; i < ranges_.size(); ++i) {
            const ContactScan part = settle_contacts(forces_, st_, old_.data(kWdOld, i), anchor(),
                                                     Ranges(&ranges_[i], 1), crossing,
                                                     [&](int j) { released_now_.push_back(j); });
            scan.sliding += part.sliding;
            raise_max_speed(scan.max_speed, part.max_speed);
          }
        }
        if (pad_) dissipated_ += half_dt_cp * (xd_old * xd_old + st_.xd * st_.xd);
        counters_.sliding_block_steps += scan.sliding;
      }
      sliding_ = scan.sliding;
      for (int j : released_now_) release(j);
      if (pad_) query_tree_failures();
      if (!(scan.max_speed <= max_speed_)) {
        if (!std::isfinite(scan.max_speed)) check_finite();
        max_speed_ = scan.max_speed;
      }
      if (sliding_ == 0) {
        // A stepper that located the last re-stick inside the step knows when it was.
        const double located =
            std::isnan(replayed_stick_time_) ? stepper_.located_stick_time() : replayed_stick_time_;
        last_stick_time_ = located > st_.t - dt_ && located <= st_.t ? located : st_.t;
      }
      if (steps % kShrinkEvery == 0) shrink_ranges();
      if (steps > max_steps_per_event) {
        char msg[300];
        std::snprintf(msg, sizeof msg,
                      "event %lld did not end after %lld steps (time %.6g): check integrator.dt "
                      "and the scene "
                      "(the bound is run.max_steps_per_event)",
                      static_cast<long long>(e.event), static_cast<long long>(steps), st_.t);
        throw Error(msg);
      }
    }
    if (!pad_ || !pad_phase()) break;
  }
  counters_.steps += steps;
  uncover_all();

  const double stored_change = stored_energy_change(x0);
  double moment = 0;
  int first = n_, last = -1;
  if (keep_slips_) slips_.clear();
  for (int j : slipped_list_) {
    moment += st_.w[j] - w_before_[j];
    if (keep_slips_) slips_.emplace_back(j, st_.w[j] - w_before_[j]);
    first = std::min(first, j);
    last = std::max(last, j);
    slipped_[j] = 0;
  }
  if (keep_slips_) std::sort(slips_.begin(), slips_.end());
  e.blocks = static_cast<int>(slipped_list_.size());
  e.first_block = first;
  e.last_block = last;
  if (forces_.lattice()) place_on_lattice(e, trigger, slipped_list_, forces_.nx());
  slipped_list_.clear();
  e.moment = moment;
  e.magnitude = moment > 0 ? std::log(moment) : std::nan("");
  e.duration = last_stick_time_;
  e.max_speed = max_speed_;
  e.pad_displacement = pad_ ? st_.x - x0 : 0.0;
  e.energy_residual = dissipated_ > 0 ? (stored_change + dissipated_) / dissipated_ : 0.0;
  return e;
}

}  // namespace bkq
