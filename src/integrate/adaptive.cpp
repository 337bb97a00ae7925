// Dormand–Prince 5(4) with FSAL, dense output and located stick–slip transitions; see
// adaptive.hpp. Every stage is one pass over the ranges; the dense output and the event
// functions are evaluated per block, only when an event has fired over a step, and the
// located transition is then polished with a few real steps (passes over the ranges).
#include "integrate/adaptive.hpp"

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <memory>
#include <utility>

#include "core/error.hpp"
#include "integrate/dopri5_dense.hpp"
#include "integrate/transit.hpp"

namespace bkq {

namespace {

// Dormand & Prince (1980): nodes, stage coefficients (row S-1 builds stage S from the
// stages before it; the last row is the 5th-order solution), b - b_hat for the error
// estimate (the dense-output weights: integrate/dopri5_dense.hpp).
constexpr double kC[7] = {0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
constexpr double kA[6][6] = {
    {1.0 / 5},
    {3.0 / 40, 9.0 / 40},
    {44.0 / 45, -56.0 / 15, 32.0 / 9},
    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
    {35.0 / 384, 0.0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
constexpr double kE[7] = {71.0 / 57600,      0.0,        -71.0 / 16695, 71.0 / 1920,
                          -17253.0 / 339200, 22.0 / 525, -1.0 / 40};
// Step-size controller (Hairer, Nørsett & Wanner, §II.4).
constexpr double kSafety = 0.9, kFacMin = 0.2, kFacMax = 10.0;
// Transitions are bisected on the dense output, then polished on real steps, to this
// times (|t| + h).
constexpr double kLocate = 1e-13;
// Real steps at most per polished transition (Newton takes two or three in practice).
constexpr int kPolishSteps = 12;

// The continuous extension at t0 + theta h of one component with ends y0, y1 and stage
// derivatives k(0..6) (DOPRI5's CONTD5, 4th order).
template <class K>
double dense(double y0, double y1, double h, double theta, K&& k) {
  double c5 = 0;
  for (int l = 0; l < 7; ++l) c5 += dopri::kDense[l] * k(l);
  return dopri::dense(y0, y1, k(0), k(6), c5, h, theta);
}

// Records q into the running maximum m; a NaN sticks (a non-finite step must be rejected).
void take_max(double& m, double q) {
  if (q > m || std::isnan(q)) m = std::isnan(m) ? m : q;
}

}  // namespace

std::unique_ptr<Stepper> Adaptive::fresh(int n_blocks) const {
  auto copy = std::make_unique<Adaptive>(n_blocks, tol_);
  copy->set_fixed_step(fixed_h_);
  return copy;
}

Adaptive::Adaptive(int n_blocks, double tolerance) : tol_(tolerance), n_(n_blocks) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) {
    char msg[120];
    std::snprintf(msg, sizeof msg, "integrator.tolerance: expected a value in (0, 1), got %g",
                  tolerance);
    throw Error(msg);
  }
  ws_.assign(n_blocks, 0.0);
  for (auto& v : vel_) v.assign(n_blocks, 0.0);
  for (auto& a : acc_) a.assign(n_blocks, 0.0);
  wq_.assign(n_blocks, 0.0);
  fired_.reserve(n_blocks);
  mark_.assign(n_blocks, 0);
  released_mark_.assign(n_blocks, 0);
  releases_.reserve(n_blocks);
}

void Adaptive::set_fixed_step(double h) {
  if (!(h >= 0.0 && std::isfinite(h))) {
    char msg[120];
    std::snprintf(msg, sizeof msg,
                  "adaptive stepper: the fixed step must be finite and >= 0, got %g", h);
    throw Error(msg);
  }
  fixed_h_ = h;
}

double Adaptive::accelerations(const ChainForces& forces, const SubstrateState& sub,
                               const double* w, const double* wd, const ChainState& st, double x,
                               double xd, double sum_w, Ranges ranges, double* a) const {
  const bool pad = forces.params().pad_moves();
  forces.block_accelerations(w, wd, st.mobile.data(), st.dir.data(), sub.s + (pad ? x : 0.0),
                             sub.v + (pad ? xd : 0.0), sub, ranges, a);
  // Rayleigh damping on the pad reads the blocks' velocities (outside the ranges at rest).
  double sum_wd = 0;
  if (pad && forces.rayleigh())
    for (const Range& r : ranges)
      for (int j = r.lo; j < r.hi; ++j) sum_wd += wd[j];
  return pad ? forces.pad_acceleration(x, xd, sum_w, sub.s, sum_wd, sub.v) : 0.0;
}

void Adaptive::first_stage(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                           Ranges ranges) {
  for (const Range& r : ranges)
    std::copy(st.wd.begin() + r.lo, st.wd.begin() + r.hi, vel_[0].begin() + r.lo);
  pad_vel_[0] = st.xd;
  pad_acc_[0] = accelerations(forces, sub.at(st.t), st.w.data(), st.wd.data(), st, st.x, st.xd,
                              st.sum_w, ranges, acc_[0].data());
}

template <int S>
void Adaptive::stage(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                     double h, Ranges ranges) {
  const double* a = kA[S - 1];
  const double* __restrict w0 = st.w.data();
  const double* __restrict wd0 = st.wd.data();
  double* __restrict ws = ws_.data();
  double* __restrict vs = vel_[S].data();
  const double* v[S];
  const double* ac[S];
  for (int l = 0; l < S; ++l) {
    v[l] = vel_[l].data();
    ac[l] = acc_[l].data();
  }
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) {
      double dw = 0, dv = 0;
      for (int l = 0; l < S; ++l) {
        dw += a[l] * v[l][j];
        dv += a[l] * ac[l][j];
      }
      ws[j] = w0[j] + h * dw;
      vs[j] = wd0[j] + h * dv;
    }
  double x = st.x, xd = st.xd, sum_w = st.sum_w;
  if (forces.params().pad_moves()) {
    double dx = 0, dxd = 0;
    for (int l = 0; l < S; ++l) {
      dx += a[l] * pad_vel_[l];
      dxd += a[l] * pad_acc_[l];
    }
    x += h * dx;
    xd += h * dxd;
    // Blocks outside the ranges do not move: only the ranges change sum_w.
    for (const Range& r : ranges)
      for (int j = r.lo; j < r.hi; ++j) sum_w += ws[j] - w0[j];
  }
  pad_vel_[S] = xd;
  pad_acc_[S] = accelerations(forces, sub.at(st.t + kC[S] * h), ws, vs, st, x, xd, sum_w, ranges,
                              acc_[S].data());
  if constexpr (S == 6) {
    x1_ = x;
    xd1_ = xd;
    sum1_ = sum_w;
  }
}

void Adaptive::attempt(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                       double h, Ranges ranges) {
  stage<1>(forces, sub, st, h, ranges);
  stage<2>(forces, sub, st, h, ranges);
  stage<3>(forces, sub, st, h, ranges);
  stage<4>(forces, sub, st, h, ranges);
  stage<5>(forces, sub, st, h, ranges);
  stage<6>(forces, sub, st, h, ranges);
}

void Adaptive::commit(ChainState& st, double t1, bool pad, Ranges ranges) {
  for (const Range& r : ranges) {
    std::copy(ws_.begin() + r.lo, ws_.begin() + r.hi, st.w.begin() + r.lo);
    std::copy(vel_[6].begin() + r.lo, vel_[6].begin() + r.hi, st.wd.begin() + r.lo);
  }
  // FSAL: the last stage is the derivative at the new point.
  std::swap(vel_[0], vel_[6]);
  std::swap(acc_[0], acc_[6]);
  pad_vel_[0] = pad_vel_[6];
  pad_acc_[0] = pad_acc_[6];
  if (pad) {
    st.x = x1_;
    st.xd = xd1_;
    st.sum_w = sum1_;
  }
  st.t = t1;
}

double Adaptive::error_norm(const ChainState& st, double s0, double h, bool pad,
                            Ranges ranges) const {
  const double* w0 = st.w.data();
  const double* wd0 = st.wd.data();
  const double* w1 = ws_.data();
  const double* wd1 = vel_[6].data();
  double err = 0;
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) {
      double ew = 0, ev = 0;
      for (int l = 0; l < 7; ++l) {
        ew += kE[l] * vel_[l][j];
        ev += kE[l] * acc_[l][j];
      }
      take_max(err,
               std::abs(h * ew) / (1.0 + std::max(std::abs(w0[j] - s0), std::abs(w1[j] - s0))));
      take_max(err, std::abs(h * ev) / (1.0 + std::max(std::abs(wd0[j]), std::abs(wd1[j]))));
    }
  if (pad) {
    double ex = 0, exd = 0;
    for (int l = 0; l < 7; ++l) {
      ex += kE[l] * pad_vel_[l];
      exd += kE[l] * pad_acc_[l];
    }
    take_max(err, std::abs(h * ex) / (1.0 + std::max(std::abs(st.x), std::abs(x1_))));
    take_max(err, std::abs(h * exd) / (1.0 + std::max(std::abs(st.xd), std::abs(xd1_))));
  }
  return err / tol_;
}

