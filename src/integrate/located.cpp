// Located transitions for the explicit schemes; see located.hpp.
#include "integrate/located.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "integrate/transit.hpp"
#include "integrate/transition_rule.hpp"

namespace bkq {

namespace {

// Transitions are bisected on the dense output to this fraction of the step.
constexpr double kLocate = 1e-13;
// Newton steps at most on real steps after the dense output's estimate (one or two suffice).
constexpr int kPolish = 3;

// Cubic Hermite interpolation on [0, 1] of a function with values y0, y1 and derivatives
// d0, d1 (with respect to time) at the ends of a step of length h, at fraction s.
double hermite(double y0, double d0, double y1, double d1, double h, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2.0 * s3 - 3.0 * s2 + 1.0) * y0 + (s3 - 2.0 * s2 + s) * h * d0 +
         (3.0 * s2 - 2.0 * s3) * y1 + (s3 - s2) * h * d1;
}

}  // namespace

LocatedTransitions::LocatedTransitions(std::unique_ptr<Stepper> scheme, int n_blocks)
    : scheme_(std::move(scheme)), traits_(located_traits(scheme_->traits())), n_(n_blocks) {
  if (!scheme_->traits().locatable)
    throw Error("integrator.transitions = located: the scheme " + std::string(scheme_->name()) +
                " resolves its transitions itself; located applies to rk2, rk4 and verlet "
                "(use integrator.transitions = step)");
  for (auto* v : {&w0_, &v0_, &a0_, &w1_, &v1_, &a1_, &wq_}) v->assign(n_blocks, 0.0);
  mark_.assign(n_blocks, 0);
  released_mark_.assign(n_blocks, 0);
  fired_.reserve(n_blocks);
  releases_.reserve(n_blocks);
}

void LocatedTransitions::restore(std::span<const double> s) {
  if (s.size() != 1)
    throw Error("located transitions: the saved stepper state does not fit this scheme");
  last_stick_time_ = s[0];
}

void LocatedTransitions::save_start(const ChainState& st, Ranges ranges) {
  for (const Range& r : ranges) {
    std::copy(st.w.begin() + r.lo, st.w.begin() + r.hi, w0_.begin() + r.lo);
    std::copy(st.wd.begin() + r.lo, st.wd.begin() + r.hi, v0_.begin() + r.lo);
  }
  x0_ = st.x;
  xd0_ = st.xd;
  sum0_ = st.sum_w;
  t0_ = st.t;
}

void LocatedTransitions::restore_start(ChainState& st, Ranges ranges) const {
  for (const Range& r : ranges) {
    std::copy(w0_.begin() + r.lo, w0_.begin() + r.hi, st.w.begin() + r.lo);
    std::copy(v0_.begin() + r.lo, v0_.begin() + r.hi, st.wd.begin() + r.lo);
  }
  st.x = x0_;
  st.xd = xd0_;
  st.sum_w = sum0_;
  st.t = t0_;
}

bool LocatedTransitions::fired_at_end(const ChainForces& forces, const Substrate& sub,
                                      const ChainState& st, Ranges ranges) {
  const Friction& fr = forces.friction();
  const double anchor = sub.at(st.t).s + (forces.params().pad_moves() ? st.x : 0.0);
  fired_.clear();
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j)
      if (transition::fired(fr, st.mobile[j], st.dir[j], st.wd[j],
                            [&] { return forces.spring_force(st.w.data(), j, anchor); }))
        fired_.push_back(j);
  return !fired_.empty();
}

double LocatedTransitions::dense_w(int j, double theta) const {
  if (!in_ranges(j)) return w1_[j];  // held over the step (w1_ holds the halo)
  return hermite(w0_[j], v0_[j], w1_[j], v1_[j], h_, theta);
}

double LocatedTransitions::dense_wd(int j, double theta) const {
  return hermite(v0_[j], a0_[j], v1_[j], a1_[j], h_, theta);
}

