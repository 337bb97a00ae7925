// One rate-and-state slider between events in closed form; see rsf_nucleation.hpp.
#include "model/rsf_nucleation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bkq::rsf {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr double kSteadySlack = 1e-9;  // ln(V theta/D_c) taken as steady state

// A slower search for what the fast paths below cannot take (non-finite intermediates at
// extreme arguments): bracketed by doubling, then Newton kept inside the bracket.
double bracketed_root(double f0, double alpha, double beta, double theta0) {
  const auto f = [&](double t) { return f0 + alpha * t + beta * std::log1p(t / theta0); };
  double lo = beta < 0 ? std::max(0.0, -beta / alpha - theta0) : 0.0;
  double hi = lo + std::max(theta0, 1 / alpha);
  for (int i = 0; f(hi) <= 0; ++i) {
    if (i > 2000 || !std::isfinite(hi)) return kNever;
    lo = hi;
    hi *= 2;
  }
  double t = hi;
  for (int i = 0; i < 200; ++i) {
    const double ft = f(t);
    (ft > 0 ? hi : lo) = t;
    double next = t - ft / (alpha + beta / (theta0 + t));
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == t || hi - lo <= 1e-15 * hi) return next;
    t = next;
  }
  return t;
}

// The roots' relative error: the old search's bracket width. Halley's method converges
// cubically, e' = C e^3 with C = (f'')^2/(4 (f')^2) - f'''/(6 f') near the root, so once the
// step taken is d (and |f f''| <= f'^2, where that estimate holds) the error left is at most
// about (f''^2/(4 f'^2) + |f'''/(6 f')|) |d|^3 (the terms' sizes: their difference can vanish
// away from the root): the iteration stops there, a log short of the step that would only
// confirm it.
constexpr double kRootTolerance = 1e-15;

// Halley's step from x for g(x) = 0 with g' = d1 > 0, g'' = d2, g''' = d3, kept inside the
// bracket (lo, hi) (else Newton's step, else the midpoint), and whether it is the last.
struct RootStep {
  double next;
  bool done;
};
RootStep root_step(double x, double g, double d1, double d2, double d3, double& lo, double& hi,
                   double tolerance) {
  (g < 0 ? lo : hi) = x;
  const double step = 2 * g * d1 / (2 * d1 * d1 - g * d2);
  double next = x - step;
  if (!(next > lo && next < hi)) {
    next = x - g / d1;
    if (!(next > lo && next < hi)) next = std::isinf(hi) ? 2 * lo : 0.5 * (lo + hi);
    return {next, next == x};
  }
  const double c = d2 * d2 / (4 * d1 * d1) + std::fabs(d3 / (6 * d1));
  return {next, next == x || (std::fabs(g * d2) <= d1 * d1 &&
                              c * step * step * std::fabs(step) <= tolerance)};
}

// beta < 0: f is convex in t, its minimum at t_min = -beta/alpha - theta0, and the root lies
// right of both t_min and F/alpha (F = -f0: there alpha t = F and the log term is negative).
// From t0 = max(F/alpha, t_min) the fixed point t1 = (F - beta ln(1 + t0/theta0))/alpha is a
// lower bound too, strictly right of t_min (as F > 0), and the log it needs is f(t0)'s; Halley
// starts from t0 where f'(t0) >= alpha/2 (the linear term dominates), else from t1, so that
// f' > 0 at every iterate (all lie right of the start).
double convex_root(double f0, double alpha, double beta, double theta0) {
  const double big_f = -f0;
  const double t0 = std::max(big_f / alpha, -beta / alpha - theta0);
  double l = std::log1p(t0 / theta0), t = t0;
  bool known = alpha + beta / (theta0 + t0) >= 0.5 * alpha;  // l is ln(1 + t/theta0)
  if (!known) t = (big_f - beta * l) / alpha;
  double lo = t0, hi = kNever;
  for (int i = 0; i < 100; ++i) {
    if (!known) l = std::log1p(t / theta0);
    known = false;
    const double y = theta0 + t, f = alpha * t + beta * l - big_f;
    const double d1 = alpha + beta / y, d2 = -beta / (y * y), d3 = 2 * beta / (y * y * y);
    if (!std::isfinite(f) || !(d1 > 0)) break;
    const RootStep r = root_step(t, f, d1, d2, d3, lo, hi, kRootTolerance * t);
    if (r.done) return r.next;
    t = r.next;
  }
  return bracketed_root(f0, alpha, beta, theta0);
}

