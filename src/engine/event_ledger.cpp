// The event's books (see event_ledger.hpp).
#include "engine/event_ledger.hpp"

#include <algorithm>
#include <cmath>

namespace bkq {

EventLedger::EventLedger(int n_blocks) {
  slipped_.assign(n_blocks, 0);
  w_before_.assign(n_blocks, 0.0);
}

void EventLedger::open(EventRecord& e) {
  e.event = ++counters_.events;
  event_steps_ = 0;
  max_speed_ = 0;
  last_stick_time_ = 0;
  dissipated_ = 0;
  sliding_ = 0;
}

void EventLedger::note_release(int j, double w) {
  ++counters_.releases;
  if (slipped_[j]) return;  // only its first release in the event counts
  slipped_[j] = 1;
  slipped_list_.push_back(j);
  w_before_[j] = w;
}

void EventLedger::close(EventRecord& e, const ChainForces& forces, const ChainState& st,
                        double x0) {
  const bool pad = forces.params().pad_moves();
  const double stored_change = stored_energy_change(forces, st, x0);
  double moment = 0;
  int first = forces.n(), last = -1;
  if (keep_slips) slips_.clear();
  for (int j : slipped_list_) {
    moment += st.w[j] - w_before_[j];
    if (keep_slips) slips_.emplace_back(j, st.w[j] - w_before_[j]);
    first = std::min(first, j);
    last = std::max(last, j);
    slipped_[j] = 0;
  }
  if (keep_slips) std::sort(slips_.begin(), slips_.end());
  e.blocks = static_cast<int>(slipped_list_.size());
  e.first_block = first;
  e.last_block = last;
  if (forces.lattice()) place_on_lattice(e, e.trigger, slipped_list_, forces.nx());
  slipped_list_.clear();
  e.moment = moment;
  e.magnitude = moment > 0 ? std::log(moment) : std::nan("");
  e.duration = last_stick_time_;
  e.max_speed = max_speed_;
  e.pad_displacement = pad ? st.x - x0 : 0.0;
  dissipated_total_ += dissipated_;
  e.energy_residual = dissipated_ > 0 ? (stored_change + dissipated_) / dissipated_ : 0.0;
}

double EventLedger::stored_energy_change(const ChainForces& forces, const ChainState& st,
                                         double x0) const {
  const bool pad = forces.params().pad_moves();
  const int n = forces.n();
  const ModelParams& p = forces.params();
  const double* w = st.w.data();
  auto before = [&](int k) { return slipped_[k] ? w_before_[k] : w[k]; };
  const double s = st.s, x1 = pad ? st.x : 0.0;
  x0 = pad ? x0 : 0.0;
  double e_pull = 0, e_bond = 0, sum_slipped = 0;
  const bool periodic = p.boundary == Boundary::Periodic && n > 2;
  const bool bonds = p.has_neighbours();
  // The change over the event of (w_a - w_b)^2, for the spring between blocks a and b.
  auto bond = [&](int a, int b) {
    const double d1 = w[a] - w[b], d0 = before(a) - before(b);
    return d1 * d1 - d0 * d0;
  };
  // Each spring once: to the partner ahead (the right, +offset) always, to the one behind
  // only when it did not slip (else it is counted as that block's spring ahead).
  const int nx = forces.nx();
  for (int j : slipped_list_) {
    const double d1 = w[j] - s - x1, d0 = before(j) - s - x0;
    e_pull += d1 * d1 - d0 * d0;
    sum_slipped += w[j];
    if (forces.lattice()) {
      const int x = j % nx, y = j / nx;
      for (const LatticeSpring& c : forces.lattice_stencil()) {
        double e = 0;
        if (const int r = forces.site(x + c.dx, y + c.dy); r >= 0) e += bond(r, j);
        if (const int l = forces.site(x - c.dx, y - c.dy); l >= 0 && !slipped_[l]) e += bond(j, l);
        e_bond += c.k * e;
      }
    } else if (forces.long_range()) {
      for (const CouplingSpring& c : forces.stencil()) {
        int right = j + c.offset, left = j - c.offset;
        if (periodic) {
          right = right >= n ? right - n : right;
          left = left < 0 ? left + n : left;
        }
        double e = 0;
        if (right < n) e += bond(right, j);
        if (left >= 0 && !slipped_[left]) e += bond(j, left);
        e_bond += c.k * e;
      }
    } else if (bonds) {
      const int right = j + 1 < n ? j + 1 : (periodic ? 0 : -1);
      const int left = j > 0 ? j - 1 : (periodic ? n - 1 : -1);
      if (right >= 0) e_bond += bond(right, j);
      if (left >= 0 && !slipped_[left]) e_bond += bond(j, left);
    }
  }
  // With range coupling e_bond already holds each spring's stiffness.
  double de =
      0.5 * p.k_p * e_pull + (forces.long_range() || forces.lattice() ? 0.5 : 0.5 * p.k_c) * e_bond;
  if (pad) {
    // Blocks that did not slip only see the anchor move from s + x0 to s + x1.
    const double others = static_cast<double>(n - static_cast<int>(slipped_list_.size()));
    const double sum_others = st.sum_w - sum_slipped - others * s;
    de += 0.5 * p.k_p * (x0 - x1) * (2.0 * sum_others - others * (x0 + x1));
    de += 0.5 * p.k_p0 * (x1 * x1 - x0 * x0);
  }
  return de;
}

}  // namespace bkq