double Adaptive::initial_step(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                              double dt, Ranges ranges) {
  // Hairer, Nørsett & Wanner, §II.4 (HINIT), in the max norm of error_norm: from the sizes
  // of y0, f(y0) and of f's change over an explicit Euler probe.
  const bool pad = forces.params().pad_moves();
  const double s0 = sub.at(st.t).s;
  const double* w0 = st.w.data();
  const double* wd0 = st.wd.data();
  const double* a0 = acc_[0].data();
  double d0 = 0, d1 = 0;
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) {
      const double sw = tol_ * (1.0 + std::abs(w0[j] - s0)), sv = tol_ * (1.0 + std::abs(wd0[j]));
      d0 = std::max({d0, std::abs(w0[j] - s0) / sw, std::abs(wd0[j]) / sv});
      d1 = std::max({d1, std::abs(wd0[j]) / sw, std::abs(a0[j]) / sv});
    }
  const double sx = tol_ * (1.0 + std::abs(st.x)), sxd = tol_ * (1.0 + std::abs(st.xd));
  if (pad) {
    d0 = std::max({d0, std::abs(st.x) / sx, std::abs(st.xd) / sxd});
    d1 = std::max({d1, std::abs(st.xd) / sx, std::abs(pad_acc_[0]) / sxd});
  }
  const double h0 = std::min(d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1, dt);

  // The Euler probe, in the scratch of stage 1 (overwritten by the first attempt).
  double* ws = ws_.data();
  double* vs = vel_[1].data();
  double sum_w = st.sum_w;
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) {
      ws[j] = w0[j] + h0 * wd0[j];
      vs[j] = wd0[j] + h0 * a0[j];
      sum_w += h0 * wd0[j];
    }
  const double x = st.x + h0 * st.xd, xd = st.xd + h0 * pad_acc_[0];
  const double ax =
      accelerations(forces, sub.at(st.t + h0), ws, vs, st, x, xd, sum_w, ranges, acc_[1].data());
  const double* a1 = acc_[1].data();
  double d2 = 0;
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) {
      const double sw = tol_ * (1.0 + std::abs(w0[j] - s0)), sv = tol_ * (1.0 + std::abs(wd0[j]));
      d2 = std::max({d2, std::abs(vs[j] - wd0[j]) / sw, std::abs(a1[j] - a0[j]) / sv});
    }
  if (pad) d2 = std::max({d2, std::abs(xd - st.xd) / sx, std::abs(ax - pad_acc_[0]) / sxd});
  d2 /= h0;
  const double d12 = std::max(d1, d2);
  const double h1 = d12 <= 1e-15 ? std::max(1e-6, 1e-3 * h0) : std::pow(0.01 / d12, 1.0 / 5.0);
  return std::min(100.0 * h0, h1);
}

