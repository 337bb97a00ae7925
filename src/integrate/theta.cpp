// The theta-method with set-valued friction; see theta.hpp for the scheme, the stick rule
// and the contact solver.
#include "integrate/theta.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>

#include "core/error.hpp"

namespace bkq {

namespace {

// The scene's law as the velocity-weakening family (model/laws/rational.hpp) whose
// friction the implicit step solves for in closed form; theta takes no other law.
law::Rational rational_law(const ModelParams& p) {
  return visit_law(p.law, [&]<class L>() -> law::Rational {
    if constexpr (std::is_base_of_v<law::Rational, L>)
      return L(p);
    else
      throw Error(
          "integrator.scheme: theta solves its step in closed form for the laws thesis, "
          "clst91, cl89 and none, not friction.law = " +
          std::string(L::name) + "; use rk2, rk4, verlet or adaptive");
  });
}

// The iteration on the weakening friction has converged when s |a - a_hat| <= this: the
// sliding speeds are then within ~1e-10/s of the solution (a chord step contracts the
// error at least as fast as its update shrinks) and friction within ~1e-10 of itself.
constexpr double kSpeedTolerance = 1e-10;
// Chord steps (reusing a factorisation made with another friction slope) before refactoring.
constexpr int kMaxChordSteps = 3;
// Projected Gauss–Seidel stops when a sweep changes no velocity by more than this relative
// amount (or after kMaxSweeps, keeping the last sweep: every block consistent with its law).
constexpr int kMaxSweeps = 100000;
constexpr double kSweepTolerance = 1e-14;
}  // namespace

std::unique_ptr<Stepper> Theta::fresh(int n_blocks) const {
  auto copy = std::make_unique<Theta>(n_blocks);
  copy->set_theta(theta_);
  copy->set_max_active_set_iterations(max_active_set_);
  return copy;
}

Theta::Theta(int n_blocks) {
  resize(n_blocks);
}

void Theta::resize(int n) {
  n_ = n;
  for (auto* v : {&v0_, &vn_, &impulse0_, &force_pred_, &diag0_, &a_hat_, &z_, &cp_, &q_, &inv_,
                  &gamma_f_, &diag_f_})
    v->assign(n, 0.0);
  start_.assign(n, 0);
  status_.assign(n, 0);
  status_f_.assign(n, 0);
  segments_.clear();
  segments_.reserve(n + 1);
  segments_f_.clear();
  segments_f_.reserve(n + 1);
  factored_ = false;
}

void Theta::build_segments(const ModelParams& p, Ranges ranges) {
  segments_.clear();
  for (const Range& r : ranges)
    if (r.hi > r.lo) segments_.push_back(Segment{r.lo, r.hi - r.lo, false});
  std::sort(segments_.begin(), segments_.end(),
            [](const Segment& a, const Segment& b) { return a.lo < b.lo; });
  // Adjacent ranges are one segment: their blocks are coupled and both move.
  std::size_t k = 0;
  for (std::size_t i = 1; i < segments_.size(); ++i) {
    if (segments_[k].lo + segments_[k].len == segments_[i].lo)
      segments_[k].len += segments_[i].len;
    else
      segments_[++k] = segments_[i];
  }
  if (!segments_.empty()) segments_.resize(k + 1);
  if (p.boundary != Boundary::Periodic || segments_.empty()) return;
  Segment& first = segments_.front();
  Segment& last = segments_.back();
  if (segments_.size() == 1 && first.len == n_) {
    first.cyclic = n_ >= 3;  // a pair is a plain 2x2 system with a doubled spring
  } else if (segments_.size() > 1 && first.lo == 0 && last.lo + last.len == n_) {
    // Blocks n-1 and 0 are neighbours: the runs through the wrap are one segment.
    first = Segment{last.lo, last.len + first.len, false};
    segments_.pop_back();
  }
}

double Theta::neighbour_velocities(int j) const {
  if (!neighbours_) return 0.0;
  if (periodic_) return vn_[j == 0 ? n_ - 1 : j - 1] + vn_[j == n_ - 1 ? 0 : j + 1];
  return (j > 0 ? vn_[j - 1] : 0.0) + (j < n_ - 1 ? vn_[j + 1] : 0.0);
}

void Theta::prepare(const ChainForces& forces, const Substrate& sub, const ChainState& st,
                    double dt) {
  const ModelParams& p = forces.params();
  const Friction& fr = forces.friction();
  const law::Rational law = rational_law(p);
  const SubstrateState s0 = sub.at(st.t), s1 = sub.at(st.t + dt);
  m_ = p.m_u;
  // Implicit weight b = theta h; the explicit one is ratio_ b = (1 - theta) h (both h/2 at
  // theta = 1/2, where ratio_ = 1 multiplies exactly).
  b_ = theta_ * dt;
  ratio_ = (1.0 - theta_) / theta_;
  neighbours_ = p.has_neighbours();
  periodic_ = p.boundary == Boundary::Periodic;
  kc_ = neighbours_ ? p.k_c : 0.0;
  kp_ = p.k_p;
  // Rayleigh damping beta_K K v+ joins the springs' b K v+ (positions w + a v + b v+): the
  // new velocities enter the stiffness terms with weight b + beta_K; alpha_M M joins the
  // dampers. Without it (0) every expression below is the undamped one, bit for bit.
  const bool rayleigh = forces.rayleigh();
  const double alpha = p.rayleigh_alpha;
  bb_ = b_ + p.rayleigh_beta;
  link_ = b_ * bb_ * (periodic_ && n_ == 2 ? 2.0 * kc_ : kc_);
  frictionless_ = law_traits(p.law).frictionless;
  backslip_ = fr.backslip;
  thr_ = fr.threshold;
  k0_ = law.kinetic0;
  s_ = law.inv_scale;
  pad_ = p.pad_moves();
  if (b_ * k0_ * s_ >= 1.0) {
    char msg[300];
    std::snprintf(msg, sizeof msg,
                  "integrator.dt: %g is too large for theta with this velocity-weakening friction: "
                  "the sliding "
                  "speed is unique only for dt < v_c/(theta F0) = %.6g",
                  dt, 1.0 / (theta_ * k0_ * s_));
    throw Error(msg);
  }

  const double* w = st.w.data();
  const double x0 = pad_ ? st.x : 0.0;
  const double a = ratio_ * b_;                         // explicit weight (1 - theta) h
  const double x_pred = pad_ ? st.x + a * st.xd : 0.0;  // x+ without the new velocity's part
  const double anchor0 = s0.s + x0, anchor_pred = s1.s + x_pred;
  const double anchor_rate0 = s0.v + (pad_ ? st.xd : 0.0);
  for_each_block([&](int j) {
    const bool stuck = !frictionless_ && st.mobile[j] == 0.0;
    start_[j] = stuck ? 0 : (backslip_ && st.dir[j] < 0.0 ? -1 : 1);
    v0_[j] = stuck ? 0.0 : st.wd[j];
  });
  double sum_v0 = 0;
  for_each_block([&](int j) {
    const double v = v0_[j];
    // L at the start, and L+ with the new velocities left out (w+ = w + a v here).
    double L = forces.spring_force(w, j, anchor0) - p.c_u * (v - s0.v) + m_ * s0.a;
    double L_pred = forces.spring_force(w, j, anchor_pred) +
                    a * (forces.neighbour_force(v0_.data(), j) - p.k_p * v) + p.c_u * s1.v +
                    m_ * s1.a;
    if (rayleigh) {
      // The damping force at the start, and at the end its part free of the new velocities.
      L += m_ *
           forces.rayleigh_acceleration(forces.spring_force(v0_.data(), j, anchor_rate0), v, s0.v);
      L_pred += (alpha * m_ + p.rayleigh_beta * p.k_p) * s1.v;
    }
    double r = 0;  // friction at the start of the step
    const int d = start_[j];
    if (d == 0) {
      r = std::clamp(-L, -thr_, backslip_ ? thr_ : HUGE_VAL);
    } else {
      r = -m_ * d * law.at(std::max(d * v, 0.0));
    }
    const int nb = !neighbours_ ? 0 : periodic_ ? 2 : (j > 0) + (j < n_ - 1);
    impulse0_[j] = m_ * v + a * (L + r);
    force_pred_[j] = L_pred;
    diag0_[j] = m_ + b_ * (p.c_u + alpha * m_) + b_ * bb_ * (p.k_p + nb * p.k_c);
    status_[j] = static_cast<std::int8_t>(d);
    // Linearise friction about the speed predicted from the start's acceleration.
    a_hat_[j] = d == 0 ? 0.0 : std::max(d * (v + (a + b_) * (L + r) / m_), 0.0);
    vn_[j] = v;
    sum_v0 += v;
  });

  pad_col_ = 0;
  xdn_ = st.xd;
  if (pad_) {
    // m_x (xd+ - xd) = b (X + X+), X the pad force; X+ with the new velocities left out.
    const double X = p.m_x * forces.pad_acceleration(st.x, st.xd, st.sum_w, s0.s, sum_v0, s0.v);
    double X_pred = p.k_p * (st.sum_w + a * sum_v0 - p.n * s1.s - p.n * x_pred) - p.k_p0 * x_pred;
    if (rayleigh) X_pred -= p.rayleigh_beta * p.k_p * p.n * s1.v;
    pad_col_ = b_ * bb_ * kp_;
    pad_diag_ = p.m_x + b_ * (p.c_p + alpha * p.m_x) + b_ * bb_ * (p.n * p.k_p + p.k_p0);
    pad_rhs_ = p.m_x * st.xd + b_ * (ratio_ * X + X_pred);
  }
  // The last factorisation serves this step if the matrix is the same but for friction slopes.
  factored_ = factored_ && segments_ == segments_f_ && link_ == link_f_ && pad_col_ == pad_col_f_ &&
              pad_diag_ == pad_diag_f_;
  for_each_block([&](int j) {
    factored_ = factored_ && diag0_[j] == diag_f_[j] && status_[j] == status_f_[j];
  });
}

Theta::Load Theta::load(int j) const {
  double f = force_pred_[j] + bb_ * kc_ * neighbour_velocities(j);
  if (pad_) f += bb_ * kp_ * xdn_;
  return Load{impulse0_[j] + b_ * f, f};
}

int Theta::decide(int j, Load l) const {
  if (frictionless_) return l.c < 0.0 ? -1 : 1;
  // Sliding in direction e has a speed > 0 iff e c > b m k0; stuck, friction must hold f.
  const double kinetic = b_ * m_ * k0_;
  const bool holds = backslip_ ? std::abs(l.f) <= thr_ : l.f <= thr_;
  const int d = start_[j];
  if (d != 0 && d * l.c > kinetic) return d;  // keeps sliding
  if (holds) return 0;                        // stays stuck, or stops and sticks
  // Friction cannot hold the block: it slides the way it is pulled, if the step's momentum
  // allows a speed that way (when it does not, the pull reversed while the block was
  // stopping: it is left stuck for this step and breaks loose at the next).
  const int e = l.f > 0.0 ? 1 : -1;
  if ((backslip_ || e > 0) && e * l.c > kinetic) return e;
  return 0;
}

double Theta::slide_speed(int j, double c, int d) const {
  const double target = d * c, D = diag0_[j], bmk = b_ * m_ * k0_;
  // The root with friction at its largest, k0, is a lower bound; Newton on the convex,
  // increasing D a + b m k0/(1 + a s) - target then converges from the right.
  double a = std::max((target - bmk) / D, 0.0);
  if (s_ == 0.0) return a;
  for (int it = 0; it < 100; ++it) {
    const double q = 1.0 / (1.0 + a * s_);
    const double da = (D * a + bmk * q - target) / (D - bmk * s_ * q * q);
    a = std::max(a - da, 0.0);
    if (std::abs(da) <= 1e-15 * a) break;
  }
  return a;
}

void Theta::solve_segment(const Segment& g, bool refactor, double& sum_y) {
  // Row of a sliding block: (D - b gamma) v_j - link (v_{j-1} + v_{j+1}) - pad_col xd
  //   = m v + b (L + r) + b (L_pred + rho),
  // with friction linearised as r+ = rho + gamma v about a_hat; a stuck block's row is v_j = 0.
  // Refactoring, three right-hand sides share the Thomas factorisation: rhs (y), the pad
  // column (z) and, for a cyclic segment, the Sherman–Morrison vector u (q). Otherwise
  // only y is solved, with the slope gamma_f the factorisation was made with and the
  // difference, applied to the current iterate, on the right (a chord step).
  const int len = g.len;
  double corner_top = 0, gamma_sm = 1;
  double cp_prev = 0, y_prev = 0, z_prev = 0, q_prev = 0;
  for (int i = 0; i < len; ++i) {
    const int j = block(g, i);
    double diag = 1, rhs = 0, col = 0, off = 0;
    if (status_[j] != 0) {
      const double a = a_hat_[j], d = status_[j];
      const double q = 1.0 / (1.0 + a * s_);
      const double k = k0_ * q, dk = -k0_ * s_ * q * q;
      const double rho = -m_ * d * (k - a * dk), gamma = -m_ * dk;
      rhs = impulse0_[j] + b_ * (force_pred_[j] + rho);
      off = -link_;
      if (refactor) {
        gamma_f_[j] = gamma;
        diag = diag0_[j] - b_ * gamma;
        col = pad_col_;
      } else {
        rhs += b_ * (gamma - gamma_f_[j]) * vn_[j];
      }
    }
    const double lower = i > 0 ? off : 0.0;
    double inv = 0;
    if (refactor) {
      const double upper = i < len - 1 ? off : 0.0;
      double u = 0;
      if (g.cyclic && i == 0) {
        corner_top = off;  // T[0][len-1]
        gamma_sm = -diag;
        diag -= gamma_sm;
        u = gamma_sm;
      }
      if (g.cyclic && i == len - 1) {
        diag -= corner_top * off / gamma_sm;  // off = T[len-1][0]
        u = off;
      }
      inv = inv_[j] = 1.0 / (diag - lower * cp_prev);
      cp_prev = cp_[j] = upper * inv;
      z_prev = z_[j] = (col - lower * z_prev) * inv;
      if (g.cyclic) q_prev = q_[j] = (u - lower * q_prev) * inv;
    } else {
      inv = inv_[j];
    }
    y_prev = vn_[j] = (rhs - lower * y_prev) * inv;
  }
  // Back substitution, carrying the next entry in registers; stuck rows come out exactly 0
  // (zero right-hand side and coupling), except through the cyclic correction.
  const int last = block(g, len - 1);
  double y_next = vn_[last], z_next = z_[last], q_next = q_[last];
  double sy = y_next, sz = z_next;
  for (int i = len - 2; i >= 0; --i) {
    const int j = block(g, i);
    y_next = vn_[j] -= cp_[j] * y_next;
    sy += y_next;
    if (!refactor) continue;
    z_next = z_[j] -= cp_[j] * z_next;
    sz += z_next;
    if (g.cyclic) q_next = q_[j] -= cp_[j] * q_next;
  }
  if (!g.cyclic) {
    sum_y += sy;
    if (refactor) sum_z_ += sz;
    return;
  }
  // Sherman–Morrison: T^-1 b = A^-1 b - (v.A^-1 b)/(1 + v.q) q, with v = (1, 0.., corner/gamma).
  const int first = block(g, 0);
  if (refactor) {
    sm_ratio_ = corner_top / gamma_sm;
    sm_denom_ = 1.0 + q_[first] + sm_ratio_ * q_[last];
    const double fz = (z_[first] + sm_ratio_ * z_[last]) / sm_denom_;
    for (int i = 0; i < len; ++i) z_[block(g, i)] -= fz * q_[block(g, i)];
  }
  const double fy = (vn_[first] + sm_ratio_ * vn_[last]) / sm_denom_;
  for (int i = 0; i < len; ++i) {
    const int j = block(g, i);
    vn_[j] -= fy * q_[j];
    if (status_[j] == 0) {
      vn_[j] = 0.0;  // exactly, whatever the correction rounded to
      if (refactor) z_[j] = 0.0;
    }
    sum_y += vn_[j];
    if (refactor) sum_z_ += z_[j];
  }
}

void Theta::solve_linear(bool refactor) {
  double sum_y = 0;
  if (refactor) sum_z_ = 0;
  for (const Segment& g : segments_) solve_segment(g, refactor, sum_y);
  if (refactor) {
    // Remember what the factorisation was made of, to reuse it while that holds.
    factored_ = true;
    segments_f_ = segments_;
    link_f_ = link_;
    pad_col_f_ = pad_col_;
    pad_diag_f_ = pad_diag_;
    for_each_block([&](int j) {
      diag_f_[j] = diag0_[j];
      status_f_[j] = status_[j];
    });
  }
  if (!pad_) return;
  // Schur complement of the pad's row: pad_diag xd - pad_col sum v = pad_rhs, v = y + z xd.
  xdn_ = (pad_rhs_ + pad_col_ * sum_y) / (pad_diag_ - pad_col_ * sum_z_);
  for_each_block([&](int j) { vn_[j] += z_[j] * xdn_; });
}

bool Theta::solve_active_set() {
  int chord_steps = 0;
  for (int it = 0; it < max_active_set_; ++it) {
    const bool refactor = !factored_ || chord_steps >= kMaxChordSteps;
    solve_linear(refactor);
    chord_steps = refactor ? 0 : chord_steps + 1;
    if (frictionless_) return true;
    bool settled = true;
    for_each_block([&](int j) {
      const Load l = load(j);
      const int state = decide(j, l);
      if (state != status_[j]) {
        settled = false;
        factored_ = false;
        status_[j] = static_cast<std::int8_t>(state);
        a_hat_[j] = state == 0 ? 0.0 : slide_speed(j, l.c, state);
        return;
      }
      if (state == 0) return;
      const double a = state * vn_[j];
      if (!(a > 0.0) || s_ * std::abs(a - a_hat_[j]) > kSpeedTolerance) settled = false;
      a_hat_[j] = a > 0.0 ? a : slide_speed(j, l.c, state);
    });
    if (settled) return true;
  }
  return false;
}

void Theta::solve_gauss_seidel() {
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double change = 0, scale = 0, sum = 0;
    for_each_block([&](int j) {
      const Load l = load(j);
      const int state = decide(j, l);
      const double v = state == 0 ? 0.0 : state * slide_speed(j, l.c, state);
      change = std::max(change, std::abs(v - vn_[j]));
      scale = std::max(scale, std::abs(v));
      status_[j] = static_cast<std::int8_t>(state);
      vn_[j] = v;
      sum += v;
    });
    if (pad_) {
      const double xd = (pad_rhs_ + pad_col_ * sum) / pad_diag_;
      change = std::max(change, std::abs(xd - xdn_));
      scale = std::max(scale, std::abs(xd));
      xdn_ = xd;
    }
    if (change <= kSweepTolerance * scale) return;
  }
}

