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

RsfActiveIntegration::RsfActiveIntegration(const RsfModel& m, double tolerance, double v_threshold)
    : m_(m),
      tol_(tolerance),
      nb_(rsf_neighbours(m)),
      detector_(v_threshold),
      slot_(m.n(), -1),
      joined_step_(m.n(), -1),
      stamp_(m.n(), 0),
      held_(m.n(), 0.0),
      slip_at_join_(m.n(), 0.0),
      passed_(nb_.index.size(), 0.0) {}

double RsfActiveIntegration::value(int i, int comp0) const {
  const int n = m_.n(), comp = i / n, j = i % n;
  return (comp0 == 0 ? dp_.y : dp_.dy)[3 * slot_[j] + comp];
}

double RsfActiveIntegration::friction_stress(int j) const {
  return m_.sigma * m_.law[j].friction(m_.form, ln_v(j), ln_theta(j)).f;
}

double RsfActiveIntegration::owed(int i) const {
  double dtau = 0;
  for (int e = nb_.start[i]; e < nb_.start[i + 1]; ++e) {
    const int s = slot_[nb_.index[e]];
    if (s >= 0) dtau += nb_.k[e] * (dp_.y[3 * s] - passed_[e]);
  }
  return dtau;
}

RsfStepSpan RsfActiveIntegration::span() const {
  RsfStepSpan p;
  p.model = &m_;
  p.n = m_.n();
  p.count = static_cast<int>(id_.size());
  p.id = id_.data();
  p.slot = slot_.data();
  p.y0 = dp_.y_prev.data();
  p.d0 = dp_.dy_prev.data();
  p.y1 = dp_.y.data();
  p.d1 = dp_.dy.data();
  p.held_slip = held_.data();
  p.t0 = dp_.t_prev;
  p.t1 = dp_.t;
  return p;
}

void RsfActiveIntegration::activate(RsfLoader& loader, int j, double t_abs, double dtau) {
  // It has had every neighbour's slip so far.
  for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
    const int i = nb_.index[e];
    passed_[e] = slot_[i] >= 0 ? dp_.y[3 * slot_[i]] : held_[i];
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
  if (joined_step_[j] < 0) touched_.push_back(j);
  joined_step_[j] = static_cast<int>(steps_in_run_);
  const int s = static_cast<int>(id_.size());
  slot_[j] = s;
  id_.push_back(j);
  slip_at_join_[j] = held_[j];
  for (auto* v : {&dp_.y, &dp_.y_prev}) v->insert(v->end(), {held_[j], x.ln_v, x.ln_theta});
  for (auto* v : {&dp_.dy, &dp_.dy_prev}) v->insert(v->end(), {0.0, 0.0, 0.0});
  // The elastic stress balances friction (and damping) here.
  double tau = m_.k * (m_.v_pl * dp_.t - held_[j]);
  for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) tau += nb_.k[e] * (passed_[e] - held_[j]);
  const double v = std::exp(x.ln_v);
  tau0_.push_back(m_.sigma * m_.law[j].friction(m_.form, x.ln_v, x.ln_theta).f + m_.eta * v - tau);
  detector_.activated(j, held_[j]);
  const double h = 1e-3 * std::min(m_.law[j].params().dc / v, std::exp(x.ln_theta));
  dp_.h = s == 0 && steps_in_run_ == 0 ? h : std::min(dp_.h, h);
  ++activations_;
}

void RsfActiveIntegration::release(RsfLoader& loader, int j, double t_abs) {
  const int s = slot_[j];
  const double slip = dp_.y[3 * s];
  const rsf::SliderState x{dp_.y[3 * s + 1], dp_.y[3 * s + 2]};
  held_[j] = slip;
  loader.move(j, slip - slip_at_join_[j]);
  const double summed = loader.release(j);
  // A barrier handed back above steady state enters it at constant friction, except at the
  // t_a cut (as the whole grid's hand-back does).
  const bool cut = dp_.t >= m_.law[j].params().a * m_.sigma / (m_.k * m_.v_pl);
  loader.set(j, t_abs, cut ? x : rsf::onto_steady_state(loader.slider(j), x));
  if (summed != 0) loader.stress_step(j, t_abs, summed);
  // The last slot takes its place.
  const int last = static_cast<int>(id_.size()) - 1;
  if (s != last) {
    id_[s] = id_[last];
    slot_[id_[s]] = s;
    tau0_[s] = tau0_[last];
    for (auto* v : {&dp_.y, &dp_.y_prev, &dp_.dy, &dp_.dy_prev})
      for (int c = 0; c < 3; ++c) (*v)[3 * s + c] = (*v)[3 * last + c];
  }
  id_.pop_back();
  tau0_.pop_back();
  for (auto* v : {&dp_.y, &dp_.y_prev, &dp_.dy, &dp_.dy_prev}) v->resize(3 * id_.size());
  slot_[j] = -1;
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
    passed_[e] = slot_[i] >= 0 ? dp_.y[3 * slot_[i]] : held_[i];
  }
}

