// The active-block event integration; see rsf_active.hpp.
#include "engine/rsf_active.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "engine/dormand_prince.hpp"
#include "engine/rsf_loader.hpp"

namespace bkq {

namespace {
// The stress [a sigma] the active blocks' slip builds up on an inactive neighbour before it is
// passed to its closed form: its clock is then late by at most a 5 % change in its slip rate.
constexpr double kPassOn = 0.05;

}  // namespace

std::vector<EventRecord> join_overlapping(std::vector<EventRecord> found) {
  std::stable_sort(found.begin(), found.end(), [](const EventRecord& a, const EventRecord& b) {
    return a.hypocentre_time < b.hypocentre_time;
  });
  std::vector<EventRecord> out;
  for (const EventRecord& e : found) {
    if (out.empty() || !(e.hypocentre_time < out.back().hypocentre_time + out.back().duration)) {
      out.push_back(e);
      continue;
    }
    EventRecord& a = out.back();
    const double end = std::max(a.hypocentre_time + a.duration, e.hypocentre_time + e.duration);
    a.blocks += e.blocks;
    a.moment += e.moment;
    a.magnitude = std::log(a.moment);
    a.first_block = std::min(a.first_block, e.first_block);
    a.last_block = std::max(a.last_block, e.last_block);
    a.first_row = std::min(a.first_row, e.first_row);
    a.last_row = std::max(a.last_row, e.last_row);
    if (e.max_speed > a.max_speed) {
      a.max_speed = e.max_speed;
      a.peak_time = e.peak_time;
    }
    a.duration = end - a.hypocentre_time;
  }
  return out;
}

RsfActiveIntegration::RsfActiveIntegration(const RsfModel& m, double tolerance, double v_threshold)
    : m_(m),
      tol_(tolerance),
      v_th_(v_threshold),
      nb_(rsf_neighbours(m)),
      group_(m.n(), -1),
      slot_(m.n(), -1),
      stamp_(m.n(), 0),
      fresh_(m.n(), 0),
      held_(m.n(), 0.0),
      slip_at_join_(m.n(), 0.0),
      passed_(nb_.index.size(), 0.0),
      in_touched_(m.n(), 0) {}

double RsfActiveIntegration::value(int i, int comp0) const {
  const int n = m_.n(), comp = i / n, j = i % n;
  const dopri::Adaptive<>& dp = dp_of(j);
  return (comp0 == 0 ? dp.y : dp.dy)[3 * slot_[j] + comp];
}

double RsfActiveIntegration::friction_stress(int j) const {
  return m_.sigma * m_.law[j].friction(m_.form, ln_v(j), ln_theta(j)).f;
}

double RsfActiveIntegration::owed(int i) const {
  double dtau = 0;
  for (int e = nb_.start[i]; e < nb_.start[i + 1]; ++e) {
    const int j = nb_.index[e];
    if (slot_[j] >= 0) dtau += nb_.k[e] * (slip(j) - passed_[e]);
  }
  return dtau;
}

RsfStepSpan RsfActiveIntegration::span(const Group& g) const {
  RsfStepSpan p;
  p.model = &m_;
  p.n = m_.n();
  p.count = static_cast<int>(g.id.size());
  p.id = g.id.data();
  p.slot = slot_.data();
  p.y0 = g.dp.y_prev.data();
  p.d0 = g.dp.dy_prev.data();
  p.y1 = g.dp.y.data();
  p.d1 = g.dp.dy.data();
  p.held_slip = held_.data();
  p.t0 = g.dp.t_prev;
  p.t1 = g.dp.t;
  return p;
}

int RsfActiveIntegration::new_group(double t) {
  int g = 0;
  while (g < static_cast<int>(g_.size()) && g_[g]->live) ++g;
  if (g == static_cast<int>(g_.size())) g_.push_back(std::make_unique<Group>(v_th_));
  Group& G = *g_[g];
  G.dp.t = G.dp.t_prev = t;
  G.dp.h = 0;
  for (auto* v : {&G.dp.y, &G.dp.y_prev, &G.dp.dy, &G.dp.dy_prev}) v->clear();
  G.id.clear();
  G.tau0.clear();
  G.live = true;
  G.proposed = G.parked = G.stale = false;
  // A group of an earlier run stopped at its t_end inside an event: that event is not this one.
  if (grouped_) G.detector.forget_event();
  live_.insert(std::upper_bound(live_.begin(), live_.end(), g), g);
  return g;
}

void RsfActiveIntegration::retire(int g) {
  g_[g]->live = false;
  live_.erase(std::find(live_.begin(), live_.end(), g));
}

void RsfActiveIntegration::activate(RsfLoader& loader, int j, int g, double t_abs, double dtau) {
  Group& G = *g_[g];
  // It has had every neighbour's slip so far.
  for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
    const int i = nb_.index[e];
    passed_[e] = slip_or_held(i);
  }
  loader.sync(j, t_abs, true);
  // The active blocks' stress reaches it at once: the direct effect, theta kept (the loader's
  // step along steady state is for a barrier's slow loading, not for a step it is integrated
  // through).
  rsf::SliderState x = loader.state_at(j, t_abs);
  x.ln_v += dtau / (m_.law[j].params().a * m_.sigma);
  // A velocity-strengthening block that crept on in the nucleation form has let theta fall as
  // ln theta0 - slip/D_c, far below steady state (V theta/D_c << 1, where the aging law would
  // heal it at once and the step size collapse): it starts at the steady state of its stress,
  // a ln V + b ln theta kept.
  const rsf::Params& p = m_.law[j].params();
  if (p.a > p.b_rsf && x.ln_v + x.ln_theta - std::log(p.dc) < -1) {
    const double ln_v = (p.a * x.ln_v + p.b_rsf * (x.ln_theta - std::log(p.dc))) / (p.a - p.b_rsf);
    x = {ln_v, std::log(p.dc) - ln_v};
    ++resets_;
  }
  loader.hold(j);
  if (!in_touched_[j]) {
    in_touched_[j] = 1;
    touched_.push_back(j);
  }
  fresh_[j] = 1;
  const int s = static_cast<int>(G.id.size());
  group_[j] = g;
  slot_[j] = s;
  G.id.push_back(j);
  slip_at_join_[j] = held_[j];
  for (auto* v : {&G.dp.y, &G.dp.y_prev}) v->insert(v->end(), {held_[j], x.ln_v, x.ln_theta});
  for (auto* v : {&G.dp.dy, &G.dp.dy_prev}) v->insert(v->end(), {0.0, 0.0, 0.0});
  // The elastic stress balances friction (and damping) here.
  double tau = m_.k * (m_.v_pl * G.dp.t - held_[j]);
  for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) tau += nb_.k[e] * (passed_[e] - held_[j]);
  const double v = std::exp(x.ln_v);
  G.tau0.push_back(m_.sigma * m_.law[j].friction(m_.form, x.ln_v, x.ln_theta).f + m_.eta * v - tau);
  G.detector.activated(j, held_[j]);
  const double h = 1e-3 * std::min(m_.law[j].params().dc / v, std::exp(x.ln_theta));
  G.dp.h = s == 0 ? h : std::min(G.dp.h, h);
  G.proposed = false;
  G.stale = true;
  ++activations_;
}

