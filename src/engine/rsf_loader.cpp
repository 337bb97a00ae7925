// The event-driven rate-and-state engine; see rsf_loader.hpp.
#include "engine/rsf_loader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "engine/rsf_events.hpp"

namespace bkq {

namespace {
template <class Cycle>
bool handed_back(const Cycle& c, int j, double ln_vh, double ln_va, bool unstable_alone,
                 bool may_cut);

// Where the closed forms are poor (d theta/dt = 1 - Omega with Omega = V theta/D_c near 1),
// a velocity-weakening block that nucleates on its own is left to the integrator: it is handed
// over when its locked phase reaches Omega = kOmegaIn (or is in [kOmegaIn, kOmegaOut)
// nucleating), and handed back below kOmegaBack or, accelerating, from kOmegaOut on: the locked
// form's d theta/dt = 1 is then within 11 % of the law's 1 - Omega, and so is the nucleation
// form's -Omega. (With kOmegaIn = 1/2 the 16 x 8 lattice's rows broke, after some 10 mm of
// plate motion, into two-site events.)
const double kLnOmegaBack = std::log(0.05), kLnOmegaIn = std::log(0.1),
             kLnOmegaOut = std::log(10.0);
// The locked form leaves out the block's creep and its unloading k_eff V (V << V_pl): a block
// goes back to it only below kSlowLocked V_pl.
constexpr double kSlowLocked = 3;
// A velocity-strengthening block goes back to its steady-state phase within this of
// Omega = 1 (or locked, Omega < 1).
constexpr double kLnOmegaSteady = 0.05;
// A block taken alone near steady sliding joins an integration at v_alone and goes back to
// being alone below v_alone/3 (not straight back and forth).
const double kLnAloneBack = std::log(3.0);
// ln V below the locked form's limit (kSlowLocked V_pl) at which a block taken alone goes back
// to it.
constexpr double kLockedMargin = 1e-6;

// Whether block j's steady sliding is unstable on its own springs: sigma (b - a)/D_c above
// the unloading stiffness of a block inside the grid, k + twice the stencil's springs. Only
// such a block is kept with the integrator near V theta/D_c = 1: it passes through there on its
// way to an event, where a stable one (a weaker asperity) may creep there for good.
bool unstable_on_own_springs(const RsfModel& m, int j) {
  const rsf::Params& p = m.law[j].params();
  double k_eff = m.k;
  for (const auto& spring : m.stencil()) k_eff += 2 * spring.k;
  return m.sigma * (p.b_rsf - p.a) / p.dc > k_eff;
}
}  // namespace

IndexedMinHeap::IndexedMinHeap(int n)
    : heap_(n), pos_(n), time_(n, std::numeric_limits<double>::infinity()) {
  for (int i = 0; i < n; ++i) heap_[i] = pos_[i] = i;
}

void IndexedMinHeap::set(int i, double time) {
  const double old = time_[i];
  time_[i] = time;
  if (time < old)
    up(pos_[i]);
  else
    down(pos_[i]);
}

void IndexedMinHeap::up(int slot) {
  const int i = heap_[slot];
  while (slot > 0) {
    const int parent = (slot - 1) / 2;
    if (!before(i, heap_[parent])) break;
    place(slot, heap_[parent]);
    slot = parent;
  }
  place(slot, i);
}

void IndexedMinHeap::down(int slot) {
  const int i = heap_[slot], n = size();
  while (true) {
    int child = 2 * slot + 1;
    if (child >= n) break;
    if (child + 1 < n && before(heap_[child + 1], heap_[child])) ++child;
    if (!before(heap_[child], i)) break;
    place(slot, heap_[child]);
    slot = child;
  }
  place(slot, i);
}

bool IndexedMinHeap::valid() const {
  for (int s = 1; s < size(); ++s)
    if (before(heap_[s], heap_[(s - 1) / 2]) || pos_[heap_[s]] != s) return false;
  return size() == 0 || pos_[heap_[0]] == 0;
}

RsfLoader::RsfLoader(const RsfModel& m, double v_handover, double creep_quantum)
    : nb_(rsf_neighbours(m)),
      t_ref_(m.n(), 0.0),
      x_ref_(m.n()),
      unsynced_(m.n(), 0.0),
      position_(m.n(), 0.0),
      lead_(m.n(), 0.0),
      clock_(m.n(), kDue),
      heap_(m.n()),
      path_(m.n()),
      in_alone_(m.n(), 0),
      h_hint_(m.n(), 0.0),
      h_first_(m.n(), 0.0),
      ln_vh_(std::log(v_handover)),
      ln_slow_(std::log(kSlowLocked * m.v_pl)),
      quantum_(creep_quantum) {
  if (!(m.v_pl > 0) || !(m.k > 0))
    throw Error("rsf: the event-driven engine needs a loader (k > 0, V_pl > 0)");
  if (!(creep_quantum > 0)) throw Error("rsf: the creep quantum must be positive");
  for (int j = 0; j < m.n(); ++j) {
    const rsf::Params& p = m.law[j].params();
    rsf::Slider s;
    s.a = p.a;
    s.b_rsf = p.b_rsf;
    s.dc = p.dc;
    s.sigma = m.sigma;
    s.stressing_rate = m.k * m.v_pl;
    s.k_eff = m.k;
    for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) s.k_eff += nb_.k[e];
    slider_.push_back(s);
    nucleates_alone_.push_back(unstable_on_own_springs(m, j) ? 1 : 0);
  }
}