void Theta::finish(ChainState& st, double dt) {
  double dsum = 0;
  for_each_block([&](int j) {
    const double v = status_[j] == 0 ? 0.0 : vn_[j];
    const double dw = b_ * (ratio_ * v0_[j] + v);
    st.w[j] += dw;
    dsum += dw;
    if (frictionless_) {
      st.mobile[j] = 1.0;
      if (v != 0.0) st.dir[j] = std::copysign(1.0, v);
    } else if (v == 0.0) {
      st.mobile[j] = 0.0;  // a sliding speed that rounded to zero: the block stops here
    } else {
      st.mobile[j] = 1.0;
      st.dir[j] = status_[j];
    }
    st.wd[j] = v;
    v0_[j] = vn_[j] = 0.0;
  });
  if (pad_) {
    st.x += b_ * (ratio_ * st.xd + xdn_);
    st.xd = xdn_;
    st.sum_w += dsum;
  }
  st.t += dt;
}

void Theta::step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                 Ranges ranges) {
  const ModelParams& p = forces.params();
  if (p.n != n_) resize(p.n);
  build_segments(p, ranges);
  prepare(forces, sub, st, dt);
  if (!solve_active_set()) solve_gauss_seidel();
  finish(st, dt);
}

Stepper::TimeStepLimit Theta::time_step_limit(const ModelParams& p) const {
  const law::Rational law = rational_law(p);
  const double slope = law.kinetic0 * law.inv_scale;  // steepest weakening, F0/v_c
  if (slope <= 0) return {HUGE_VAL, "theta is unconditionally stable on the linear part"};
  // Strictly below: step() needs dt * theta * slope < 1.
  return {std::nextafter(1.0 / (theta_ * slope), 0.0),
          "theta: the sliding speed under velocity-weakening friction is unique only for dt < "
          "v_c/(theta F0)"};
}