void RsfActiveIntegration::release(RsfLoader& loader, int j, double t_abs) {
  Group& G = *g_[group_[j]];
  const int s = slot_[j];
  const double slip = G.dp.y[3 * s];
  const rsf::SliderState x{G.dp.y[3 * s + 1], G.dp.y[3 * s + 2]};
  held_[j] = slip;
  loader.move(j, slip - slip_at_join_[j]);
  const double summed = loader.release(j);
  // A barrier handed back above steady state enters it at constant friction, except at the
  // t_a cut (as the whole grid's hand-back does).
  const bool cut = G.dp.t >= t_a(j);
  loader.set(j, t_abs, cut ? x : rsf::onto_steady_state(loader.slider(j), x));
  if (summed != 0) loader.stress_step(j, t_abs, summed);
  // The last slot takes its place.
  const int last = static_cast<int>(G.id.size()) - 1;
  if (s != last) {
    G.id[s] = G.id[last];
    slot_[G.id[s]] = s;
    G.tau0[s] = G.tau0[last];
    for (auto* v : {&G.dp.y, &G.dp.y_prev, &G.dp.dy, &G.dp.dy_prev})
      for (int c = 0; c < 3; ++c) (*v)[3 * s + c] = (*v)[3 * last + c];
  }
  G.id.pop_back();
  G.tau0.pop_back();
  for (auto* v : {&G.dp.y, &G.dp.y_prev, &G.dp.dy, &G.dp.dy_prev}) v->resize(3 * G.id.size());
  slot_[j] = -1;
  group_[j] = -1;
  G.proposed = false;
  G.stale = true;
  // Its slip to its inactive neighbours, what they have not had of it.
  ++stamp_now_;
  for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
    const int i = nb_.index[e];
    if (i == j || slot_[i] >= 0 || stamp_[i] == stamp_now_) continue;
    stamp_[i] = stamp_now_;
    double dtau = 0;
    for (int f = nb_.start[i]; f < nb_.start[i + 1]; ++f)
      if (nb_.index[f] == j) {
        dtau += nb_.k[f] * (slip - passed_[f]);
        passed_[f] = slip;
      }
    if (dtau != 0) loader.sudden_stress_step(i, t_abs, dtau);
  }
  // It has had its neighbours' slip so far (its stress is the law's at its state).
  for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
    const int i = nb_.index[e];
    passed_[e] = slip_or_held(i);
  }
}