rsf::SliderState RsfLoader::state_at(int j, double t) const {
  if (t == t_ref_[j]) return x_ref_[j];
  if (in_alone_[j]) {
    const rsf::AloneSlider::Point p = alone_.at(slider_[j], path_[j], t - t_ref_[j]);
    return {p.y[1], p.y[2]};
  }
  return rsf::evolve(slider_[j], x_ref_[j], t - t_ref_[j]);
}

double RsfLoader::unsynced(int j, double t) const {
  if (t == t_ref_[j]) return unsynced_[j];
  if (in_alone_[j]) return unsynced_[j] + alone_.at(slider_[j], path_[j], t - t_ref_[j]).y[0];
  return unsynced_[j] + rsf::slip(slider_[j], x_ref_[j], t - t_ref_[j]);
}

void RsfLoader::integrate_alone(double v_alone, double tolerance) {
  alone_ = rsf::AloneSlider(tolerance);
  v_alone_ = v_alone;
  alone_limits_.ln_v_target = std::log(v_alone);
  alone_limits_.ln_omega_lo = kLnOmegaBack;
  alone_limits_.ln_omega_hi = kLnOmegaOut;
  alone_limits_.ln_v_locked = ln_slow_ - kLockedMargin;
  for (int j = 0; j < n(); ++j)
    if (!held(j)) schedule(j);
}

void RsfLoader::rephase() {
  const int j = heap_.top();
  rebase(j, heap_.top_time());
  schedule(j);
}

void RsfLoader::set(int j, double t, rsf::SliderState x) {
  set(j, t, x, 0.0, 0.0);
}

void RsfLoader::set(int j, double t, rsf::SliderState x, double unsynced, double lead) {
  t_ref_[j] = t;
  x_ref_[j] = x;
  unsynced_[j] = unsynced;
  lead_[j] = lead;
  schedule(j);
}

void RsfLoader::rebase(int j, double t) {
  if (t == t_ref_[j]) return;
  if (in_alone_[j]) {
    const rsf::AloneSlider::Point p = alone_.at(slider_[j], path_[j], t - t_ref_[j]);
    unsynced_[j] += p.y[0];
    x_ref_[j] = {p.y[1], p.y[2]};
  } else {
    unsynced_[j] = unsynced(j, t);
    x_ref_[j] = state_at(j, t);
  }
  t_ref_[j] = t;
}