// Layout: n, factored, the scalars, the segment count and (lo, len, cyclic) of each,
// z, cp, inv, q, gamma_f, diag_f and status_f (n each).
std::vector<double> Theta::save() const {
  std::vector<double> s = {static_cast<double>(n_),
                           factored_ ? 1.0 : 0.0,
                           link_f_,
                           pad_col_f_,
                           pad_diag_f_,
                           sum_z_,
                           sm_ratio_,
                           sm_denom_,
                           static_cast<double>(segments_f_.size())};
  for (const Segment& g : segments_f_)
    s.insert(s.end(),
             {static_cast<double>(g.lo), static_cast<double>(g.len), g.cyclic ? 1.0 : 0.0});
  for (const auto* v : {&z_, &cp_, &inv_, &q_, &gamma_f_, &diag_f_})
    s.insert(s.end(), v->begin(), v->end());
  for (std::int8_t x : status_f_) s.push_back(x);
  return s;
}

void Theta::restore(std::span<const double> s) {
  const auto n = static_cast<std::size_t>(n_);
  const auto bad = [] { throw Error("theta: the saved stepper state does not fit this chain"); };
  if (s.size() < 9 || s[0] != n_) bad();
  const auto segments = static_cast<std::size_t>(s[8]);
  if (s[8] < 0 || s[8] > n_ + 1 || s.size() != 9 + 3 * segments + 7 * n) bad();
  factored_ = s[1] != 0.0;
  link_f_ = s[2];
  pad_col_f_ = s[3];
  pad_diag_f_ = s[4];
  sum_z_ = s[5];
  sm_ratio_ = s[6];
  sm_denom_ = s[7];
  std::size_t k = 9;
  segments_f_.clear();
  for (std::size_t i = 0; i < segments; ++i, k += 3)
    segments_f_.push_back(
        Segment{static_cast<int>(s[k]), static_cast<int>(s[k + 1]), s[k + 2] != 0.0});
  for (auto* v : {&z_, &cp_, &inv_, &q_, &gamma_f_, &diag_f_}) {
    v->assign(s.begin() + static_cast<std::ptrdiff_t>(k),
              s.begin() + static_cast<std::ptrdiff_t>(k + n));
    k += n;
  }
  for (std::size_t j = 0; j < n; ++j) status_f_[j] = static_cast<std::int8_t>(s[k + j]);
}

}  // namespace bkq