void RsfActiveIntegration::merge(int into, int from) {
  Group &A = *g_[into], &B = *g_[from];
  const std::vector<int> mine = A.id, theirs = B.id;
  for (std::size_t s = 0; s < B.id.size(); ++s) {
    const int j = B.id[s];
    group_[j] = into;
    slot_[j] = static_cast<int>(A.id.size());
    A.id.push_back(j);
    A.tau0.push_back(B.tau0[s]);
  }
  A.dp.y.insert(A.dp.y.end(), B.dp.y.begin(), B.dp.y.end());
  A.dp.y_prev.insert(A.dp.y_prev.end(), B.dp.y_prev.begin(), B.dp.y_prev.end());
  A.dp.dy.insert(A.dp.dy.end(), B.dp.dy.begin(), B.dp.dy.end());
  A.dp.dy_prev.insert(A.dp.dy_prev.end(), B.dp.dy_prev.begin(), B.dp.dy_prev.end());
  A.dp.h = std::min(A.dp.h, B.dp.h);
  A.detector.absorb(B.detector, mine, theirs, [&](int j) { return slip(j); });
  A.proposed = false;
  A.stale = true;
  B.id.clear();
  retire(from);
}

void RsfActiveIntegration::rebuild(int g) {
  Group& G = *g_[g];
  const int count = static_cast<int>(G.id.size());
  G.cstart.assign(1, 0);
  G.cslot.clear();
  G.cblock.clear();
  G.ck.clear();
  for (int s = 0; s < count; ++s) {
    const int j = G.id[s];
    for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
      G.cslot.push_back(slot_[nb_.index[e]]);
      G.cblock.push_back(nb_.index[e]);
      G.ck.push_back(nb_.k[e]);
    }
    G.cstart.push_back(static_cast<int>(G.cslot.size()));
  }
  const std::size_t size = 3 * static_cast<std::size_t>(count);
  for (auto& k : G.dp.k) k.resize(size);
  G.dp.ytmp.resize(size);
  G.dp.err.resize(size);
  G.v.resize(count);
  G.dp.dy.resize(size);
  if (count > 0) rhs(G, G.dp.t, G.dp.y.data(), G.dp.dy.data());
  G.stale = false;
  G.proposed = false;
}

void RsfActiveIntegration::rebuild_stale() {
  for (const int g : live_)
    if (g_[g]->stale) rebuild(g);
}