// The earlier of the time to V_h and the time at which the unsynced slip reaches the lead plus
// half a quantum.
void RsfLoader::schedule(int j) {
  const rsf::Slider& s = slider_[j];
  const rsf::SliderState& x = x_ref_[j];
  // A velocity-weakening block nearing steady state goes to the integrator (kOmegaIn), and so
  // does a velocity-strengthening one away from it (both only as an integration's end left
  // them: see handed_back).
  const double lo = rsf::ln_omega(s, x);
  const double amount = std::isinf(quantum_) ? quantum_ : 0.5 * quantum_ + lead_[j] - unsynced_[j];
  // Taken alone (when on): a velocity-weakening block that neither nucleates (Omega >=
  // kOmegaOut) nor is locked and slow (Omega < kOmegaBack, below kSlowLocked V_pl less a
  // margin, so that the locked form's clock to kSlowLocked V_pl lands here and not back in the
  // locked form); its forecast makes it due at once if it is at v_alone or above.
  const bool alone_on = v_alone_ > 0 && !s.strengthening();
  in_alone_[j] =
      alone_on && lo < kLnOmegaOut && !(lo < kLnOmegaBack && x.ln_v < alone_limits_.ln_v_locked);
  if (in_alone_[j]) {
    rsf::AloneSlider::Limits lim = alone_limits_;
    lim.amount = amount;
    h_first_[j] = h_hint_[j];
    const rsf::AloneSlider::Forecast f = alone_.forecast(s, x, lim, path_[j], h_first_[j]);
    if (f.h_next > 0) h_hint_[j] = f.h_next;
    using Exit = rsf::AloneSlider::Exit;
    clock_[j] = f.exit == Exit::Speed ? kDue : f.exit == Exit::Slip ? kQuantum : kPhase;
    heap_.set(j, t_ref_[j] + f.dt);
    return;
  }
  h_hint_[j] = 0;  // a closed form: the next forecast alone starts afresh
  if (alone_on && lo < kLnOmegaOut) {
    // Locked and slow: the locked form until Omega reaches kOmegaIn or V kSlowLocked V_pl.
    const rsf::NextClock c = rsf::next_clock(s, x, ln_slow_, amount, kLnOmegaIn);
    clock_[j] = c.slip ? kQuantum : kPhase;
    heap_.set(j, t_ref_[j] + c.time);
    return;
  }
  if (nucleates_alone_[j] ? !rsf::locked(s, x) && lo < kLnOmegaOut
                          : s.strengthening() && lo >= kLnOmegaSteady) {
    clock_[j] = kDue;
    heap_.set(j, t_ref_[j]);
    return;
  }
  const rsf::NextClock c =
      rsf::next_clock(s, x, ln_vh_, amount, nucleates_alone_[j] ? kLnOmegaIn : 0.0);
  clock_[j] = c.slip ? kQuantum : kDue;
  heap_.set(j, t_ref_[j] + c.time);
}

void RsfLoader::stress_step(int j, double t, double dtau) {
  rebase(j, t);
  x_ref_[j] = rsf::stress_step(slider_[j], x_ref_[j], dtau);
  schedule(j);
}

void RsfLoader::sudden_stress_step(int j, double t, double dtau) {
  rebase(j, t);
  x_ref_[j].ln_v += dtau / (slider_[j].a * slider_[j].sigma);
  schedule(j);
}

double RsfLoader::sync(int j, double t, bool settle) {
  rebase(j, t);
  const double moved = unsynced_[j];
  unsynced_[j] = 0;
  position_[j] += moved;
  double slip = moved - lead_[j];
  if (std::isinf(quantum_)) {
    slip = 0;  // no quanta: the creep is left out between events altogether
  } else if (settle) {
    lead_[j] = 0;
  } else {
    slip += 0.5 * quantum_;
    lead_[j] = 0.5 * quantum_;
  }
  if (slip != 0)
    for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e)
      if (nb_.index[e] != j) {
        const int i = nb_.index[e];
        if (held(i))
          held_stress_[i] += nb_.k[e] * slip;
        else
          stress_step(i, t, nb_.k[e] * slip);
      }
  schedule(j);
  return slip;
}

void RsfLoader::hold(int j) {
  if (held_.empty()) {
    held_.assign(n(), 0);
    held_stress_.assign(n(), 0.0);
  }
  held_[j] = 1;
  held_stress_[j] = 0;
  h_hint_[j] = 0;
  heap_.set(j, std::numeric_limits<double>::infinity());
}

double RsfLoader::release(int j) {
  if (!held(j)) return 0;
  held_[j] = 0;
  const double s = held_stress_[j];
  held_stress_[j] = 0;
  return s;
}

double RsfLoader::take_held_stress(int j) {
  if (!held(j)) return 0;
  const double s = held_stress_[j];
  held_stress_[j] = 0;
  return s;
}

