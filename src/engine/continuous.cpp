// Continuous driving; see continuous.hpp.
#include "engine/continuous.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "engine/contacts.hpp"
#include "model/friction_laws.hpp"

namespace bkq {

ContinuousDriver::ContinuousDriver(const ChainForces& forces, Stepper& stepper,
                                   const Substrate& substrate, ChainState state, double dt)
    : forces_(forces),
      stepper_(stepper),
      substrate_(substrate),
      st_(std::move(state)),
      dt_(dt),
      located_releases_(stepper.stick_rule() == StickRule::Located) {
  const int n = forces.n();
  all_ = Range{0, n};
  wd_old_.assign(n, 0.0);
  w_start_.assign(n, 0.0);
  slid_.assign(n, 0);
  st_.recompute_sum_w();
  // Blocks loaded beyond the threshold at the start break loose before the first step.
  const SubstrateState sub = substrate_.at(st_.t);
  const double anchor = sub.s + (forces.params().pad_moves() ? st_.x : 0.0);
  const ContactScan scan =
      settle_contacts(forces_, st_, wd_old_.data(), anchor, Ranges(&all_, 1), false, [](int) {});
  sliding_ = scan.sliding;
  if (sliding_ > 0) start_episode(-1);
  energy_.e0 = energy();
  power_ = power();
}

ContinuousDriver::ContinuousDriver(const ChainForces& forces, Stepper& stepper,
                                   const Substrate& substrate, const ContinuousSnapshot& saved,
                                   double dt)
    : forces_(forces),
      stepper_(stepper),
      substrate_(substrate),
      st_(saved.state),
      dt_(dt),
      located_releases_(stepper.stick_rule() == StickRule::Located) {
  const int n = forces.n();
  const auto size = static_cast<std::size_t>(n);
  if (st_.w.size() != size || st_.wd.size() != size || st_.mobile.size() != size ||
      st_.dir.size() != size || saved.w_start.size() != size || saved.slid.size() != size)
    throw Error("the saved continuous-run state does not fit a chain of " + std::to_string(n) +
                " blocks");
  all_ = Range{0, n};
  wd_old_.assign(size, 0.0);
  w_start_ = saved.w_start;
  slid_ = saved.slid;
  sliding_ = saved.sliding;
  in_episode_ = saved.in_episode;
  episode_ = saved.episode;
  episode_t0_ = saved.episode_t0;
  episode_x0_ = saved.episode_x0;
  episodes_ = saved.episodes;
  energy_ = saved.energy;
  stepper_.restore_carried_state(saved.stepper);
  power_ = power();
}

ContinuousSnapshot ContinuousDriver::snapshot() const {
  return {st_,      sliding_,    in_episode_, w_start_,  slid_,
          episode_, episode_t0_, episode_x0_, episodes_, stepper_.carried_state(),
          energy_};
}

double ContinuousDriver::energy() const {
  // The chain state's own s is the event engine's; here the schedule gives it.
  ChainState st = st_;
  const SubstrateState sub = substrate();
  st.s = sub.s;
  return forces_.spring_energy(st) + forces_.kinetic_energy(st, sub.v);
}

ContinuousDriver::Power ContinuousDriver::power() const {
  const ModelParams& p = forces_.params();
  const SubstrateState sub = substrate();
  const double x = p.pad_moves() ? st_.x : 0.0;
  const int n = forces_.n();
  // One pass, every sum in block order beside the others (each is a chain of dependent
  // additions; side by side they cost the time of one). Friction: a sliding block's
  // opposes its frozen direction; a stuck one does no work against the substrate
  // (w' = 0) and adds +0.0, which leaves the sum as it was.
  double sum_w = 0, sum_wd = 0, sum_u2 = 0, friction = 0;
  visit_law(p.law, [&]<class L>() {
    const L law(p);
    const double v = sub.v;
    const double* __restrict w = st_.w.data();
    const double* __restrict wd = st_.wd.data();
    const double* __restrict mobile = st_.mobile.data();
    const double* __restrict dir = st_.dir.data();
    auto pass = [&]<bool Friction, bool Damper>() {
      double s_w = 0, s_wd = 0, s_u2 = 0, f = 0;
      for (int j = 0; j < n; ++j) {
        s_w += w[j];
        s_wd += wd[j];
        if constexpr (Damper) s_u2 += (wd[j] - v) * (wd[j] - v);
        if constexpr (Friction)
          f += mobile[j] != 0.0 ? law.magnitude(wd[j]) * (L::backslip ? dir[j] : 1.0) * wd[j] : 0.0;
      }
      sum_w = s_w;
      sum_wd = s_wd;
      sum_u2 = s_u2;
      friction = f;
    };
    const bool rubs = sliding_ > 0 && p.law != law_id<law::None>;
    if (p.c_u != 0)
      rubs ? pass.template operator()<true, true>() : pass.template operator()<false, true>();
    else
      rubs ? pass.template operator()<true, false>() : pass.template operator()<false, false>();
  });
  const double sum_u1 = sum_wd - n * sub.v;
  Power w;
  w.momentum = p.m_u * sum_u1;
  w.force = p.k_p * (sum_w - p.n * sub.s - p.n * x) + p.c_u * sum_u1;
  w.dissipation =
      p.m_u * friction + p.c_u * sum_u2 + (p.pad_moves() ? p.c_p * st_.xd * st_.xd : 0.0);
  if (forces_.viscous()) {
    // The dashpots between blocks (model.viscosity): internal forces, which cancel in the sum,
    // and the power they dissipate.
    const Range all{0, p.n};
    w.dissipation += forces_.damper_power(st_.wd.data(), Ranges(&all, 1));
  }
  if (forces_.rayleigh()) {
    // Rayleigh damping: its force on the blocks, -alpha_M m_u sum u' - beta_K k_p sum (u' - x')
    // (the neighbour springs' parts cancel), and the power u'^T C u' it dissipates.
    const double xd = p.pad_moves() ? st_.xd : 0.0;
    w.force += p.rayleigh_alpha * p.m_u * sum_u1 + p.rayleigh_beta * p.k_p * (sum_u1 - p.n * xd);
    w.dissipation += forces_.rayleigh_power(st_.wd.data(), xd, sub.v);
  }
  return w;
}

double ContinuousDriver::pad_friction() const {
  const ModelParams& p = forces_.params();
  // With the pad held the steppers do not keep sum_w, so sum it here (output time only).
  double sum_w = st_.sum_w, x = 0;
  if (p.pad_moves()) {
    x = st_.x;
  } else {
    sum_w = 0;
    for (double w : st_.w) sum_w += w;
  }
  return p.k_p * (sum_w - p.n * substrate().s - p.n * x);
}

void ContinuousDriver::start_episode(int trigger) {
  in_episode_ = true;
  episode_ = EventRecord{};
  episode_.event = ++episodes_;
  episode_.load = substrate().s;
  episode_.trigger = trigger;
  episode_t0_ = st_.t;
  episode_x0_ = st_.x;
  std::copy(st_.w.begin(), st_.w.end(), w_start_.begin());
  std::fill(slid_.begin(), slid_.end(), 0);
  for (int j = 0; j < forces_.n(); ++j)
    if (st_.mobile[j] != 0.0) slid_[j] = 1;
}

void ContinuousDriver::step() {
  const Ranges ranges(&all_, 1);
  const double t0 = st_.t;
  // A schedule step changes the substrate speed abruptly: sliding blocks keep their lab
  // velocity, stuck ones stay stuck.
  const double jump = substrate_.speed_jump(t0, t0 + dt_);
  std::copy(st_.wd.begin(), st_.wd.end(), wd_old_.begin());
  stepper_.step(forces_, substrate_, st_, dt_, ranges);
  if (jump != 0.0)
    for (int j = 0; j < forces_.n(); ++j)
      if (st_.mobile[j] != 0.0) {
        st_.wd[j] += jump;
        if (st_.wd[j] != 0.0) st_.dir[j] = std::copysign(1.0, st_.wd[j]);
      }

  const SubstrateState sub = substrate_.at(st_.t);
  const double anchor = sub.s + (forces_.params().pad_moves() ? st_.x : 0.0);
  int first_release = -1;
  const ContactScan scan =
      settle_contacts(forces_, st_, wd_old_.data(), anchor, ranges,
                      stepper_.stick_rule() == StickRule::Crossing, [&](int j) {
                        if (first_release < 0) first_release = j;
                        if (in_episode_) slid_[j] = 1;
                      });
  // Located releases (the located wrapper and the adaptive stepper): the blocks that broke
  // loose inside the step (the contact pass sees none of them: they are sliding, or stuck
  // again, at its end). Without them an episode left out every block it reached inside a
  // step, with its slip, and a slip that began and ended inside one step was no episode.
  std::span<const Stepper::Release> inside;
  if (located_releases_) inside = stepper_.releases_in_step();
  if (first_release < 0 && !inside.empty()) first_release = inside.front().block;
  const bool was_sliding = sliding_ > 0;
  sliding_ = scan.sliding;
  // The balance over the step: the substrate's work -v * (friction impulse on the chain),
  // the impulse and the dissipation by the trapezoidal rule.
  const Power before = power_;
  power_ = power();
  const double v_mid = 0.5 * (substrate_.at(t0).v + sub.v);
  const double impulse =
      power_.momentum - before.momentum + 0.5 * dt_ * (before.force + power_.force);
  energy_.work -= v_mid * impulse;
  energy_.dissipated += 0.5 * dt_ * (before.dissipation + power_.dissipation);
  if (!was_sliding && (sliding_ > 0 || !inside.empty())) {
    start_episode(first_release);
    // w_start_ was taken after the step; the blocks the contact pass released had not moved
    // yet, those released inside it had, from where they broke loose.
    for (const Stepper::Release& r : inside) w_start_[r.block] = r.w;
  }
  if (in_episode_)
    for (const Stepper::Release& r : inside) slid_[r.block] = 1;
  if (in_episode_) {
    episode_.max_speed = std::max(episode_.max_speed, scan.max_speed);
    if (sliding_ == 0) {
      in_episode_ = false;
      EventRecord e = episode_;
      double moment = 0;
      int count = 0, first = -1, last = -1;
      for (int j = 0; j < forces_.n(); ++j) {
        if (!slid_[j]) continue;
        moment += st_.w[j] - w_start_[j];
        ++count;
        if (first < 0) first = j;
        last = j;
      }
      e.blocks = count;
      e.first_block = first;
      e.last_block = last;
      e.moment = moment;
      e.magnitude = moment > 0 ? std::log(moment) : std::nan("");
      e.duration = st_.t - episode_t0_;
      e.pad_displacement = forces_.params().pad_moves() ? st_.x - episode_x0_ : 0.0;
      if (e.trigger < 0) e.trigger = first;
      if (forces_.lattice()) {
        std::vector<int> sites;
        for (int j = 0; j < forces_.n(); ++j)
          if (slid_[j]) sites.push_back(j);
        place_on_lattice(e, e.trigger, sites, forces_.nx());
      }
      finished_ = e;
    }
  }
}

std::optional<EventRecord> ContinuousDriver::finished_episode() {
  std::optional<EventRecord> e;
  std::swap(e, finished_);
  return e;
}

}  // namespace bkq