// The cycle integrator's right-hand side over the slots; a held neighbour's slip rate is 0
// and its slip its held value.
void RsfActiveIntegration::rhs(const Group& g, double t, const double* y, double* dy) {
  const int count = static_cast<int>(g.id.size());
  std::vector<double>& v = g.v;
  for (int s = 0; s < count; ++s) v[s] = std::exp(y[3 * s + 1]);
  for (int s = 0; s < count; ++s) {
    const rsf::Law& law = m_.law[g.id[s]];
    const double ln_v = y[3 * s + 1], ln_th = y[3 * s + 2];
    const double dlnth = law.dlntheta_dt(m_.state_law, v[s], ln_v, ln_th);
    const rsf::FrictionValue fr = law.friction(m_.form, ln_v, ln_th);
    double dlnv;
    if (m_.dynamics == RsfDynamics::QuasiDynamic) {
      double c = 0;
      for (int e = g.cstart[s]; e < g.cstart[s + 1]; ++e)
        c += g.ck[e] * ((g.cslot[e] >= 0 ? v[g.cslot[e]] : 0.0) - v[s]);
      const double dtau = m_.k * (m_.v_pl - v[s]) + c;
      dlnv = (dtau - m_.sigma * fr.f_lntheta * dlnth) / (m_.sigma * fr.f_lnv + m_.eta * v[s]);
    } else if (m_.dynamics == RsfDynamics::ImposedRate) {
      dlnv = 0;
    } else {
      double c = 0;
      for (int e = g.cstart[s]; e < g.cstart[s + 1]; ++e)
        c += g.ck[e] * ((g.cslot[e] >= 0 ? y[3 * g.cslot[e]] : held_[g.cblock[e]]) - y[3 * s]);
      const double tau = g.tau0[s] + m_.k * (m_.v_pl * t - y[3 * s]) + c;
      dlnv = (tau - m_.eta * v[s] - m_.sigma * fr.f) / (m_.mass * v[s]);
    }
    dy[3 * s] = v[s];
    dy[3 * s + 1] = dlnv;
    dy[3 * s + 2] = dlnth;
  }
}

// RsfCycle::step over the slots (the same scheme, error norm and step-size control), proposed.
void RsfActiveIntegration::propose(int g, double t_max) {
  Group& G = *g_[g];
  const auto norm = [&] {
    double err = 0;
    for (std::size_t i = 0; i < G.dp.y.size(); ++i) {
      const double ei = G.dp.err[i];
      const double scale =
          i % 3 == 0 ? tol_ * (m_.law[G.id[i / 3]].params().dc + std::fabs(G.dp.ytmp[i])) : tol_;
      err = dopri::worse(err, std::fabs(ei) / scale);
    }
    return err;
  };
  G.dp.propose(
      t_max, [&](double t, const double* y, double* dy) { rhs(G, t, y, dy); }, norm,
      [&](double t) {
        throw Error("rsf: the step size fell below the clock's resolution at t = " +
                    std::to_string(t) + " s into an event (rsf.dc, integrator.tolerance)");
      });
  G.proposed = true;
}

void RsfActiveIntegration::concerned(int b) {
  concerned_.clear();
  if (!grouped_) {
    if (!live_.empty()) concerned_.push_back(live_.front());
    return;
  }
  for (int e = nb_.start[b]; e < nb_.start[b + 1]; ++e) {
    const int g = group_[nb_.index[e]];
    if (g >= 0 && std::find(concerned_.begin(), concerned_.end(), g) == concerned_.end())
      concerned_.push_back(g);
  }
  std::sort(concerned_.begin(), concerned_.end());
}

void RsfActiveIntegration::process_item(RsfLoader& loader, double t0, double t) {
  const double now = t0 + t;
  const int b = loader.next_block();
  if (loader.next_is_phase()) {
    loader.rephase();
  } else if (loader.next_is_quantum()) {
    loader.sync(b, now);
    ++syncs_;
    // The quantum reaches its active neighbours at once: a stress step on the slot.
    for (int e = nb_.start[b]; e < nb_.start[b + 1]; ++e) {
      const int i = nb_.index[e], s = slot_[i];
      if (s < 0) continue;
      const double dtau = loader.take_held_stress(i);
      if (dtau == 0) continue;
      Group& G = *g_[group_[i]];
      const double v = std::exp(G.dp.y[3 * s + 1]);
      G.dp.y[3 * s + 1] += dtau / (m_.law[i].params().a * m_.sigma + m_.eta * v);
      G.tau0[s] += dtau;
      G.stale = true;  // the slot's derivative is stale: rebuild
      G.proposed = false;
    }
  } else {
    // A block at V_h joins the group it touches, merging those it touches, or starts one.
    int g;
    if (concerned_.empty()) {
      g = new_group(t);
    } else {
      g = concerned_.front();
      for (std::size_t c = 1; c < concerned_.size(); ++c) merge(g, concerned_[c]);
    }
    activate(loader, b, g, now, owed(b));
  }
}

