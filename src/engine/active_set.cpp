// The covered ranges and the force tree (see active_set.hpp).
#include "engine/active_set.hpp"

#include <algorithm>

namespace bkq {

ActiveSet::ActiveSet(const ChainForces& forces, int margin, bool pad)
    : forces_(forces), n_(forces.n()), margin_(margin), pad_(pad) {
  covered_.assign(n_, 0);
  need_.assign(n_, 0);
}

void ActiveSet::rebuild_tree(const ChainState& st) {
  tree_.reset(n_);
  tree_.set_range(0, n_, [&](int j) { return forces_.local_force(st.w.data(), j); });
}

void ActiveSet::add_to_ranges(int k) {
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

void ActiveSet::cover(int j) {
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

void ActiveSet::shrink(const ChainState& st) {
  const bool periodic = forces_.params().boundary == Boundary::Periodic;
  const bool lattice = forces_.lattice();
  for (const Range& r : ranges_)
    for (int j = r.lo; j < r.hi; ++j) {
      if (st.mobile[j] == 0.0) continue;
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
  const double* w = st.w.data();
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

void ActiveSet::uncover_all(const ChainState& st) {
  const double* w = st.w.data();
  for (const Range& r : ranges_) {
    std::fill(covered_.begin() + r.lo, covered_.begin() + r.hi, 0);
    tree_.set_range(r.lo, r.hi, [&](int j) { return forces_.local_force(w, j); });
  }
  ranges_.clear();
  ++uncovers_;
}

}  // namespace bkq