double LocatedTransitions::event_value(const ChainForces& forces, const Substrate& sub,
                                       const ChainState& st, int j, double theta) {
  if (st.mobile[j] != 0.0) return st.dir[j] * dense_wd(j, theta);
  // The spring force reads the block and its two neighbours (wrapped; unused at free ends).
  for (int k : {(j - 1 + n_) % n_, j, (j + 1) % n_}) wq_[k] = dense_w(k, theta);
  const double pad = forces.params().pad_moves() ? hermite(x0_, xd0_, x1_, xd1_, h_, theta) : 0.0;
  const double anchor = sub.at(t0_ + theta * h_).s + pad;
  const double f = forces.spring_force(wq_.data(), j, anchor);
  const Friction& fr = forces.friction();
  // Friction::breaks(f) exactly when this is negative (a - b < 0 iff a < b in IEEE arithmetic).
  return fr.threshold - (fr.backslip ? std::abs(f) : f);
}

double LocatedTransitions::locate(const ChainForces& forces, const Substrate& sub,
                                  const ChainState& st, int& who) {
  double best = 1.0;
  who = -1;
  for (int j : fired_) {
    // A block whose transition has not happened by the earliest so far cannot be earlier.
    const double g_best = event_value(forces, sub, st, j, best);
    if (who >= 0 && !fired(st, j, g_best)) continue;
    // The first instant at which the transition has happened, bracketed by [lo, hi] to kLocate:
    // the Illinois variant of regula falsi on the event function (Dowell & Jarratt 1971, BIT
    // 11, 168-174), a bisection whenever a step did not halve the bracket; about ten
    // evaluations instead of bisection's 43.
    double lo = 0.0, hi = best;
    double g_lo = event_value(forces, sub, st, j, 0.0), g_hi = g_best;
    int kept = 0;  // which end the last step kept: -1 lo, +1 hi
    bool bisect = false;
    while (hi - lo > kLocate) {
      const double width = hi - lo;
      double mid = 0.5 * (lo + hi);
      if (!bisect && g_lo > 0.0 && g_hi < 0.0) {
        const double secant = hi - g_hi * (hi - lo) / (g_hi - g_lo);
        if (secant > lo && secant < hi) mid = secant;
      }
      const double g = event_value(forces, sub, st, j, mid);
      if (fired(st, j, g)) {
        hi = mid;
        g_hi = g;
        if (kept == -1) g_lo *= 0.5;  // lo kept twice: the Illinois halving
        kept = -1;
      } else {
        lo = mid;
        g_lo = g;
        if (kept == 1) g_hi *= 0.5;
        kept = 1;
      }
      bisect = hi - lo > 0.5 * width;
    }
    if (who < 0 || hi < best) {
      best = hi;
      who = j;
    }
  }
  return best;
}

void LocatedTransitions::transit(const ChainForces& forces, const Substrate& sub, ChainState& st,
                                 int who, Ranges ranges) {
  located_ += apply_transitions(forces, sub, st, who, ranges, released_mark_, stamp_, releases_,
                                last_stick_time_);
}

double LocatedTransitions::newton_ratio(const ChainForces& forces, const Substrate& sub,
                                        const ChainState& st, int j) {
  const bool pad = forces.params().pad_moves();
  const SubstrateState s = sub.at(st.t);
  if (st.mobile[j] != 0.0) {
    // dir w' over dir w'': the acceleration with the flags of the step.
    const Range one{j, j + 1};
    forces.block_accelerations(st.w.data(), st.wd.data(), st.mobile.data(), st.dir.data(),
                               s.s + (pad ? st.x : 0.0), s.v + (pad ? st.xd : 0.0), s,
                               Ranges(&one, 1), a1_.data());
    return st.wd[j] / a1_[j];
  }
  // threshold - |f| over its rate: the spring force is linear in the positions and the
  // anchor, so its rate is the same expression in their velocities.
  const Friction& fr = forces.friction();
  const double f = forces.spring_force(st.w.data(), j, s.s + (pad ? st.x : 0.0));
  for (int k : {(j - 1 + n_) % n_, j, (j + 1) % n_}) wq_[k] = in_ranges(k) ? st.wd[k] : 0.0;
  const double df = forces.spring_force(wq_.data(), j, s.v + (pad ? st.xd : 0.0));
  const double side = fr.backslip && f < 0.0 ? -1.0 : 1.0;
  return (fr.threshold - side * f) / (-side * df);
}