double Adaptive::dense_w(const ChainState& st, int j, double h, double theta) const {
  if (!in_ranges(j)) return st.w[j];  // held fixed over the step
  return dense(st.w[j], ws_[j], h, theta, [&](int l) { return vel_[l][j]; });
}
double Adaptive::dense_wd(const ChainState& st, int j, double h, double theta) const {
  return dense(st.wd[j], vel_[6][j], h, theta, [&](int l) { return acc_[l][j]; });
}
double Adaptive::dense_x(const ChainState& st, double h, double theta) const {
  return dense(st.x, x1_, h, theta, [&](int l) { return pad_vel_[l]; });
}

bool Adaptive::fired_at_end(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                            double t1, Ranges ranges) {
  const Friction& fr = forces.friction();
  const double anchor = sub.at(t1).s + (forces.params().pad_moves() ? x1_ : 0.0);
  const double* wd1 = vel_[6].data();
  fired_.clear();
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) {
      const bool fired = st.mobile[j] != 0.0
                             ? st.dir[j] * wd1[j] <= 0.0
                             : fr.breaks(forces.spring_force(ws_.data(), j, anchor));
      if (fired) fired_.push_back(j);
    }
  return !fired_.empty();
}

bool Adaptive::fired_at(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                        int j, double t0, double h, double theta) {
  if (st.mobile[j] != 0.0) return st.dir[j] * dense_wd(st, j, h, theta) <= 0.0;
  // The spring force reads the block and its two neighbours (wrapped; unused at free ends).
  for (int k : {(j - 1 + n_) % n_, j, (j + 1) % n_}) wq_[k] = dense_w(st, k, h, theta);
  const bool pad = forces.params().pad_moves();
  const double anchor = sub.at(t0 + theta * h).s + (pad ? dense_x(st, h, theta) : 0.0);
  return forces.friction().breaks(forces.spring_force(wq_.data(), j, anchor));
}

