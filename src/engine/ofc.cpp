// The OFC automaton; see ofc.hpp for the model, the update order and the boundaries.
#include "engine/ofc.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/initial_state.hpp"

namespace bkq {

std::vector<double> ofc_initial_field(const OfcParams& p, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> f(static_cast<std::size_t>(p.sites()));
  for (double& x : f) x = uniform01(rng);
  return f;
}

void OfcEngine::check(const OfcParams& p) {
  if (p.nx < 1 || p.ny < 1) throw Error("ofc: the lattice needs at least one site");
  if (!(p.alpha > 0 && p.alpha <= 0.25))
    throw Error("ofc.alpha = " + format_real(p.alpha) +
                ": allowed (0, 0.25] (0 < alpha <= 1/z, z = 4)");
  // A wrapped axis of fewer than three sites would make a site its own or a double neighbour.
  if (p.periodic_x && p.nx < 3)
    throw Error("model.boundary = periodic needs model.blocks >= 3 for ofc, got model.blocks = " +
                std::to_string(p.nx));
  if (p.periodic_y && p.ny < 3)
    throw Error("model.boundary_y = periodic needs model.rows >= 3, got model.rows = " +
                std::to_string(p.ny));
  if (p.periodic_x && p.periodic_y && p.alpha == 0.25)
    throw Error(
        "ofc.alpha = 0.25 with model.boundary = periodic and model.boundary_y = periodic: stress "
        "is conserved and never leaves the lattice, so an avalanche would never end; allowed: "
        "ofc.alpha < 0.25, or a free boundary on one axis");
  if (!(p.relaxation_time >= 0) || !std::isfinite(p.relaxation_time))
    throw Error("ofc.relaxation_time = " + format_real(p.relaxation_time) +
                ": allowed a finite value >= 0 (0: no relaxation)");
  if (!(p.relaxation_alpha >= 0 && p.alpha + p.relaxation_alpha <= 0.25))
    throw Error("ofc.relaxation_alpha = " + format_real(p.relaxation_alpha) +
                " with ofc.alpha = " + format_real(p.alpha) +
                ": allowed [0, 0.25 - ofc.alpha] (a toppling passes on at most its stress)");
  if (p.relaxes() && p.relaxation_alpha == 0)
    throw Error("ofc.relaxation_time = " + format_real(p.relaxation_time) +
                " with ofc.relaxation_alpha = 0: nothing would relax; allowed: "
                "ofc.relaxation_alpha in (0, 0.25 - ofc.alpha], or ofc.relaxation_time = 0");
  if (!p.relaxes() && p.relaxation_alpha > 0)
    throw Error("ofc.relaxation_alpha = " + format_real(p.relaxation_alpha) +
                " with ofc.relaxation_time = 0: the delayed share needs a relaxation time; "
                "allowed: ofc.relaxation_alpha = 0, or ofc.relaxation_time > 0");
  if (p.relaxes() && p.periodic_x && p.periodic_y && p.alpha + p.relaxation_alpha == 0.25)
    throw Error(
        "ofc.alpha + ofc.relaxation_alpha = 0.25 with model.boundary = periodic and "
        "model.boundary_y = periodic: stress would never leave the lattice; allowed: a "
        "smaller sum, or a free boundary on one axis");
}

std::size_t OfcEngine::stored_size(const OfcParams& p) {
  const int needed = (p.sites() + kBucket - 1) / kBucket;
  std::size_t buckets = 1;
  while (buckets < static_cast<std::size_t>(needed)) buckets *= 2;
  return buckets * kBucket;
}

OfcEngine::OfcEngine(const OfcParams& p, const std::vector<double>& initial) : p_(p) {
  check(p);
  if (static_cast<int>(initial.size()) != p.sites())
    throw Error("ofc: the initial field has " + std::to_string(initial.size()) + " values for " +
                std::to_string(p.sites()) + " sites");
  build_tree();  // sizes g_
  std::copy(initial.begin(), initial.end(), g_.begin());
  rebuild_tree();
}

OfcEngine::OfcEngine(const OfcParams& p, const OfcSnapshot& saved)
    : p_(p), offset_(saved.offset), load_(saved.load), counters_(saved.counters) {
  check(p);
  build_tree();
  if (saved.g.size() != g_.size())
    throw Error("ofc: the saved field has " + std::to_string(saved.g.size()) +
                " values, this lattice " + std::to_string(g_.size()));
  g_ = saved.g;
  rebuild_tree();
  if (p.relaxes()) {
    if (saved.pending.size() != static_cast<std::size_t>(p.sites()) ||
        saved.pending_at.size() != saved.pending.size() ||
        saved.arrival.size() != saved.pending.size())
      throw Error("ofc: the saved state has no pending stress for each of the " +
                  std::to_string(p.sites()) + " sites (ofc.relaxation_time > 0)");
    pend_ = saved.pending;
    pend_at_ = saved.pending_at;
    // The arrival times as they were computed (recomputing them now would round otherwise).
    for (int j = 0; j < p.sites(); ++j)
      if (pend_[j] != 0) heap_set(j, saved.arrival[j]);
  }
}

OfcSnapshot OfcEngine::snapshot() const {
  OfcSnapshot s{g_, offset_, load_, counters_, pend_, pend_at_, {}};
  if (p_.relaxes()) {
    s.arrival.assign(pend_.size(), -1.0);
    for (const auto& [key, j] : heap_) s.arrival[j] = key;
  }
  return s;
}

void OfcEngine::build_tree() {
  const int n = p_.sites();
  const int needed = (n + kBucket - 1) / kBucket;
  buckets_ = 1;
  while (buckets_ < needed) buckets_ *= 2;
  g_.assign(static_cast<std::size_t>(buckets_) * kBucket, -HUGE_VAL);
  tree_.assign(2 * static_cast<std::size_t>(buckets_), Node{-HUGE_VAL, 0, false});
  bucket_marked_.assign(buckets_, 0);
  touched_buckets_.clear();
  site_.assign(n, Site{0, 0, 0});
  if (p_.sequential) {
    queue_.assign(n, 0);
    depth_.assign(n, 0);
    queued_.assign(n, 0);
  }
  if (p_.relaxes()) {
    pend_.assign(n, 0.0);
    pend_at_.assign(n, 0.0);
    heap_pos_.assign(n, -1);
    relax_marked_.assign(n, 0);
    heap_.reserve(n);
  }
  stamp_ = 0;
  receivers_.reserve(n);
  now_.reserve(n);
  next_.reserve(n);
  const int nx = p_.nx, ny = p_.ny;
  edge_.assign(n, 0);
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
      edge_[x + nx * y] = static_cast<unsigned char>((x == 0 ? 1 : 0) | (x == nx - 1 ? 2 : 0) |
                                                     (y == 0 ? 4 : 0) | (y == ny - 1 ? 8 : 0));
  // Across a wrapped side the neighbour is j + wrap_[d]; across a free one there is none.
  wrap_[0] = p_.periodic_x ? nx - 1 : 0;
  wrap_[1] = p_.periodic_x ? -(nx - 1) : 0;
  wrap_[2] = p_.periodic_y ? nx * (ny - 1) : 0;
  wrap_[3] = p_.periodic_y ? -nx * (ny - 1) : 0;
}

inline void OfcEngine::neighbours(int j, int nb[4]) const {
  nb[0] = j - 1;
  nb[1] = j + 1;
  nb[2] = j - p_.nx;
  nb[3] = j + p_.nx;
  const unsigned e = edge_[j];
  if (e == 0) return;  // an interior site
  const bool periodic[4] = {p_.periodic_x, p_.periodic_x, p_.periodic_y, p_.periodic_y};
  for (int d = 0; d < 4; ++d)
    if (e & (1u << d)) nb[d] = periodic[d] ? j + wrap_[d] : -1;
}

// The bucket's largest value, the first site holding it, and whether another holds it.
void OfcEngine::scan(int b) {
  const int first = b * kBucket;
  const double* g = g_.data() + first;
  Node hi{g[0], first, false};
  for (int k = 1; k < kBucket; ++k)
    if (g[k] > hi.g)
      hi = Node{g[k], first + k, false};
    else if (g[k] == hi.g)
      hi.tied = true;
  tree_[buckets_ + b] = hi;
}

// Ties to the left child, which holds the lower sites.
void OfcEngine::pull(int i) {
  const Node &a = tree_[2 * i], &b = tree_[2 * i + 1];
  if (a.g == b.g)
    tree_[i] = Node{a.g, a.j, true};
  else
    tree_[i] = a.g > b.g ? a : b;
}

void OfcEngine::rebuild_tree() {
  for (int b = 0; b < buckets_; ++b) scan(b);
  for (int i = buckets_ - 1; i >= 1; --i) pull(i);
}

inline void OfcEngine::touch(int j) {
  const int b = j / kBucket;
  if (!bucket_marked_[b]) {
    bucket_marked_[b] = 1;
    touched_buckets_.push_back(b);
  }
}

std::vector<double> OfcEngine::field() const {
  std::vector<double> f(p_.sites());
  for (int j = 0; j < p_.sites(); ++j) f[j] = stress(j);
  return f;
}

// Folds the offset into the field so that g_j stays of the order of the stresses (its
// rounding that of a number below 1, not of the cumulative drive).
void OfcEngine::renormalise() {
  for (int j = 0; j < p_.sites(); ++j) g_[j] += offset_;
  offset_ = 0;
  rebuild_tree();
}

// Every site whose stored value equals `value`, the subtree's maximum, in index order.
void OfcEngine::collect_ties(int i, double value) {
  if (tree_[i].g != value) return;
  if (i >= buckets_) {
    const int first = (i - buckets_) * kBucket;
    for (int k = first; k < first + kBucket; ++k)
      if (g_[k] == value) now_.push_back(k);
    return;
  }
  collect_ties(2 * i, value);
  collect_ties(2 * i + 1, value);
}

double OfcEngine::stress(int j) const {
  double f = g_[j] + offset_;
  if (p_.relaxes() && pend_[j] != 0)
    f += pend_[j] * -std::expm1(-(load_ - pend_at_[j]) / p_.relaxation_time);
  return f;
}

double OfcEngine::pending(int j) const {
  if (!p_.relaxes() || pend_[j] == 0) return 0;
  return pend_[j] * std::exp(-(load_ - pend_at_[j]) / p_.relaxation_time);
}

// What has flowed in since the site was last brought up to date joins g_ (pending stress P
// at load l0 becomes P exp(-(l - l0)/tau) at load l: the rest has flowed in). A remainder
// below 2^-60 flows in at once, so a site leaves the relaxing set (stress is kept whole).
void OfcEngine::fold(int j) {
  const double p = pend_[j];
  if (p == 0 || pend_at_[j] == load_) return;
  const double left = p * std::exp(-(load_ - pend_at_[j]) / p_.relaxation_time);
  if (left < 0x1p-60) {
    g_[j] += p;
    pend_[j] = 0;
  } else {
    g_[j] += p - left;
    pend_[j] = left;
  }
  pend_at_[j] = load_;
}

// The load at which site j reaches the threshold: F + t + P (1 - exp(-t/tau)) = 1, with F
// and P brought up to the current load. The left side rises and is concave in t, so Newton's
// method from a point below the root climbs to it without overshooting.
double OfcEngine::crossing(int j) const {
  const double tau = p_.relaxation_time;
  const double f = stress(j), p = pending(j);
  double t = std::max(0.0, 1.0 - f - p);
  for (int k = 0; k < 100; ++k) {
    const double e = std::exp(-t / tau);
    const double h = f + t + p * (1 - e) - 1;
    const double step = -h / (1 + p * e / tau);
    t += std::max(step, 0.0);
    if (!(step > 1e-16 * (1 + t))) break;
  }
  return load_ + t;
}

void OfcEngine::mark_relaxing(int j) {
  if (!relax_marked_[j]) {
    relax_marked_[j] = 1;
    relax_dirty_.push_back(j);
  }
}

void OfcEngine::heap_up(int k) {
  while (k > 0) {
    const int parent = (k - 1) / 2;
    if (!(heap_[k] < heap_[parent])) break;
    std::swap(heap_[k], heap_[parent]);
    heap_pos_[heap_[k].second] = k;
    heap_pos_[heap_[parent].second] = parent;
    k = parent;
  }
}

void OfcEngine::heap_down(int k) {
  const int n = static_cast<int>(heap_.size());
  for (;;) {
    int least = k;
    for (const int c : {2 * k + 1, 2 * k + 2})
      if (c < n && heap_[c] < heap_[least]) least = c;
    if (least == k) break;
    std::swap(heap_[k], heap_[least]);
    heap_pos_[heap_[k].second] = k;
    heap_pos_[heap_[least].second] = least;
    k = least;
  }
}

void OfcEngine::heap_set(int j, double key) {
  int k = heap_pos_[j];
  if (k < 0) {
    k = static_cast<int>(heap_.size());
    heap_.emplace_back(key, j);
    heap_pos_[j] = k;
  } else {
    heap_[k].first = key;
  }
  heap_up(k);
  heap_down(heap_pos_[j]);
}

void OfcEngine::heap_remove(int j) {
  const int k = heap_pos_[j];
  if (k < 0) return;
  heap_pos_[j] = -1;
  const int last = static_cast<int>(heap_.size()) - 1;
  if (k == last) {
    heap_.pop_back();
    return;
  }
  const int moved = heap_[last].second;
  heap_[k] = heap_[last];
  heap_pos_[moved] = k;
  heap_.pop_back();
  heap_up(k);
  heap_down(heap_pos_[moved]);
}

EventRecord OfcEngine::next_event() {
  // Drive: the largest site to the threshold. The offset stops one rounding step short of
  // F = 1 if needed, so that no other site reaches the threshold by the drive alone; the
  // sites holding the largest value (exact ties are common: sites that toppled together
  // and were fed alike) topple together as generation 1. With relaxation, a relaxing site
  // may get there first (the heap's earliest arrival): it is then the trigger, alone.
  const Node top = tree_[1];
  int relaxing_trigger = -1;
  if (p_.relaxes() && !heap_.empty() && heap_[0].first <= load_ + (1.0 - (top.g + offset_)))
    relaxing_trigger = heap_[0].second;
  EventRecord e;
  if (relaxing_trigger < 0) {
    const double delta = 1.0 - (top.g + offset_);
    offset_ += delta;
    // Each step lowers the exact sum by at least one ulp of 1, so the loop ends in a step or
    // two (a step of one ulp of a small offset could leave the rounded sum where it was).
    while (top.g + offset_ >= 1.0)
      offset_ -= std::max(offset_ - std::nextafter(offset_, -HUGE_VAL), 0x1p-52);
    load_ += delta;
    e.trigger = top.j;
  } else {
    const double delta = std::max(heap_[0].first - load_, 0.0);
    offset_ += delta;
    load_ += delta;
    e.trigger = relaxing_trigger;
  }
  e.load = load_;
  // Until the avalanche ends, trigger and first/last_row hold site indices j = x + nx y and
  // first/last_block columns x; the rows are the lowest and highest j's rows.
  e.first_block = e.last_block = e.trigger % p_.nx;
  e.first_row = e.last_row = e.trigger;
  ++counters_.events;
  // 32-bit stamps keep the per-site bookkeeping small; they are cleared long before they
  // could wrap (an event would need 2^31 generations to reach the end).
  if (stamp_ > 0x7fffffffu) {
    for (Site& s : site_) s.queued_at = s.toppled_at = 0;
    stamp_ = 0;
  }
  const std::uint32_t first_generation = stamp_ + 1;
  double moment = 0, lost = 0;
  std::int64_t topplings = 0, generations = 0;
  int distinct = 0;
  now_.clear();
  if (relaxing_trigger >= 0)
    now_.push_back(relaxing_trigger);
  else if (top.tied)
    collect_ties(1, top.g);
  else
    now_.push_back(top.j);
  if (p_.sequential) {
    if (p_.relaxes())
      avalanche_sequential<true>(e, first_generation, moment, lost, topplings, generations,
                                 distinct);
    else
      avalanche_sequential<false>(e, first_generation, moment, lost, topplings, generations,
                                  distinct);
  } else {
    if (p_.relaxes())
      avalanche_generations<true>(e, first_generation, moment, lost, topplings, generations,
                                  distinct);
    else
      avalanche_generations<false>(e, first_generation, moment, lost, topplings, generations,
                                   distinct);
  }
  lost_ += lost;
  counters_.topplings += topplings;
  counters_.generations += generations;

  // The max tree, once per event over the buckets the avalanche touched. A node that comes
  // out as it was leaves its ancestors as they were: the walk up stops there (most changes
  // stay below the top of the tree, so an event costs about its touched buckets).
  for (const int b : touched_buckets_) {
    bucket_marked_[b] = 0;
    const Node old = tree_[buckets_ + b];
    scan(b);
    if (same(tree_[buckets_ + b], old)) continue;
    for (int i = (buckets_ + b) / 2; i >= 1; i /= 2) {
      const Node was = tree_[i];
      pull(i);
      if (same(tree_[i], was)) break;
    }
  }
  touched_buckets_.clear();
  // The relaxing sites this event changed: their new arrival times.
  for (const int j : relax_dirty_) {
    relax_marked_[j] = 0;
    if (pend_[j] == 0)
      heap_remove(j);
    else
      heap_set(j, crossing(j));
  }
  relax_dirty_.clear();
  if (offset_ > 4.0) renormalise();

  e.trigger_row = e.trigger / p_.nx;
  e.trigger -= e.trigger_row * p_.nx;
  e.first_row /= p_.nx;
  e.last_row /= p_.nx;
  e.blocks = distinct;
  e.moment = moment;
  e.magnitude = std::log(moment);
  e.duration = static_cast<double>(generations);
  e.topplings = topplings;
  if (keep_slips_) collect_slips(e.magnitude);
  return e;
}

// Parallel update by generations: every site of a generation releases what it holds at the
// generation's start and hands alpha of it to each neighbour, in the neighbour's slot for
// the side it comes from; the share pushed over a free edge is lost. The slots are summed
// after every release of the generation. With relaxation each site is brought up to date
// before it is read, and relaxation_alpha of each release joins each neighbour's pending
// stress (over a free edge it is lost).
// The bookkeeping of a site's first toppling in the event (both orders): the stamp that
// marks it, the count of distinct sites and the event's bounding box (rows as site indices
// until the event is finished).
inline void OfcEngine::note_first_toppling(int j, std::uint32_t stamp,
                                           std::uint32_t first_generation, EventRecord& e,
                                           int& distinct) {
  Site& sj = site_[j];
  if (sj.toppled_at >= first_generation) return;
  sj.toppled_at = stamp;
  ++distinct;
  const int x = j % p_.nx;
  e.first_block = std::min(e.first_block, x);
  e.last_block = std::max(e.last_block, x);
  e.first_row = std::min(e.first_row, j);
  e.last_row = std::max(e.last_row, j);
}

void OfcEngine::keep_slips(bool on, double min_magnitude) {
  keep_slips_ = on;
  slip_min_magnitude_ = min_magnitude;
  releases_.clear();
  releases_.reserve(on ? p_.sites() : 0);
  slips_.clear();
  slip_topplings_.clear();
}

// The event's map from its topplings when its magnitude reaches the threshold: sorted by
// site, stably, so each site's releases add up in the order it toppled.
void OfcEngine::collect_slips(double magnitude) {
  slips_.clear();
  slip_topplings_.clear();
  if (magnitude >= slip_min_magnitude_) {
    std::stable_sort(releases_.begin(), releases_.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [j, released] : releases_) {
      if (!slips_.empty() && slips_.back().first == j) {
        slips_.back().second += released;
        ++slip_topplings_.back();
      } else {
        slips_.emplace_back(j, released);
        slip_topplings_.push_back(1);
      }
    }
  }
  releases_.clear();
}

// Relaxation: the share a toppling passes to neighbour n as pending stress, which flows in
// over the drive (both orders).
inline void OfcEngine::pass_pending(int n, double amount) {
  fold(n);
  pend_[n] += amount;
  pend_at_[n] = load_;
  mark_relaxing(n);
}

template <bool kRelax>
void OfcEngine::avalanche_generations(EventRecord& e, std::uint32_t first_generation,
                                      double& moment, double& lost, std::int64_t& topplings,
                                      std::int64_t& generations, int& distinct) {
  const double alpha = p_.alpha, beta = p_.relaxation_alpha;
  double* g = g_.data();
  while (!now_.empty()) {
    ++generations;
    if (stamp_ == 0xffffffffu) throw Error("ofc: an avalanche of more than 2^31 generations");
    const std::uint32_t gen = ++stamp_;
    receivers_.clear();
    for (const int j : now_) {
      if constexpr (kRelax) {
        fold(j);
        mark_relaxing(j);
      }
      const double r = g[j] + offset_;
      const double s = alpha * r;
      g[j] = -offset_;
      moment += r;
      if (keep_slips_) releases_.emplace_back(j, r);
      touch(j);
      note_first_toppling(j, gen, first_generation, e, distinct);
      int nb[4];
      neighbours(j, nb);
      for (int d = 0; d < 4; ++d) {
        const int n = nb[d];
        if (n < 0) {
          lost += s;
          if constexpr (kRelax) lost += beta * r;
          continue;
        }
        Site& sn = site_[n];
        if (sn.queued_at != gen) {
          sn.queued_at = gen;
          sn.slot = static_cast<std::int32_t>(receivers_.size());
          receivers_.push_back(Receiver{n, {0.0, 0.0, 0.0, 0.0}});
        }
        receivers_[sn.slot].in[d ^ 1] = s;  // j is n's neighbour on the opposite side
        if constexpr (kRelax) pass_pending(n, beta * r);
      }
    }
    topplings += static_cast<std::int64_t>(now_.size());
    // Each receiver adds (left + right) + (down + up): a sum whose rounding does not depend
    // on the order of the lists, and is the same under shifts, reflections and transposition
    // of the lattice (floating-point addition commutes), so those symmetries hold bit for bit.
    next_.clear();
    for (const Receiver& rc : receivers_) {
      const int n = rc.n;
      if constexpr (kRelax) {
        fold(n);
        mark_relaxing(n);
      }
      g[n] += (rc.in[0] + rc.in[1]) + (rc.in[2] + rc.in[3]);
      touch(n);
      if (g[n] + offset_ >= 1.0) next_.push_back(n);
    }
    now_.swap(next_);
  }
}

// Sequential order: one site at a time, first in, first out, starting from generation 1's
// sites. A toppling hands alpha of its stress to each neighbour at once, so a neighbour
// queued earlier releases what it holds when its turn comes. The event's duration is the
// depth of its longest causal chain (1: the trigger alone).
template <bool kRelax>
void OfcEngine::avalanche_sequential(EventRecord& e, std::uint32_t first_generation, double& moment,
                                     double& lost, std::int64_t& topplings,
                                     std::int64_t& generations, int& distinct) {
  const double alpha = p_.alpha, beta = p_.relaxation_alpha;
  double* g = g_.data();
  const std::size_t cap = queue_.size();
  std::size_t head = 0, count = 0;
  auto push = [&](int j, int depth) {
    const std::size_t at = (head + count) % cap;
    queue_[at] = j;
    depth_[at] = depth;
    ++count;
    queued_[j] = 1;
  };
  for (const int j : now_) push(j, 1);
  if (stamp_ == 0xffffffffu) throw Error("ofc: an avalanche of more than 2^31 generations");
  const std::uint32_t stamp = ++stamp_;
  int deepest = 0;
  while (count > 0) {
    const int j = queue_[head];
    const int depth = depth_[head];
    head = (head + 1) % cap;
    --count;
    queued_[j] = 0;
    deepest = std::max(deepest, depth);
    if constexpr (kRelax) fold(j);
    const double r = g[j] + offset_;
    const double s = alpha * r;
    g[j] = -offset_;
    moment += r;
    if (keep_slips_) releases_.emplace_back(j, r);
    ++topplings;
    touch(j);
    if constexpr (kRelax) mark_relaxing(j);
    note_first_toppling(j, stamp, first_generation, e, distinct);
    int nb[4];
    neighbours(j, nb);
    for (int d = 0; d < 4; ++d) {
      const int n = nb[d];
      if (n < 0) {
        lost += s;
        if constexpr (kRelax) lost += beta * r;
        continue;
      }
      if constexpr (kRelax) pass_pending(n, beta * r);
      g[n] += s;
      touch(n);
      if (!queued_[n] && g[n] + offset_ >= 1.0) push(n, depth + 1);
    }
  }
  generations = deepest;
}

}  // namespace bkq