double LocatedTransitions::sub_step_work(const ChainForces& forces, const ChainState& st,
                                         Ranges ranges, double tau) const {
  const ModelParams& p = forces.params();
  const double damper = p.c_u / p.m_u;
  return forces.with_law([&](const auto& law) {
    double sum = 0;
    for (const Range& r : ranges)
      for (int j = r.lo; j < r.hi; ++j)
        if (st.mobile[j] != 0.0) sum += step_power(law, v0_[j], st.wd[j], st.dir[j], damper);
    return transition::located_work(tau, p.m_u, sum);
  });
}

bool LocatedTransitions::include(int k, const ChainState& st) {
  if (in_ranges(k)) return false;
  mark_[k] = stamp_;
  own_.push_back(Range{k, k + 1});
  std::sort(own_.begin(), own_.end(), [](const Range& a, const Range& b) { return a.lo < b.lo; });
  std::size_t out = 0;
  for (std::size_t i = 1; i < own_.size(); ++i) {
    if (own_[i].lo <= own_[out].hi)
      own_[out].hi = std::max(own_[out].hi, own_[i].hi);
    else
      own_[++out] = own_[i];
  }
  own_.resize(out + 1);
  halo(st);
  return true;
}

void LocatedTransitions::halo(const ChainState& st) {
  // The dense positions of the blocks next to the ranges are their (held) positions.
  for (const Range& r : own_)
    for (int k : {(r.lo - 1 + n_) % n_, r.hi % n_})
      if (!in_ranges(k)) w0_[k] = w1_[k] = st.w[k];
}

bool LocatedTransitions::instant_matters(const ChainState& st, int who, Ranges ranges) {
  if (st.mobile[who] == 0.0) return true;  // a failure
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j)
      if (j != who && st.mobile[j] != 0.0 && !transition::stopped(st.dir[j], st.wd[j]))
        return false;
  return true;  // a stick after which nothing of the ranges slides: the event may end here
}