// beta > 0: f is concave in t but convex and rising in s = ln(1 + t/theta0),
// g(s) = f0 + alpha theta0 (e^s - 1) + beta s, whose root lies above 0 and below both
// ln(1 + F/(alpha theta0)) (the log term left out) and F/beta (the linear one): Halley from the
// smaller, t = theta0 (e^s - 1), whose relative error is the error in s over 1 - e^{-s}.
double concave_root(double f0, double alpha, double beta, double theta0) {
  const double big_f = -f0, a = alpha * theta0;
  double s = std::min(std::log1p(big_f / a), big_f / beta), lo = 0, hi = kNever;
  for (int i = 0; i < 100; ++i) {
    const double e = std::expm1(s);
    const double g = a * e + beta * s - big_f, d2 = a * (e + 1), d1 = d2 + beta;
    if (!std::isfinite(g) || !std::isfinite(d1)) break;
    const RootStep r = root_step(s, g, d1, d2, d2, lo, hi, -kRootTolerance * std::expm1(-s));
    if (r.done) {
      const double t = theta0 * std::expm1(r.next);
      if (std::isfinite(t)) return t;
      break;
    }
    s = r.next;
  }
  return bracketed_root(f0, alpha, beta, theta0);
}

}  // namespace

double first_root(double f0, double alpha, double beta, double theta0) {
  if (f0 >= 0) return 0;
  if (alpha <= 0) return beta > 0 ? theta0 * std::expm1(-f0 / beta) : kNever;
  if (beta == 0) return -f0 / alpha;
  return beta < 0 ? convex_root(f0, alpha, beta, theta0) : concave_root(f0, alpha, beta, theta0);
}