RsfEventEngine::RsfEventEngine(RsfModel m, double tolerance, double v_threshold, double v_handover,
                               double creep_quantum, const std::vector<double>& v,
                               const std::vector<double>& theta)
    : m_(std::move(m)),
      tol_(tolerance),
      v_th_(v_threshold),
      loader_(m_, v_handover, creep_quantum) {
  if (!(v_handover < v_threshold))
    throw Error("rsf: the hand-over speed must lie below the seismic threshold");
  const int n = m_.n();
  for (const auto* x : {&v, &theta})
    if (x->size() != 1 && x->size() != static_cast<std::size_t>(n))
      throw Error("rsf: a start value per block or one for all");
  const auto at = [](const std::vector<double>& x, int j) { return x.size() == 1 ? x[0] : x[j]; };
  for (int j = 0; j < n; ++j) loader_.set(j, 0, {std::log(at(v, j)), std::log(at(theta, j))});
}

std::optional<EventRecord> RsfEventEngine::next(double t_end) {
  while (pending_.empty()) {
    const double t_next = loader_.next_time();
    if (!(t_next < t_end)) {
      t_ = std::max(t_, t_end);
      return std::nullopt;
    }
    if (loader_.next_is_phase()) {
      loader_.rephase();
      continue;
    }
    if (loader_.next_is_quantum()) {
      loader_.sync(loader_.next_block(), t_next);
      ++syncs_;
      continue;
    }
    if (active_blocks())
      integrate_active(loader_.next_block(), t_next, t_end);
    else
      integrate_event(t_next, t_end);
  }
  EventRecord e = pending_.front();
  pending_.pop_front();
  return e;
}

// Whether the integration has lasted block j's t_a = a sigma/(k V_pl), where handed_back()
// sends blocks back from where their closed forms are poor. A velocity-strengthening block
// handed back then keeps its state (its theta goes to D_c/V at its V); one handed back earlier
// enters steady state at constant friction (rsf::onto_steady_state). Projecting at the cut as
// well sent the 16 x 8 lattice from one start into a cycle of two-site events after 70 mm of
// plate motion (docs/validation/rsf-events.md).
namespace {
template <class Cycle>
bool cut_short(const Cycle& c, int j) {
  const RsfModel& m = c.model();
  return c.t() >= m.law[j].params().a * m.sigma / (m.k * m.v_pl);
}
}  // namespace

// Whether block j can go back to its closed form: below V_h and where its closed form holds.
// Locked (below kOmegaBack, or Omega < 1 for a > b) only below kSlowLocked V_pl. A velocity-
// strengthening block (a > b): within kLnOmegaSteady of steady state, where its steady-state
// phase takes it. A velocity-weakening one that nucleates on its own: accelerating from
// kOmegaOut on (nucleating); in between the closed forms are poor, so it stays with the
// integrator. Any other: accelerating, locked, or near steady state (ln Omega < 0.05) a decade
// below V_h, so that one creeping there ends the integration (not decelerating while the
// nucleation form, accelerating only, would send it straight back).
// On a grid some block may always be near V theta/D_c = 1 (asperities nucleating in turn), so
// once the integration has lasted the block's t_a = a sigma/(k V_pl) such a block (from
// kOmegaIn on) and a velocity-strengthening one away from steady state go back below V_h: the
// events are then returned, and RsfLoader::schedule sends them straight back, so that the
// integration goes on from there. The cut applies only where may_cut (no event open: the
// active-block integration, which hands blocks back one by one, would otherwise send them back
// and take them in again at every step of an event).
namespace {
template <class Cycle>
bool handed_back(const Cycle& c, int j, double ln_vh, double ln_va, bool unstable_alone,
                 bool may_cut) {
  const double ln_v = c.ln_v(j);
  const RsfModel& m = c.model();
  const rsf::Params& p = m.law[j].params();
  const double lo = ln_v + c.ln_theta(j) - std::log(p.dc);
  if (!(p.a > p.b_rsf) && ln_va > -std::numeric_limits<double>::infinity() && lo < kLnOmegaOut)
    return ln_v < ln_va - kLnAloneBack;
  if (!(ln_v < ln_vh)) return false;
  const bool cut = may_cut && cut_short(c, j);
  const bool slow = ln_v < std::log(kSlowLocked * m.v_pl);
  const bool accelerating = c.dy()[c.n() + j] >= 0;
  if (p.a > p.b_rsf) return lo < 0 ? slow : lo < kLnOmegaSteady || cut;
  if (unstable_alone) {
    if (lo < kLnOmegaBack) return slow;
    return lo < kLnOmegaOut ? cut && lo >= kLnOmegaIn : accelerating;
  }
  return accelerating || (lo < 0 && slow) || (lo < 0.05 && ln_v < ln_vh - std::log(10.0));
}
}  // namespace

