// The event-driven rate-and-state engine; see rsf_loader.hpp.
#include "engine/rsf_loader.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "engine/rsf_events.hpp"

namespace bkq {

namespace {
bool handed_back(const RsfCycle& c, int j, double ln_vh);
}

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

RsfLoader::RsfLoader(const RsfModel& m, double v_handover)
    : t_ref_(m.n(), 0.0), x_ref_(m.n()), heap_(m.n()), ln_vh_(std::log(v_handover)) {
  if (!(m.v_pl > 0) || !(m.k > 0))
    throw Error("rsf: the event-driven engine needs a loader (k > 0, V_pl > 0)");
  const RsfNeighbours nb = rsf_neighbours(m);
  for (int j = 0; j < m.n(); ++j) {
    const rsf::Params& p = m.law[j].params();
    rsf::Slider s;
    s.a = p.a;
    s.b_rsf = p.b_rsf;
    s.dc = p.dc;
    s.sigma = m.sigma;
    s.stressing_rate = m.k * m.v_pl;
    s.k_eff = m.k;
    for (int e = nb.start[j]; e < nb.start[j + 1]; ++e) s.k_eff += nb.k[e];
    slider_.push_back(s);
  }
}

rsf::SliderState RsfLoader::state_at(int j, double t) const {
  if (t == t_ref_[j]) return x_ref_[j];
  return rsf::evolve(slider_[j], x_ref_[j], t - t_ref_[j]);
}

void RsfLoader::set(int j, double t, rsf::SliderState x) {
  t_ref_[j] = t;
  x_ref_[j] = x;
  heap_.set(j, t + rsf::time_to_speed(slider_[j], x, ln_vh_));
}

void RsfLoader::stress_step(int j, double t, double dtau) {
  set(j, t, rsf::stress_step(slider_[j], state_at(j, t), dtau));
}

RsfEventEngine::RsfEventEngine(RsfModel m, double tolerance, double v_threshold, double v_handover,
                               const std::vector<double>& v, const std::vector<double>& theta)
    : m_(std::move(m)), tol_(tolerance), v_th_(v_threshold), loader_(m_, v_handover) {
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
    integrate_event(t_next, t_end);
  }
  EventRecord e = pending_.front();
  pending_.pop_front();
  return e;
}

// Whether block j can go back to its closed form: below V_h, and not decelerating while the
// closed form would have it nucleate (V theta/D_c >= 1, where it only accelerates) -- such a
// block, slowed by its neighbours or by healing the nucleation form leaves out, would be handed
// straight back to the integrator. Near steady state (ln Omega < 0.05) a decelerating block
// goes back once it is a decade below V_h, so that a creeping barrier ends the integration.
namespace {
bool handed_back(const RsfCycle& c, int j, double ln_vh) {
  const double ln_v = c.ln_v(j);
  if (!(ln_v < ln_vh)) return false;
  if (c.dy()[c.n() + j] >= 0) return true;
  const double ln_omega = ln_v + c.ln_theta(j) - std::log(c.model().law[j].params().dc);
  return ln_omega < 0 || (ln_omega < 0.05 && ln_v < ln_vh - std::log(10.0));
}
}  // namespace

// From t0 on the cycle integrator runs the whole grid from every block's closed-form state,
// until no event is open and every block is below V_h (or t_end); its events get the run's
// times and numbers, and every block goes back to its closed form from where it ended.
void RsfEventEngine::integrate_event(double t0, double t_end) {
  const int n = m_.n();
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
    for (int j = 0; j < n && done; ++j) done = handed_back(cycle, j, ln_vh);
    if (done) break;
  }
  steps_ += cycle.accepted();
  t_ = t0 + cycle.t();
  for (int j = 0; j < n; ++j) loader_.set(j, t_, {cycle.ln_v(j), cycle.ln_theta(j)});
}

std::vector<double> RsfEventEngine::snapshot() const {
  if (!pending_.empty()) throw Error("rsf: a checkpoint inside an event");
  std::vector<double> s = {t_, static_cast<double>(events_), static_cast<double>(integrations_),
                           static_cast<double>(steps_)};
  for (int j = 0; j < loader_.n(); ++j) {
    s.push_back(loader_.t_ref(j));
    s.push_back(loader_.x_ref(j).ln_v);
    s.push_back(loader_.x_ref(j).ln_theta);
  }
  return s;
}

void RsfEventEngine::restore(const std::vector<double>& s) {
  const int n = loader_.n();
  if (s.size() != 4 + 3 * static_cast<std::size_t>(n))
    throw Error("rsf: a checkpoint of another chain's size");
  t_ = s[0];
  events_ = static_cast<std::int64_t>(s[1]);
  integrations_ = static_cast<std::int64_t>(s[2]);
  steps_ = static_cast<std::int64_t>(s[3]);
  for (int j = 0; j < n; ++j) loader_.set(j, s[4 + 3 * j], {s[5 + 3 * j], s[6 + 3 * j]});
  pending_.clear();
}

}  // namespace bkq