namespace {

double alpha_of(const Slider& s) {
  return s.stressing_rate / (s.a * s.sigma);
}

// The locked phase dt on (dt at most its time to Omega = 1).
SliderState locked_after(const Slider& s, SliderState x, double dt) {
  const double grow = std::log1p(dt * std::exp(-x.ln_theta));
  return {x.ln_v + alpha_of(s) * dt - (s.b_rsf / s.a) * grow, x.ln_theta + grow};
}

// Seconds from a locked state to Omega = 1.
double time_to_nucleation(const Slider& s, SliderState x) {
  return first_root(ln_omega(s, x), alpha_of(s), 1 - s.b_rsf / s.a, std::exp(x.ln_theta));
}

// The nucleating phase dt on.
SliderState nucleating_after(const Slider& s, SliderState x, double dt) {
  const double alpha = alpha_of(s), c = s.h() / (s.a * alpha), v0 = std::exp(x.ln_v);
  const double u = std::exp(-x.ln_v - alpha * dt) + c * std::expm1(-alpha * dt);
  if (!(u > 0)) return {kNever, -kNever};
  // ln[1 - c V0 (e^{alpha dt} - 1)] = ln(u V0) + alpha dt; slip = -that/(alpha c).
  double slip;
  if (c == 0)
    slip = v0 * std::expm1(alpha * dt) / alpha;
  else if (alpha * dt < 1)
    slip = -std::log1p(-c * v0 * std::expm1(alpha * dt)) / (alpha * c);
  else
    slip = -(std::log(u) + x.ln_v + alpha * dt) / (alpha * c);
  return {-std::log(u), x.ln_theta - slip / s.dc};
}

double nucleating_time(const Slider& s, SliderState x, double ln_v_target) {
  if (x.ln_v >= ln_v_target) return 0;
  const double alpha = alpha_of(s), c = s.h() / (s.a * alpha);
  const double u0 = std::exp(-x.ln_v), ut = std::exp(-ln_v_target);
  if (!(ut + c > 0)) return kNever;  // H < 0: the steady creep stays below the target
  return std::log1p((u0 - ut) / (ut + c)) / alpha;
}

// ln(e^x - 1) for x > 0, without overflow.
double log_expm1(double x) {
  return x > 30 ? x + std::log(-std::expm1(-x)) : std::log(std::expm1(x));
}

// ln(1 + e^l), without overflow.
double log1p_exp(double l) {
  return l > 30 ? l + std::log1p(std::exp(-l)) : std::log1p(std::exp(l));
}

// The nucleating phase's slip over dt: -ln(1 - y)/(alpha c), y = c V0 (e^{alpha dt} - 1),
// written as V0 (e^{alpha dt} - 1)/alpha times -ln(1 - y)/y (-> 1 as y -> 0, so H -> 0 is
// smooth), and in logarithms where y < -1 (H < 0, long creep: e^{alpha dt} may overflow).
double nucleating_slip(const Slider& s, SliderState x, double dt) {
  if (!(dt > 0)) return 0;
  const double alpha = alpha_of(s), c = s.h() / (s.a * alpha);
  const double ln_e = log_expm1(alpha * dt);                   // ln(e^{alpha dt} - 1)
  const double ln_y = std::log(std::fabs(c)) + x.ln_v + ln_e;  // ln |y|
  if (c < 0 && ln_y > 0) return log1p_exp(ln_y) / (alpha * -c);
  const double y = c == 0 ? 0.0 : std::copysign(std::exp(ln_y), c);
  if (!(y < 1)) return kNever;  // past the instability
  const double ratio = std::fabs(y) < 1e-8 ? 1 + 0.5 * y : -std::log1p(-y) / y;
  return std::exp(x.ln_v + ln_e) / alpha * ratio;
}

// The time in the nucleating phase to the slip `amount`: from 1 - y = e^{-alpha c amount},
// e^{alpha t} - 1 = (alpha amount/V0) r, r = (1 - e^{-z})/z with z = alpha c amount (r -> 1
// as H -> 0), in logarithms so that neither e^{alpha t} nor r overflows.
double nucleating_slip_time(const Slider& s, SliderState x, double amount) {
  const double alpha = alpha_of(s), c = s.h() / (s.a * alpha), z = alpha * c * amount;
  double ln_r;
  if (std::fabs(z) < 1e-8)
    ln_r = -0.5 * z;
  else if (z > 0)
    ln_r = std::log(-std::expm1(-z) / z);
  else
    ln_r = log_expm1(-z) - std::log(-z);
  const double ln_e = std::log(alpha * amount) - x.ln_v + ln_r;  // ln(e^{alpha t} - 1)
  return log1p_exp(ln_e) / alpha;
}

// The steady-state phase of a velocity-strengthening block (a > b): theta = D_c/V, so
// (a - b) sigma d ln V/dt = tau_dot - k_eff V, d ln V/dt = beta (1 - V/V_inf) with
// beta = tau_dot/((a - b) sigma) and V_inf = tau_dot/k_eff: the logistic
// V(t) = V_inf/(1 + (V_inf/V0 - 1) e^{-beta t}), slip (V_inf/beta) ln[1 + (V0/V_inf)(e^{beta t} -
// 1)].
double beta_of(const Slider& s) {
  return s.stressing_rate / ((s.a - s.b_rsf) * s.sigma);
}

double ln_v_inf(const Slider& s) {
  return std::log(s.stressing_rate / s.k_eff);
}

SliderState steady_after(const Slider& s, SliderState x, double dt) {
  const double lvi = ln_v_inf(s), d = lvi - x.ln_v, bt = beta_of(s) * dt;
  // ln(1 + A e^{-beta t}), A = V_inf/V0 - 1 = e^d - 1, in logarithms where A > 0.
  double ln_den;
  if (d > 0)
    ln_den = log1p_exp(log_expm1(d) - bt);
  else
    ln_den = std::log1p(std::expm1(d) * std::exp(-bt));
  const double ln_v = lvi - ln_den;
  return {ln_v, std::log(s.dc) - ln_v};
}

double steady_time(const Slider& s, SliderState x, double ln_v_target) {
  if (x.ln_v >= ln_v_target) return 0;
  const double lvi = ln_v_inf(s);
  if (!(ln_v_target < lvi)) return kNever;  // the creep tends to V_inf and stays below it
  return (log_expm1(lvi - x.ln_v) - log_expm1(lvi - ln_v_target)) / beta_of(s);
}

double steady_slip(const Slider& s, SliderState x, double dt) {
  if (!(dt > 0)) return 0;
  const double beta = beta_of(s), lvi = ln_v_inf(s);
  return std::exp(lvi) / beta * log1p_exp(x.ln_v - lvi + log_expm1(beta * dt));
}

// From e^{beta t} - 1 = (V_inf/V0)(e^{beta amount/V_inf} - 1).
double steady_slip_time(const Slider& s, SliderState x, double amount) {
  const double beta = beta_of(s), lvi = ln_v_inf(s);
  return log1p_exp(lvi - x.ln_v + log_expm1(beta * amount * std::exp(-lvi))) / beta;
}

// The phase after the locked one: steady state (a > b) or nucleating (a <= b).
SliderState sliding_after(const Slider& s, SliderState x, double dt) {
  return s.strengthening() ? steady_after(s, x, dt) : nucleating_after(s, x, dt);
}
double sliding_time(const Slider& s, SliderState x, double ln_v_target) {
  return s.strengthening() ? steady_time(s, x, ln_v_target) : nucleating_time(s, x, ln_v_target);
}
double sliding_slip(const Slider& s, SliderState x, double dt) {
  return s.strengthening() ? steady_slip(s, x, dt) : nucleating_slip(s, x, dt);
}
double sliding_slip_time(const Slider& s, SliderState x, double amount) {
  return s.strengthening() ? steady_slip_time(s, x, amount) : nucleating_slip_time(s, x, amount);
}

}  // namespace

