// The Olami–Feder–Christensen automaton (Olami, Feder & Christensen 1992, Phys. Rev. Lett.
// 68, 1244): the quasistatic, massless limit of a two-dimensional spring-block fault. Each
// site j of an nx × ny square lattice carries a stress F_j; the threshold is F_th = 1.
//
// Drive: every site's stress grows at one rate, so the loader jumps by 1 − max F and the
// largest site (the lowest index in a tie) reaches the threshold. The field is kept as
// g_j = F_j − offset with one shared offset, so driving is O(1); a max tree over buckets of
// sites (updated once per event, for the sites the avalanche touched) gives the largest.
// Toppling (OFC eq. 2): a site with F_j >= 1 sets F_j = 0 and adds α F_j to each of its
// z = 4 neighbours. Update order (OfcParams::sequential): by default parallel, by
// generations. Generation 1 is the trigger (with any site holding exactly its stress);
// generation t + 1 is every site that reached the threshold during generation t. All sites
// of a generation release the stress they held at its start, then each receiver adds its
// neighbours' shares in a fixed pairing, so the field does not depend on list order and the
// lattice's symmetries hold bit for bit; a site may topple again in a later generation of
// the same avalanche. Sequential: one site at a time, first in, first out.
// Viscoelastic relaxation (after Hainzl, Zoller & Kurths 1999, J. Geophys. Res. 104, 7243):
// a toppling also hands relaxation_alpha F_j to each neighbour's pending stress P, which
// flows in as dF/dl = P / tau, dP/dl = -P / tau over the drive l; relaxing sites reach the
// threshold at their own times, kept in a heap beside the max tree.
// Boundaries, per axis: free is OFC's open boundary (the share α F_j pushed over the edge is
// lost; an edge site keeps α, not 1/z_eff); periodic wraps. Stress is conserved in a
// toppling exactly when α = 1/4 and no share crosses a free edge.
// An event is one avalanche: sites index j = x + nx y (x along strike, model.blocks).
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "engine/event_record.hpp"

namespace bkq {

struct OfcParams {
  int nx = 1, ny = 1;  // sites along strike (model.blocks) and across (model.rows)
  double alpha = 0.2;  // share of a toppling site's stress given to each neighbour at once
  bool periodic_x = false, periodic_y = false;
  // Toppling order: false, parallel by generations; true, one site at a time (first in,
  // first out).
  bool sequential = false;
  // Viscoelastic relaxation (after Hainzl, Zoller & Kurths 1999, J. Geophys. Res. 104,
  // 7243): a toppling site also hands relaxation_alpha of its stress to each neighbour as
  // pending stress, which flows into the neighbour as exp(-drive / relaxation_time) decays
  // (the drive is the automaton's clock). relaxation_time = 0: off.
  double relaxation_time = 0;
  double relaxation_alpha = 0;
  bool relaxes() const { return relaxation_time > 0; }
  int sites() const { return nx * ny; }
};

struct OfcCounters {
  std::int64_t events = 0;
  std::int64_t topplings = 0;
  std::int64_t generations = 0;
};

// Everything needed to continue exactly: the field as stored, the shared offset, the
// cumulative drive and the counters (the max tree is rebuilt from the field bit for bit).
struct OfcSnapshot {
  std::vector<double> g;
  double offset = 0, load = 0;
  OfcCounters counters;
  // With relaxation: each site's pending stress, the load it was last brought up to, and
  // the load at which it reaches the threshold as computed then (-1 for a site without
  // pending stress); empty without relaxation.
  std::vector<double> pending, pending_at, arrival;
};

// The starting field of a seed: each site's stress uniform in [0, 1) (std::mt19937_64 and
// engine/initial_state.hpp's conversion, so a seed gives the same field on every platform).
std::vector<double> ofc_initial_field(const OfcParams& p, std::uint64_t seed);

class OfcEngine {
 public:
  // Throws bkq::Error for a lattice or α that cannot run (no boundary dissipates and α = 1/4:
  // an avalanche would never end; an axis too short to wrap).
  static void check(const OfcParams& p);
  // The length of the stored field (snapshot().g): the sites padded to whole buckets of a
  // power-of-two count, the padding at -inf.
  static std::size_t stored_size(const OfcParams& p);

  // A fresh start from the stresses `initial` (each in [0, 1), one per site).
  OfcEngine(const OfcParams& p, const std::vector<double>& initial);
  OfcEngine(const OfcParams& p, const OfcSnapshot& saved);

  // Drives to the next threshold and topples the avalanche. The record: the trigger at
  // (trigger, trigger_row) = (x, y); the bounding box of the sites toppled, columns
  // first_block..last_block and rows first_row..last_row (lowest and highest coordinates,
  // also on a periodic axis); blocks = distinct sites toppled; moment = total stress released (the
  // sum of F_j over topplings); duration = generations; load = cumulative drive at the trigger;
  // topplings = all topplings; max_speed, pad_displacement, energy_residual = 0.
  EventRecord next_event();

  OfcSnapshot snapshot() const;
  const OfcCounters& counters() const { return counters_; }
  const OfcParams& params() const { return p_; }
  double load() const { return load_; }
  // The stress now (with relaxation: what has flowed in of the pending stress so far).
  double stress(int j) const;
  // Pending stress not yet flowed in (0 without relaxation).
  double pending(int j) const;
  std::vector<double> field() const;
  // The value the loader ranks, F_j - offset (the stored one).
  double ranked_value(int j) const { return g_[j]; }
  // The site with the largest stress, the lowest index in a tie (what the loader picks).
  int argmax() const { return tree_[1].j; }
  // Stress that left the lattice over free edges in all events so far (for the balance).
  double lost() const { return lost_; }