double Adaptive::locate(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                        double h, int& who) {
  const double t0 = st.t;
  const double bracket = kLocate * (std::abs(t0) + h) / h;
  double best = 1.0;
  who = -1;
  for (int j : fired_) {
    // A block whose event has not fired by the earliest crossing so far cannot be earlier.
    if (who >= 0 && !fired_at(forces, sub, st, j, t0, h, best)) continue;
    double lo = 0.0, hi = best;
    while (hi - lo > bracket) {
      const double mid = 0.5 * (lo + hi);
      (fired_at(forces, sub, st, j, t0, h, mid) ? hi : lo) = mid;
    }
    if (who < 0 || hi < best) {
      best = hi;
      who = j;
    }
  }
  return best;
}

Adaptive::EventValue Adaptive::event_at_end(const ChainForces& forces, const Substrate& sub,
                                            const ChainState& st, int j, double t1) {
  if (st.mobile[j] != 0.0) {
    const double d = st.dir[j];
    return {d * vel_[6][j], d * acc_[6][j],
            2.0 * DBL_EPSILON * (std::abs(st.wd[j]) + std::abs(vel_[6][j]))};
  }
  const ModelParams& p = forces.params();
  const SubstrateState s1 = sub.at(t1);
  const double anchor = s1.s + (p.pad_moves() ? x1_ : 0.0);
  const double f = forces.spring_force(ws_.data(), j, anchor);
  // The spring force is linear in (w, anchor): its rate is the same expression in their
  // velocities (0 for the blocks outside the ranges, held over the step). Its rounding
  // error grows with the size of the terms it sums, |w| (w = u + s carries the loading).
  const int left = (j - 1 + n_) % n_, right = (j + 1) % n_;  // wrapped; unused at free ends
  auto w = [&](int k) { return std::abs(in_ranges(k) ? ws_[k] : st.w[k]); };
  const double size = p.k_c * (w(left) + 2.0 * w(j) + w(right)) + p.k_p * (w(j) + std::abs(anchor));
  for (int k : {left, j, right}) wq_[k] = in_ranges(k) ? vel_[6][k] : 0.0;
  const double df = forces.spring_force(wq_.data(), j, s1.v + (p.pad_moves() ? xd1_ : 0.0));
  const Friction& fr = forces.friction();
  const double side = fr.backslip && f < 0.0 ? -1.0 : 1.0;  // the threshold it nears
  return {fr.threshold - side * f, -side * df, 2.0 * DBL_EPSILON * size};
}

double Adaptive::polish(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                        double h, double theta, int who, Ranges ranges) {
  const double t0 = st.t;
  const double converged = kLocate * (std::abs(t0) + h);
  const bool sliding = st.mobile[who] != 0.0;
  // The real steps bracket the crossing: not fired at t0, fired at t0 + h.
  double lo = 0.0, hi = h, tau = theta * h, last = HUGE_VAL;
  for (int k = 1;; ++k) {
    attempt(forces, sub, st, tau, ranges);
    ++polishing_;
    const EventValue e = event_at_end(forces, sub, st, who, t0 + tau);
    const bool fired = sliding ? e.g <= 0.0 : e.g < 0.0;
    (fired ? hi : lo) = tau;
    const double newton = -e.g / e.rate;  // not finite where the rate is 0
    if (std::abs(e.g) <= e.noise || std::abs(newton) <= converged || hi - lo <= converged ||
        k == kPolishSteps)
      return tau;
    if (const double next = tau + newton; next > lo && next < hi) {
      // Newton converges quadratically; a correction no smaller than half the last one
      // is rounding noise.
      if (std::abs(newton) >= 0.5 * last) return tau;
      tau = next;
      last = std::abs(newton);
    } else {
      tau = 0.5 * (lo + hi);
      last = HUGE_VAL;
    }
  }
}