void RsfActiveIntegration::rebuild() {
  const int count = static_cast<int>(id_.size());
  cstart_.assign(1, 0);
  cslot_.clear();
  cblock_.clear();
  ck_.clear();
  for (int s = 0; s < count; ++s) {
    const int j = id_[s];
    for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
      cslot_.push_back(slot_[nb_.index[e]]);
      cblock_.push_back(nb_.index[e]);
      ck_.push_back(nb_.k[e]);
    }
    cstart_.push_back(static_cast<int>(cslot_.size()));
  }
  const std::size_t size = 3 * static_cast<std::size_t>(count);
  for (auto& k : dp_.k) k.resize(size);
  dp_.ytmp.resize(size);
  dp_.err.resize(size);
  v_.resize(count);
  dp_.dy.resize(size);
  if (count > 0) rhs(dp_.t, dp_.y.data(), dp_.dy.data());
}

// The cycle integrator's right-hand side over the slots; a held neighbour's slip rate is 0
// and its slip its held value.
void RsfActiveIntegration::rhs(double t, const double* y, double* dy) {
  const int count = static_cast<int>(id_.size());
  for (int s = 0; s < count; ++s) v_[s] = std::exp(y[3 * s + 1]);
  for (int s = 0; s < count; ++s) {
    const rsf::Law& law = m_.law[id_[s]];
    const double ln_v = y[3 * s + 1], ln_th = y[3 * s + 2];
    const double dlnth = law.dlntheta_dt(m_.state_law, ln_v, ln_th);
    const rsf::FrictionValue fr = law.friction(m_.form, ln_v, ln_th);
    double dlnv;
    if (m_.dynamics == RsfDynamics::QuasiDynamic) {
      double c = 0;
      for (int e = cstart_[s]; e < cstart_[s + 1]; ++e)
        c += ck_[e] * ((cslot_[e] >= 0 ? v_[cslot_[e]] : 0.0) - v_[s]);
      const double dtau = m_.k * (m_.v_pl - v_[s]) + c;
      dlnv = (dtau - m_.sigma * fr.f_lntheta * dlnth) / (m_.sigma * fr.f_lnv + m_.eta * v_[s]);
    } else if (m_.dynamics == RsfDynamics::ImposedRate) {
      dlnv = 0;
    } else {
      double c = 0;
      for (int e = cstart_[s]; e < cstart_[s + 1]; ++e)
        c += ck_[e] * ((cslot_[e] >= 0 ? y[3 * cslot_[e]] : held_[cblock_[e]]) - y[3 * s]);
      const double tau = tau0_[s] + m_.k * (m_.v_pl * t - y[3 * s]) + c;
      dlnv = (tau - m_.eta * v_[s] - m_.sigma * fr.f) / (m_.mass * v_[s]);
    }
    dy[3 * s] = v_[s];
    dy[3 * s + 1] = dlnv;
    dy[3 * s + 2] = dlnth;
  }
}

// RsfCycle::step over the slots (the same scheme, error norm and step-size control).
double RsfActiveIntegration::step(double t_max) {
  const auto norm = [&] {
    double err = 0;
    for (std::size_t i = 0; i < dp_.y.size(); ++i) {
      const double ei = dp_.err[i];
      const double scale =
          i % 3 == 0 ? tol_ * (m_.law[id_[i / 3]].params().dc + std::fabs(dp_.ytmp[i])) : tol_;
      err = dopri::worse(err, std::fabs(ei) / scale);
    }
    return err;
  };
  return dp_.step(
      t_max, [&](double t, const double* y, double* dy) { rhs(t, y, dy); }, norm,
      [](double t) {
        throw Error("rsf: the step size fell below the clock's resolution at t = " +
                    std::to_string(t) + " s into an event (rsf.dc, integrator.tolerance)");
      });
}