bool RsfActiveIntegration::take_due(RsfLoader& loader, double t, double t0) {
  bool any = false;
  while (loader.next_time() - t0 <= t) {
    concerned(loader.next_block());
    for (const int c : concerned_)
      if (g_[c]->dp.t < t) return any;  // a group behind: the run loop brings it here first
    process_item(loader, t0, t);
    any = true;
  }
  return any;
}

bool RsfActiveIntegration::all_parked() const {
  for (const int g : live_)
    if (!g_[g]->parked) return false;
  return true;
}

bool RsfActiveIntegration::any_in_event() const {
  for (const int g : live_)
    if (g_[g]->detector.in_event()) return true;
  return false;
}

void RsfActiveIntegration::commit(RsfLoader& loader, int g, double t0,
                                  const HandBack& handed_back) {
  {
    Group& G = *g_[g];
    for (const int j : G.id) fresh_[j] = 0;
    G.dp.accept();
    G.proposed = false;
    ++accepted_;
    slot_steps_ += static_cast<std::int64_t>(G.id.size());
    for (int s = 0; s < static_cast<int>(G.id.size()); ++s)
      if (!std::isfinite(G.dp.y[3 * s + 1]))
        throw Error("rsf: non-finite slip rate in an event at t = " + std::to_string(t0 + G.dp.t) +
                    " s (lower integrator.tolerance)");
    if (auto e = G.detector.observe(span(G))) found_.push_back(*e);
    // A group brought up to a t_a cut that opens an event there calls the stop off: the run
    // ends at a later cut, with no event open.
    if (grouped_ && t_stop_ < t_end_ && G.detector.in_event()) {
      t_stop_ = t_end_;
      for (const int h : live_) g_[h]->parked = false;
    }
    if (G.dp.t >= t_stop_) {
      G.parked = true;
      return;
    }
  }
  const double t = g_[g]->dp.t, now = t0 + t;
  const int anchor = g_[g]->id.front();
  bool changed = take_due(loader, t, t0);
  g = group_[anchor];  // a join may have merged it into another group
  // The active blocks' slip reaches their inactive neighbours' clocks as sudden stress steps
  // (the direct effect) once it has built up to kPassOn a sigma; one brought to V_h, or a
  // barrier taken away from steady state, is due and joins at once.
  ++stamp_now_;
  for (std::size_t s = 0; s < g_[g]->id.size(); ++s) {
    const int j = g_[g]->id[s];
    for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
      const int i = nb_.index[e];
      if (slot_[i] >= 0 || stamp_[i] == stamp_now_) continue;
      stamp_[i] = stamp_now_;
      const double dtau = owed(i);
      if (!(std::fabs(dtau) >= kPassOn * m_.law[i].params().a * m_.sigma)) continue;
      loader.sudden_stress_step(i, now, dtau);
      for (int f = nb_.start[i]; f < nb_.start[i + 1]; ++f)
        if (slot_[nb_.index[f]] >= 0) passed_[f] = slip(nb_.index[f]);
    }
  }
  changed = take_due(loader, t, t0) || changed;
  g = group_[anchor];
  if (changed) rebuild_stale();
  // Blocks back to their closed forms (not in the step they joined).
  cur_ = g;
  std::vector<int>& leaving = leaving_;
  leaving.clear();
  if (!g_[g]->detector.in_event())
    for (const int j : g_[g]->id)
      if (!fresh_[j] && handed_back(*this, j)) leaving.push_back(j);
  // A block handed back once the run has lasted its t_a (the hand-back test's cut) ends the
  // run when no event is open, as the whole grid's integration ends there: what is due then
  // starts the next one, so that its events are returned.
  bool cut = false;
  for (const int j : leaving) cut = cut || t >= t_a(j);
  for (const int j : leaving) release(loader, j, now);
  if (cut && !any_in_event()) {
    t_stop_ = t;
    for (const int h : live_)
      if (g_[h]->proposed && g_[h]->dp.proposed_t > t) g_[h]->proposed = false;
    if (g_[g]->id.empty()) {
      retire(g);
    } else {
      rebuild_stale();
      g_[g]->parked = true;
    }
    return;
  }
  if (!leaving.empty()) {
    if (grouped_ && g_[g]->id.empty()) retire(g);
    take_due(loader, t, t0);
    rebuild_stale();
  }
  if (g_[g]->live && g_[g]->id.empty()) retire(g);
}