// At t0 every block's unsynced creep is passed on (in block order), then the cycle integrator
// runs the whole grid from every block's closed-form state, until no event is open and every
// block is below V_h (or t_end); its events get the run's times and numbers, and every block
// goes back to its closed form from where it ended, its position moved by the integrated slip.
void RsfEventEngine::integrate_event(double t0, double t_end) {
  const int n = m_.n();
  for (int j = 0; j < n; ++j) loader_.sync(j, t0, true);
  std::vector<double> v(n), theta(n);
  for (int j = 0; j < n; ++j) {
    const rsf::SliderState x = loader_.state_at(j, t0);
    v[j] = std::exp(x.ln_v);
    theta[j] = std::exp(x.ln_theta);
  }
  RsfCycle cycle(m_, tol_, v, theta);
  RsfEventDetector detector(v_th_);
  const double ln_vh = loader_.ln_v_handover();
  ++integrations_;
  while (true) {
    cycle.step(t_end - t0);
    if (!std::isfinite(cycle.ln_v(0)))
      throw Error("rsf: non-finite slip rate in an event at t = " + std::to_string(t0 + cycle.t()) +
                  " s (lower integrator.tolerance)");
    if (auto e = detector.observe(cycle)) {
      e->event = ++events_;
      e->hypocentre_time += t0;
      e->peak_time += t0;
      e->load = m_.v_pl * e->hypocentre_time;
      pending_.push_back(*e);
    }
    if (t0 + cycle.t() >= t_end) break;
    if (detector.in_event()) continue;
    bool done = true;
    for (int j = 0; j < n && done; ++j)
      done = handed_back(cycle, j, ln_vh, loader_.ln_v_alone(), loader_.nucleates_alone(j), true);
    if (done) break;
  }
  steps_ += cycle.accepted();
  t_ = t0 + cycle.t();
  for (int j = 0; j < n; ++j) {
    loader_.move(j, cycle.slip(j));
    const rsf::SliderState x{cycle.ln_v(j), cycle.ln_theta(j)};
    loader_.set(j, t_, cut_short(cycle, j) ? x : rsf::onto_steady_state(loader_.slider(j), x));
  }
}

// Only the active blocks are integrated (engine/rsf_active.hpp); its events get the run's
// times and numbers as integrate_event's do.
void RsfEventEngine::integrate_active(int first, double t0, double t_end) {
  if (!active_) active_ = std::make_unique<RsfActiveIntegration>(m_, tol_, v_th_);
  active_->set_groups(groups_);
  const double ln_vh = loader_.ln_v_handover();
  ++integrations_;
  const std::int64_t steps0 = active_->accepted(), syncs0 = active_->syncs(),
                     slots0 = active_->slot_steps();
  const double ln_va = loader_.ln_v_alone();
  t_ = active_->run(
      loader_, first, t0, t_end, [this, ln_vh, ln_va](const RsfActiveIntegration& a, int j) {
        return handed_back(a, j, ln_vh, ln_va, loader_.nucleates_alone(j), !a.in_event());
      });
  steps_ += active_->accepted() - steps0;
  syncs_ += active_->syncs() - syncs0;
  active_block_steps_ += active_->slot_steps() - slots0;
  for (EventRecord e : active_->events()) {
    e.event = ++events_;
    e.hypocentre_time += t0;
    e.peak_time += t0;
    e.load = m_.v_pl * e.hypocentre_time;
    pending_.push_back(e);
  }
}