void Adaptive::transit(const ChainForces& forces, const Substrate& sub, ChainState& st, int who,
                       Ranges ranges) {
  transitions_ += apply_transitions(forces, sub, st, who, ranges, released_mark_, stamp_, releases_,
                                    last_stick_time_);
}

void Adaptive::step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                    Ranges ranges) {
  const bool pad = forces.params().pad_moves();
  const bool located = !law_traits(forces.params().law).frictionless;
  const double t_end = st.t + dt;

  ++stamp_;
  releases_.clear();
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j) {
      mark_[j] = stamp_;
      if (st.mobile[j] != 0.0 && st.dir[j] * st.wd[j] < 0.0)
        st.dir[j] = std::copysign(1.0, st.wd[j]);
    }
  // The stages read the neighbours of each range's end blocks: they stay at st.w.
  for (const Range& r : ranges)
    for (int k : {(r.lo - 1 + n_) % n_, r.hi % n_})
      if (!in_ranges(k)) ws_[k] = st.w[k];

  if (!(st.t == t_resume_)) h_ = 0.0;  // not a continuation: guess the first step afresh
  first_stage(forces, sub, st, ranges);
  if (fixed_h_ > 0.0) {
    h_ = fixed_h_;
  } else if (h_ == 0.0) {
    h_ = initial_step(forces, sub, st, dt, ranges);
  }

  bool after_rejection = false;
  while (st.t < t_end) {
    const double t0 = st.t;
    const bool last = t_end - t0 <= h_ * (1.0 + 1e-10);
    const double h = last ? t_end - t0 : h_;
    attempt(forces, sub, st, h, ranges);

    double h_next = h_;
    if (fixed_h_ == 0.0) {
      const double err = error_norm(st, sub.at(t0).s, h, pad, ranges);
      if (!(err <= 1.0)) {
        ++rejected_;
        after_rejection = true;
        h_ = h * (std::isnan(err) ? kFacMin : std::max(kFacMin, kSafety * std::pow(err, -0.2)));
        const double h_min = 16.0 * DBL_EPSILON * std::max(std::abs(t0), dt);
        if (h_ < h_min) {
          char msg[400];
          std::snprintf(
              msg, sizeof msg,
              "adaptive stepper: the step size fell to %.3g at time %.9g, below the minimum "
              "%.3g, without meeting integrator.tolerance = %g (error estimate %.3g times the "
              "tolerance): the state is not finite or the tolerance is beyond double precision "
              "for this scene",
              h_, t0, h_min, tol_, err);
          throw Error(msg);
        }
        continue;
      }
      double fac =
          err > 0.0 ? std::min(kFacMax, std::max(kFacMin, kSafety * std::pow(err, -0.2))) : kFacMax;
      if (after_rejection) fac = std::min(fac, 1.0);
      after_rejection = false;
      h_next = h * fac;
      // A step shortened to land on t_end says nothing against the longer one planned.
      if (last && fac >= 1.0) h_next = std::max(h_next, h_);
    }
    ++accepted_;

    const double t1 = last ? t_end : t0 + h;
    if (located && fired_at_end(forces, sub, st, t1, ranges)) {
      int who = -1;
      const double theta = locate(forces, sub, st, h, who);
      const double tau = polish(forces, sub, st, h, theta, who, ranges);
      commit(st, tau == h ? t1 : t0 + tau, pad, ranges);
      transit(forces, sub, st, who, ranges);
      first_stage(forces, sub, st, ranges);  // the right-hand side jumps here: restart
    } else {
      commit(st, t1, pad, ranges);
    }
    h_ = h_next;
  }
  t_resume_ = st.t;
}

std::vector<double> Adaptive::save() const {
  return {h_, t_resume_, last_stick_time_};
}

void Adaptive::restore(std::span<const double> s) {
  if (s.size() != 3) throw Error("adaptive: the saved stepper state does not fit this scheme");
  h_ = s[0];
  t_resume_ = s[1];
  last_stick_time_ = s[2];
}

}  // namespace bkq
