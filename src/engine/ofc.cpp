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
}

OfcEngine::OfcEngine(const OfcParams& p, const std::vector<double>& initial) : p_(p) {
  check(p);
  if (static_cast<int>(initial.size()) != p.sites())
    throw Error("ofc: the initial field has " + std::to_string(initial.size()) + " values for " +
                std::to_string(p.sites()) + " sites");
  build_tree();  // sizes g_
  std::copy(initial.begin(), initial.end(), g_.begin());
  for (int b = 0; b < buckets_; ++b) scan(b);
  for (int i = buckets_ - 1; i >= 1; --i) pull(i);
}

OfcEngine::OfcEngine(const OfcParams& p, const OfcSnapshot& saved)
    : p_(p), offset_(saved.offset), load_(saved.load), counters_(saved.counters) {
  check(p);
  build_tree();
  if (saved.g.size() != g_.size())
    throw Error("ofc: the saved field has " + std::to_string(saved.g.size()) +
                " values, this lattice " + std::to_string(g_.size()));
  g_ = saved.g;
  for (int b = 0; b < buckets_; ++b) scan(b);
  for (int i = buckets_ - 1; i >= 1; --i) pull(i);
}

void OfcEngine::build_tree() {
  const int n = p_.sites();
  const int needed = (n + kBucket - 1) / kBucket;
  buckets_ = 1;
  while (buckets_ < needed) buckets_ *= 2;
  g_.assign(static_cast<std::size_t>(buckets_) * kBucket, -HUGE_VAL);
  tree_.assign(2 * static_cast<std::size_t>(buckets_), Node{-HUGE_VAL, 0});
  bucket_marked_.assign(buckets_, 0);
  touched_buckets_.clear();
  release_.assign(n, 0.0);
  released_at_.assign(n, 0);
  queued_at_.assign(n, 0);
  receivers_.reserve(n);
  toppled_at_.assign(n, 0);
  now_.reserve(n);
  next_.reserve(n);
  nbr_.assign(4 * static_cast<std::size_t>(n), -1);
  const int nx = p_.nx, ny = p_.ny;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      int* nb = &nbr_[4 * static_cast<std::size_t>(x + nx * y)];
      if (x > 0)
        nb[0] = x - 1 + nx * y;
      else if (p_.periodic_x)
        nb[0] = nx - 1 + nx * y;
      if (x < nx - 1)
        nb[1] = x + 1 + nx * y;
      else if (p_.periodic_x)
        nb[1] = nx * y;
      if (y > 0)
        nb[2] = x + nx * (y - 1);
      else if (p_.periodic_y)
        nb[2] = x + nx * (ny - 1);
      if (y < ny - 1)
        nb[3] = x + nx * (y + 1);
      else if (p_.periodic_y)
        nb[3] = x;
    }
}

// The bucket's largest value and the first site holding it.
void OfcEngine::scan(int b) {
  const int first = b * kBucket;
  const double* g = g_.data() + first;
  Node hi{g[0], first};
  for (int k = 1; k < kBucket; ++k)
    if (g[k] > hi.g) hi = Node{g[k], first + k};
  tree_[buckets_ + b] = hi;
}

// Ties to the left child, which holds the lower sites.
void OfcEngine::pull(int i) {
  const Node &a = tree_[2 * i], &b = tree_[2 * i + 1];
  tree_[i] = a.g >= b.g ? a : b;
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
  for (int b = 0; b < buckets_; ++b) scan(b);
  for (int i = buckets_ - 1; i >= 1; --i) pull(i);
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

EventRecord OfcEngine::next_event() {
  // Drive: the largest site to the threshold. The offset stops one rounding step short of
  // F = 1 if needed, so that no other site reaches the threshold by the drive alone; the
  // sites holding the largest value (exact ties are common: sites that toppled together
  // and were fed alike) topple together as generation 1.
  const Node top = tree_[1];
  const double delta = 1.0 - (top.g + offset_);
  offset_ += delta;
  // Each step lowers the exact sum by at least one ulp of 1, so the loop ends in a step or
  // two (a step of one ulp of a small offset could leave the rounded sum where it was).
  while (top.g + offset_ >= 1.0)
    offset_ -= std::max(offset_ - std::nextafter(offset_, -HUGE_VAL), 0x1p-52);
  load_ += delta;

  EventRecord e;
  e.load = load_;
  e.trigger = top.j;
  e.first_block = top.j;
  e.last_block = top.j;
  const std::int64_t event_stamp = ++counters_.events;
  const double alpha = p_.alpha;
  const int* nbr = nbr_.data();
  double* g = g_.data();
  double moment = 0, lost = 0;
  std::int64_t topplings = 0, generations = 0;
  int distinct = 0;
  now_.clear();
  collect_ties(1, top.g);
  while (!now_.empty()) {
    ++generations;
    const std::int64_t gen_stamp = ++stamp_;
    // Every site of the generation releases what it holds at the generation's start.
    for (const int j : now_) {
      const double r = g[j] + offset_;
      release_[j] = alpha * r;
      released_at_[j] = gen_stamp;
      g[j] = -offset_;
      moment += r;
      touch(j);
      if (toppled_at_[j] != event_stamp) {
        toppled_at_[j] = event_stamp;
        ++distinct;
        e.first_block = std::min(e.first_block, j);
        e.last_block = std::max(e.last_block, j);
      }
    }
    topplings += static_cast<std::int64_t>(now_.size());
    // The sites that receive, each once; the share pushed over a free edge is lost.
    receivers_.clear();
    for (const int j : now_) {
      const int* nb = nbr + 4 * static_cast<std::size_t>(j);
      for (int d = 0; d < 4; ++d) {
        const int n = nb[d];
        if (n < 0) {
          lost += release_[j];
        } else if (queued_at_[n] != gen_stamp) {
          queued_at_[n] = gen_stamp;
          receivers_.push_back(n);
        }
      }
    }
    // Each receiver adds (left + right) + (down + up): a sum whose rounding does not depend
    // on the order of the lists, and is the same under shifts, reflections and transposition
    // of the lattice (floating-point addition commutes), so those symmetries hold bit for bit.
    auto share = [&](int n) { return n >= 0 && released_at_[n] == gen_stamp ? release_[n] : 0.0; };
    next_.clear();
    for (const int n : receivers_) {
      const int* nb = nbr + 4 * static_cast<std::size_t>(n);
      g[n] += (share(nb[0]) + share(nb[1])) + (share(nb[2]) + share(nb[3]));
      touch(n);
      if (g[n] + offset_ >= 1.0) next_.push_back(n);
    }
    now_.swap(next_);
  }
  lost_ += lost;
  counters_.topplings += topplings;
  counters_.generations += generations;

  // The max tree, once per event over the buckets the avalanche touched. A node that comes
  // out as it was leaves its ancestors as they were: the walk up stops there (most changes
  // stay below the top of the tree, so an event costs about its touched buckets).
  for (int b : touched_buckets_) {
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
  if (offset_ > 4.0) renormalise();

  e.blocks = distinct;
  e.moment = moment;
  e.magnitude = std::log(moment);
  e.duration = static_cast<double>(generations);
  e.topplings = topplings;
  return e;
}

}  // namespace bkq