namespace {

// An event record as numbers and back (the integers exactly: each is below 2^53).
constexpr std::size_t kRecordSize = 18;

void put_record(std::vector<double>& s, const EventRecord& e) {
  const double r[kRecordSize] = {static_cast<double>(e.event),
                                 e.load,
                                 static_cast<double>(e.trigger),
                                 static_cast<double>(e.blocks),
                                 e.moment,
                                 e.magnitude,
                                 e.duration,
                                 e.max_speed,
                                 e.pad_displacement,
                                 static_cast<double>(e.first_block),
                                 static_cast<double>(e.last_block),
                                 e.energy_residual,
                                 static_cast<double>(e.topplings),
                                 static_cast<double>(e.trigger_row),
                                 static_cast<double>(e.first_row),
                                 static_cast<double>(e.last_row),
                                 e.hypocentre_time,
                                 e.peak_time};
  s.insert(s.end(), r, r + kRecordSize);
}

EventRecord take_record(const double* r) {
  EventRecord e;
  e.event = static_cast<std::int64_t>(r[0]);
  e.load = r[1];
  e.trigger = static_cast<int>(r[2]);
  e.blocks = static_cast<int>(r[3]);
  e.moment = r[4];
  e.magnitude = r[5];
  e.duration = r[6];
  e.max_speed = r[7];
  e.pad_displacement = r[8];
  e.first_block = static_cast<int>(r[9]);
  e.last_block = static_cast<int>(r[10]);
  e.energy_residual = r[11];
  e.topplings = static_cast<std::int64_t>(r[12]);
  e.trigger_row = static_cast<int>(r[13]);
  e.first_row = static_cast<int>(r[14]);
  e.last_row = static_cast<int>(r[15]);
  e.hypocentre_time = r[16];
  e.peak_time = r[17];
  return e;
}

}  // namespace

std::vector<double> RsfEventEngine::snapshot() const {
  std::vector<double> s = {t_, static_cast<double>(events_), static_cast<double>(integrations_),
                           static_cast<double>(steps_), static_cast<double>(syncs_)};
  for (int j = 0; j < loader_.n(); ++j) {
    s.push_back(loader_.t_ref(j));
    s.push_back(loader_.x_ref(j).ln_v);
    s.push_back(loader_.x_ref(j).ln_theta);
    s.push_back(loader_.unsynced(j, loader_.t_ref(j)));
    s.push_back(loader_.lead(j));
    s.push_back(loader_.position(j));
  }
  // The counters of the active-block integration (absent from older checkpoints).
  s.push_back(static_cast<double>(active_block_steps_));
  s.push_back(static_cast<double>(loader_.alone_steps()));
  // The records not yet returned (absent from older checkpoints: none).
  s.push_back(static_cast<double>(pending_.size()));
  for (const EventRecord& e : pending_) put_record(s, e);
  // The blocks' first steps alone (absent from older checkpoints: none).
  for (int j = 0; j < loader_.n(); ++j) s.push_back(loader_.alone_first_step(j));
  return s;
}

void RsfEventEngine::restore(const std::vector<double>& s) {
  const int n = loader_.n();
  constexpr std::size_t head = 5, per_block = 6;
  const std::size_t size = head + per_block * static_cast<std::size_t>(n);
  const std::size_t pending =
      s.size() > size + 2 ? static_cast<std::size_t>(std::max(0.0, s[size + 2])) : 0;
  const std::size_t records_end = size + 3 + kRecordSize * pending;
  const bool hints = s.size() == records_end + static_cast<std::size_t>(n);
  if (s.size() < size || (s.size() > size + 2 && s.size() != records_end && !hints))
    throw Error("rsf: a checkpoint of another chain's size");
  for (int j = 0; j < n; ++j) loader_.set_alone_first_step(j, hints ? s[records_end + j] : 0.0);
  active_block_steps_ = s.size() > size ? static_cast<std::int64_t>(s[size]) : 0;
  t_ = s[0];
  events_ = static_cast<std::int64_t>(s[1]);
  integrations_ = static_cast<std::int64_t>(s[2]);
  steps_ = static_cast<std::int64_t>(s[3]);
  syncs_ = static_cast<std::int64_t>(s[4]);
  for (int j = 0; j < n; ++j) {
    const double* b = s.data() + head + per_block * j;
    loader_.set(j, b[0], {b[1], b[2]}, b[3], b[4]);
    loader_.set_position(j, b[5]);
  }
  // After the blocks: their forecasts are the ones the run had made (not counted twice).
  loader_.set_alone_steps(s.size() > size + 1 ? static_cast<long long>(s[size + 1]) : 0);
  pending_.clear();
  for (std::size_t i = 0; i < pending; ++i)
    pending_.push_back(take_record(s.data() + size + 3 + kRecordSize * i));
}

}  // namespace bkq