double ln_omega(const Slider& s, const SliderState& x) {
  return x.ln_v + x.ln_theta - std::log(s.dc);
}

bool locked(const Slider& s, const SliderState& x) {
  // A steady-state block's theta = D_c/V holds to rounding: it stays steady.
  return ln_omega(s, x) < (s.strengthening() ? -kSteadySlack : 0.0);
}

// While locked, ln(V theta/D_c) = f(t) of first_root rises through 0 once (f(0) < 0, f monotone
// or convex), so the locked form dt on says itself whether dt lies before the time to
// nucleation: evolve and slip look for that time only where it does not.
SliderState evolve(const Slider& s, SliderState x, double dt) {
  if (locked(s, x)) {
    const SliderState y = locked_after(s, x, dt);
    if (!(ln_omega(s, y) > 0)) return y;
    const double t_nuc = time_to_nucleation(s, x);
    if (dt <= t_nuc) return y;
    x = locked_after(s, x, t_nuc);
    dt -= t_nuc;
  }
  return sliding_after(s, x, dt);
}

namespace {

// time_to_speed from a locked state, given its time to nucleation.
// While locked ln V rises at most as fast as alpha t (b >= 0), so where that reaches the target
// only after nucleation the search for the locked phase's own time is skipped (same result).
double locked_time_to_speed(const Slider& s, SliderState x, double ln_v_target, double t_nuc) {
  const double alpha = alpha_of(s);
  if (!(s.b_rsf >= 0 && (ln_v_target - x.ln_v) / alpha > t_nuc)) {
    const double theta0 = std::exp(x.ln_theta);
    const double t_v = first_root(x.ln_v - ln_v_target, alpha, -s.b_rsf / s.a, theta0);
    if (t_v <= t_nuc) return t_v;
  }
  if (t_nuc == kNever) return kNever;
  return t_nuc + sliding_time(s, locked_after(s, x, t_nuc), ln_v_target);
}

// time_to_slip from a locked state, given its time to nucleation.
double locked_time_to_slip(const Slider& s, SliderState x, double amount, double t_nuc) {
  if (t_nuc == kNever) return kNever;
  return t_nuc + sliding_slip_time(s, locked_after(s, x, t_nuc), amount);
}

}  // namespace