double RsfActiveIntegration::run(RsfLoader& loader, int first, double t0, double t_end,
                                 const HandBack& handed_back) {
  dp_.t = dp_.t_prev = 0;
  steps_in_run_ = 0;
  events_.clear();
  // What the loader has due by now: quanta passed on, blocks at V_h taken in. Due is read on
  // the integration's clock (a time that rounds to within it of dp_.t is due), so that a step to
  // the next loader time always moves dp_.t.
  const auto take_due = [&](double now) {
    bool joined = false;
    while (loader.next_time() - t0 <= dp_.t) {
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
          const double v = std::exp(dp_.y[3 * s + 1]);
          dp_.y[3 * s + 1] += dtau / (m_.law[i].params().a * m_.sigma + m_.eta * v);
          tau0_[s] += dtau;
          joined = true;  // the slot's derivative is stale: rebuild
        }
      } else {
        activate(loader, b, now, owed(b));
        joined = true;
      }
    }
    return joined;
  };
  activate(loader, first, t0, 0.0);
  take_due(t0);
  rebuild();
  std::vector<int> leaving;
  while (true) {
    // Stress steps passed on since (a joining block's creep, a leaving block's slip) may have
    // made a block due now; then up to the loader's next time, at the latest.
    if (take_due(t0 + dp_.t)) rebuild();
    step(std::min(t_end, loader.next_time()) - t0);
    ++steps_in_run_;
    slot_steps_ += static_cast<std::int64_t>(id_.size());
    for (int s = 0; s < static_cast<int>(id_.size()); ++s)
      if (!std::isfinite(dp_.y[3 * s + 1]))
        throw Error("rsf: non-finite slip rate in an event at t = " + std::to_string(t0 + dp_.t) +
                    " s (lower integrator.tolerance)");
    if (auto e = detector_.observe(span())) events_.push_back(*e);
    const double now = t0 + dp_.t;
    if (dp_.t >= t_end - t0) break;
    bool changed = take_due(now);
    // The active blocks' slip reaches their inactive neighbours' clocks as sudden stress steps
    // (the direct effect) once it has built up to kPassOn a sigma; one brought to V_h, or a
    // barrier taken away from steady state, is due and joins at once.
    ++stamp_now_;
    for (std::size_t s = 0; s < id_.size(); ++s) {
      const int j = id_[s];
      for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
        const int i = nb_.index[e];
        if (slot_[i] >= 0 || stamp_[i] == stamp_now_) continue;
        stamp_[i] = stamp_now_;
        const double dtau = owed(i);
        if (!(std::fabs(dtau) >= kPassOn * m_.law[i].params().a * m_.sigma)) continue;
        loader.sudden_stress_step(i, now, dtau);
        for (int f = nb_.start[i]; f < nb_.start[i + 1]; ++f)
          if (slot_[nb_.index[f]] >= 0) passed_[f] = dp_.y[3 * slot_[nb_.index[f]]];
      }
    }
    changed = take_due(now) || changed;
    if (changed) rebuild();
    // Blocks back to their closed forms (not in the step they joined).
    leaving.clear();
    if (!detector_.in_event())
      for (const int j : id_)
        if (joined_step_[j] < steps_in_run_ && handed_back(*this, j)) leaving.push_back(j);
    // A block handed back once the run has lasted its t_a (the hand-back test's cut) ends the
    // run when no event is open, as the whole grid's integration ends there: what is due then
    // starts the next one, so that its events are returned.
    bool cut = false;
    for (const int j : leaving)
      cut = cut || dp_.t >= m_.law[j].params().a * m_.sigma / (m_.k * m_.v_pl);
    for (const int j : leaving) release(loader, j, now);
    if (cut && !detector_.in_event()) break;
    if (!leaving.empty()) {
      take_due(now);
      rebuild();
    }
    if (id_.empty()) break;
  }
  const double t_stop = t0 + dp_.t;
  while (!id_.empty()) release(loader, id_.back(), t_stop);
  for (const int j : touched_) {
    joined_step_[j] = -1;
    held_[j] = 0;
    slip_at_join_[j] = 0;
    for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) {
      passed_[e] = 0;
      const int i = nb_.index[e];
      for (int f = nb_.start[i]; f < nb_.start[i + 1]; ++f) passed_[f] = 0;
    }
  }
  touched_.clear();
  return t_stop;
}

}  // namespace bkq