double RsfActiveIntegration::run(RsfLoader& loader, int first, double t0, double t_end,
                                 const HandBack& handed_back) {
  found_.clear();
  events_.clear();
  t_stop_ = t_end_ = t_end - t0;
  // Due items are read on the integration's clock (a time that rounds to within it of a
  // group's time is due), so that a step to the next loader time always moves the clock.
  const int g0 = new_group(0.0);
  activate(loader, first, g0, t0, 0.0);
  take_due(loader, 0.0, t0);
  rebuild_stale();
  double t_last = 0;
  while (!live_.empty()) {
    if (all_parked() && (!grouped_ || loader.next_time() - t0 > t_stop_)) break;
    // The loader's next item: at once where its groups are at its time (or past it: due).
    const double t_item = loader.next_time() - t0;
    concerned(loader.next_block());
    bool ready = !concerned_.empty();
    double t_at = 0;
    for (const int c : concerned_) {
      ready = ready && g_[c]->dp.t >= t_item;
      t_at = std::max(t_at, g_[c]->dp.t);
      // A group it touches does not step past it.
      if (g_[c]->proposed && g_[c]->dp.proposed_t > t_item) g_[c]->proposed = false;
    }
    if (ready) {
      process_item(loader, t0, t_at);
      t_last = std::max(t_last, t_at);
      rebuild_stale();
      continue;
    }
    // Each group's next step: up to the next loader item that touches it (without groups,
    // the next item), and the stop.
    int next = -1;
    for (const int g : live_) {
      Group& G = *g_[g];
      if (G.parked) continue;
      if (G.dp.t >= t_stop_) {  // at the stop already (a cut, or joined there)
        G.parked = true;
        continue;
      }
      if (G.stale) rebuild(g);
      if (!G.proposed) {
        double t_max;
        if (grouped_) {
          double horizon = std::numeric_limits<double>::infinity();
          for (std::size_t e = 0; e < G.cblock.size(); ++e)
            if (G.cslot[e] < 0) horizon = std::min(horizon, loader.time_of(G.cblock[e]));
          t_max = std::min(t_stop_, horizon - t0);
          if (!(t_max > G.dp.t)) continue;  // an item at its time waits behind another
        } else {
          t_max = std::min(t_end, loader.next_time()) - t0;
        }
        propose(g, t_max);
      }
      if (next < 0 || G.dp.proposed_t < g_[next]->dp.proposed_t) next = g;
    }
    if (concerned_.empty() && (next < 0 || t_item < g_[next]->dp.proposed_t) && t_item <= t_stop_) {
      process_item(loader, t0, t_item);  // a new group, or a quantum or phase of no group's
      t_last = std::max(t_last, t_item);
      rebuild_stale();
      continue;
    }
    if (next < 0) {
      if (all_parked()) continue;  // parked at the stop in this pass: the loop's top ends the run
      throw Error("rsf: the active-block integration found no group to step");
    }
    t_last = std::max(t_last, g_[next]->dp.proposed_t);
    commit(loader, next, t0, handed_back);
  }
  // Every block still active goes back at its group's time.
  for (const int g : std::vector<int>(live_)) {
    Group& G = *g_[g];
    t_last = std::max(t_last, G.dp.t);
    while (!G.id.empty()) release(loader, G.id.back(), t0 + G.dp.t);
    retire(g);
  }
  for (const int j : touched_) {
    in_touched_[j] = 0;
    fresh_[j] = 0;
    held_[j] = 0;
    slip_at_join_[j] = 0;
    for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
      passed_[e] = 0;
      const int i = nb_.index[e];
      for (int f = nb_.start[i]; f < nb_.start[i + 1]; ++f) passed_[f] = 0;
    }
  }
  touched_.clear();
  events_ = join_overlapping(std::move(found_));
  found_.clear();
  return t0 + t_last;
}

}  // namespace bkq