double time_to_speed(const Slider& s, SliderState x, double ln_v_target) {
  if (x.ln_v >= ln_v_target) return 0;
  if (!locked(s, x)) return sliding_time(s, x, ln_v_target);
  return locked_time_to_speed(s, x, ln_v_target, time_to_nucleation(s, x));
}

double slip(const Slider& s, SliderState x, double dt) {
  if (locked(s, x)) {
    if (!(ln_omega(s, locked_after(s, x, dt)) > 0)) return 0;
    const double t_nuc = time_to_nucleation(s, x);
    if (!(dt > t_nuc)) return 0;
    x = locked_after(s, x, t_nuc);
    dt -= t_nuc;
  }
  return sliding_slip(s, x, dt);
}

double time_to_slip(const Slider& s, SliderState x, double amount) {
  if (!(amount > 0)) return 0;
  if (!locked(s, x)) return sliding_slip_time(s, x, amount);
  return locked_time_to_slip(s, x, amount, time_to_nucleation(s, x));
}

Clocks clocks(const Slider& s, SliderState x, double ln_v_target, double amount) {
  if (!locked(s, x) || x.ln_v >= ln_v_target || !(amount > 0))
    return {time_to_speed(s, x, ln_v_target), time_to_slip(s, x, amount)};
  const double t_nuc = time_to_nucleation(s, x);
  return {locked_time_to_speed(s, x, ln_v_target, t_nuc), locked_time_to_slip(s, x, amount, t_nuc)};
}

SliderState onto_steady_state(const Slider& s, SliderState x) {
  const double lo = ln_omega(s, x);
  if (!s.strengthening() || !(lo > 0)) return x;
  const double ln_v = x.ln_v + s.b_rsf / (s.a - s.b_rsf) * lo;
  return {ln_v, std::log(s.dc) - ln_v};
}

SliderState stress_step(const Slider& s, SliderState x, double dtau) {
  if (s.strengthening() && !locked(s, x)) {
    const double ln_v = x.ln_v + dtau / ((s.a - s.b_rsf) * s.sigma);
    return {ln_v, std::log(s.dc) - ln_v};
  }
  return {x.ln_v + dtau / (s.a * s.sigma), x.ln_theta};
}

double time_to_omega(const Slider& s, SliderState x, double ln_target) {
  const double ln_omega0 = ln_omega(s, x);
  if (!locked(s, x) || ln_omega0 >= ln_target) return 0;
  return first_root(ln_omega0 - ln_target, alpha_of(s), 1 - s.b_rsf / s.a, std::exp(x.ln_theta));
}

NextClock next_clock(const Slider& s, SliderState x, double ln_v_target, double amount,
                     double ln_omega_target) {
  const bool omega = ln_omega_target < 0 && locked(s, x);
  if (omega && x.ln_v < ln_v_target && amount > 0) {
    const double t_omega = time_to_omega(s, x, ln_omega_target);
    if (t_omega < kNever) {
      // The speed only while locked can come first (after nucleation it is later than
      // t_omega), and only where ln V, rising at most alpha t, can reach it by t_omega.
      const double alpha = alpha_of(s);
      if (s.b_rsf >= 0 && (ln_v_target - x.ln_v) / alpha > t_omega) return {t_omega, false};
      const double t_v =
          first_root(x.ln_v - ln_v_target, alpha, -s.b_rsf / s.a, std::exp(x.ln_theta));
      return {std::min(t_omega, t_v), false};
    }
  }
  double to_speed, to_slip = kNever;
  if (std::isinf(amount)) {
    to_speed = time_to_speed(s, x, ln_v_target);
  } else {
    const Clocks c = clocks(s, x, ln_v_target, amount);
    to_speed = c.to_speed;
    to_slip = c.to_slip;
  }
  if (omega) to_speed = std::min(to_speed, time_to_omega(s, x, ln_omega_target));
  return {std::min(to_speed, to_slip), to_slip < to_speed};
}

}  // namespace bkq::rsf