void LocatedTransitions::step(const ChainForces& forces, const Substrate& sub, ChainState& st,
                              double dt, Ranges ranges) {
  const bool pad = forces.params().pad_moves();
  const bool periodic = forces.params().boundary == Boundary::Periodic;
  const double t_end = st.t + dt;
  ++stamp_;
  releases_.clear();
  own_.assign(ranges.begin(), ranges.end());
  int blocks = 0;
  for (const Range& r : own_)
    for (int j = r.lo; j < r.hi; ++j) {
      mark_[j] = stamp_;
      ++blocks;
      // A sliding block moving against its direction (as a continuous run may leave it)
      // slides the way it moves: its transition is the next zero of its velocity.
      if (st.mobile[j] != 0.0 && st.dir[j] * st.wd[j] < 0.0 && forces.friction().backslip)
        st.dir[j] = std::copysign(1.0, st.wd[j]);
    }
  halo(st);
  work_ = 0;
  // Every block of the step's ranges can stick and break loose a few times in one step at
  // most; more cuts than this mean the step cannot resolve the transitions. The blocks that
  // join the ranges inside the step count too: a rupture front that runs through several
  // blocks at the threshold within one step cuts it once per block (the thesis scene at
  // dt = 0.03).
  int max_cuts = 8 * blocks + 16;
  for (int cuts = 0;; ++cuts) {
    const double h = t_end - st.t;
    if (!(h > 0.0)) break;
    const Ranges cur(own_);
    save_start(st, cur);
    scheme_->step(forces, sub, st, h, cur);
    ++scheme_steps_;
    if (!fired_at_end(forces, sub, st, cur)) {
      work_ += sub_step_work(forces, st, cur, h);
      break;
    }
    if (cuts == max_cuts) {
      char msg[300];
      std::snprintf(msg, sizeof msg,
                    "integrator.transitions = located: more than %d transitions inside one step "
                    "at time %.9g: reduce integrator.dt",
                    max_cuts, t_end - dt);
      throw Error(msg);
    }
    // The dense output of the attempted step: its end, and the accelerations at both ends
    // with the flags and directions of the step.
    h_ = h;
    for (const Range& r : cur) {
      std::copy(st.w.begin() + r.lo, st.w.begin() + r.hi, w1_.begin() + r.lo);
      std::copy(st.wd.begin() + r.lo, st.wd.begin() + r.hi, v1_.begin() + r.lo);
    }
    x1_ = st.x;
    xd1_ = st.xd;
    const SubstrateState s1 = sub.at(st.t), s0 = sub.at(t0_);
    forces.block_accelerations(w1_.data(), v1_.data(), st.mobile.data(), st.dir.data(),
                               s1.s + (pad ? x1_ : 0.0), s1.v + (pad ? xd1_ : 0.0), s1, cur,
                               a1_.data());
    forces.block_accelerations(w0_.data(), v0_.data(), st.mobile.data(), st.dir.data(),
                               s0.s + (pad ? x0_ : 0.0), s0.v + (pad ? xd0_ : 0.0), s0, cur,
                               a0_.data());
    int who = -1;
    const double theta = locate(forces, sub, st, who);
    if (theta < 1.0) {
      // The step again, by the same scheme, from its start to the located instant, then
      // Newton's method on such real steps: the dense output's end values come from a
      // step that ran past the transition, where the right-hand side has a kink (friction
      // at zero velocity), which limits the interpolant's accuracy there; the real steps
      // end before it, so the polished instant has the scheme's own accuracy.
      if (watcher_) watcher_->cut(forces, st, who, cur);
      double tau = theta * h;
      restore_start(st, cur);
      scheme_->step(forces, sub, st, tau, cur);
      ++scheme_steps_;
      const int polish = instant_matters(st, who, cur) ? kPolish : 0;
      for (int k = 0; k < polish; ++k) {
        const double g_over_rate = newton_ratio(forces, sub, st, who);
        const double next = tau - g_over_rate;
        if (!(next > 0.0 && next < h) || std::abs(next - tau) <= kLocate * h) break;
        tau = next;
        restore_start(st, cur);
        scheme_->step(forces, sub, st, tau, cur);
        ++scheme_steps_;
      }
      work_ += sub_step_work(forces, st, cur, tau);
    } else {
      st.t = t_end;  // located at the end: the attempted step stands
      work_ += sub_step_work(forces, st, cur, h);
    }
    const std::size_t released = releases_.size();
    transit(forces, sub, st, who, cur);
    // A block that broke loose moves for the rest of the step: its neighbours join the
    // ranges (as stuck blocks), so that the scheme's stages read their positions.
    for (std::size_t i = released; i < releases_.size(); ++i) {
      const int j = releases_[i].block;
      for (int k : {j - 1, j + 1}) {
        if (k < 0 || k >= n_) {
          if (!periodic || n_ < 2) continue;
          k = (k + n_) % n_;
        }
        if (include(k, st)) max_cuts += 8;
      }
    }
  }
  st.t = t_end;
}

std::unique_ptr<Stepper> with_located_transitions(std::unique_ptr<Stepper> scheme, int n_blocks) {
  return std::make_unique<LocatedTransitions>(std::move(scheme), n_blocks);
}

}  // namespace bkq