  // Keep each event's slip map (output.event_slip): after next_event(), slips() holds
  // (site j, stress it released over the event: the sum over its topplings, in their order,
  // of what it held) for the sites that toppled, ascending in j, and slip_topplings() how
  // many times each toppled (the same order), for an event of magnitude >= min_magnitude;
  // for a smaller one both are empty. The released stresses sum to the event's moment (up
  // to the rounding of the order of summation). Off (the default): nothing is kept, at the
  // cost of one untaken branch per toppling; on, a toppling appends (site, release) to a
  // list, and only a mapped event sorts it.
  void keep_slips(bool on, double min_magnitude = -HUGE_VAL);
  const std::vector<std::pair<int, double>>& slips() const { return slips_; }
  const std::vector<int>& slip_topplings() const { return slip_topplings_; }

 private:
  // The loader's max tree over buckets of kBucket sites: a node holds its subtree's largest
  // value, the lowest site holding it, and whether another site holds it too (so that an
  // event without ties, the usual case, skips the search for them).
  struct Node {
    double g;
    int j;
    bool tied;
  };
  static constexpr int kBucket = 8;
  static bool same(const Node& a, const Node& b) {
    return a.j == b.j && a.g == b.g && a.tied == b.tied;
  }
  void build_tree();
  void rebuild_tree();
  void scan(int b);
  void pull(int i);
  void touch(int j);  // marks j's bucket for the end-of-event tree update
  void renormalise();
  void note_first_toppling(int j, std::uint32_t stamp, std::uint32_t first_generation,
                           EventRecord& e, int& distinct);
  void pass_pending(int n, double amount);
  void collect_slips(double magnitude);
  template <bool kRelax>
  void avalanche_generations(EventRecord& e, std::uint32_t first_generation, double& moment,
                             double& lost, std::int64_t& topplings, std::int64_t& generations,
                             int& distinct);
  template <bool kRelax>
  void avalanche_sequential(EventRecord& e, std::uint32_t first_generation, double& moment,
                            double& lost, std::int64_t& topplings, std::int64_t& generations,
                            int& distinct);
  // Relaxation: brings site j's pending stress up to the current load (what has flowed in
  // joins g_), its arrival time of the threshold, and the heap of those times.
  void fold(int j);
  double crossing(int j) const;
  void mark_relaxing(int j);
  void heap_set(int j, double key);
  void heap_remove(int j);
  void heap_up(int k);
  void heap_down(int k);

  OfcParams p_;
  std::vector<double> g_;  // F_j - offset_, padded to whole buckets with -inf
  double offset_ = 0, load_ = 0;
  OfcCounters counters_;
  double lost_ = 0;

  int buckets_ = 1;  // a power of two
  std::vector<Node> tree_;
  std::vector<int> touched_buckets_;
  std::vector<unsigned char> bucket_marked_;
  void collect_ties(int node, double value);
  // x + nx y neighbours of j in the order left, right, down, up; -1 for a free edge. An
  // interior site's are j -+ 1 and j -+ nx; edge_ says which of a site's sides is an edge.
  void neighbours(int j, int nb[4]) const;

  // Per avalanche: the generation lists, and the receivers of a generation with the
  // shares each got, by the side they came from (left, right, down, up).
  std::vector<int> now_, next_;
  struct Receiver {
    int n;
    double in[4];
  };
  std::vector<Receiver> receivers_;
  // Per site, small so that the lattice's bookkeeping stays in cache: the generation stamp
  // it last received in (and its entry in receivers_ then), and the one it last toppled in
  // (it toppled in this event when that is at least the event's first generation).
  struct Site {
    std::uint32_t queued_at, toppled_at;
    std::int32_t slot;
  };
  std::vector<Site> site_;
  std::uint32_t stamp_ = 0;  // generations so far, since the stamps were last cleared
  // Sequential order: the queue (a ring of at most one entry per site), each entry's depth
  // in the causal chain (the event's duration is the deepest), and who is queued.
  std::vector<int> queue_, depth_;
  std::vector<unsigned char> queued_;
  // Relaxation: per site, the pending stress and the load it was brought up to; a min-heap
  // of the loads at which relaxing sites reach the threshold (heap_pos_ -1: not in it);
  // the sites whose pending stress or stress changed in this event.
  std::vector<double> pend_, pend_at_;
  std::vector<std::pair<double, int>> heap_;
  std::vector<int> heap_pos_, relax_dirty_;
  std::vector<unsigned char> relax_marked_;
  // The slip map (keep_slips): the event's topplings as (site, release) in toppling order,
  // and the event's map as handed out.
  bool keep_slips_ = false;
  double slip_min_magnitude_ = 0;
  std::vector<std::pair<int, double>> releases_, slips_;
  std::vector<int> slip_topplings_;
  std::vector<unsigned char> edge_;  // bit d: side d (left, right, down, up) is an edge
  int wrap_[4] = {0, 0, 0, 0};       // offset to the neighbour across side d on a wrapped axis
};

}  // namespace bkq
