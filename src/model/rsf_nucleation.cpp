// One rate-and-state slider between events in closed form; see rsf_nucleation.hpp.
#include "model/rsf_nucleation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bkq::rsf {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr double kSteadySlack = 1e-9;  // ln(V theta/D_c) taken as steady state

// The first t > 0 where f(t) = f0 + alpha t + beta ln(1 + t/theta0) reaches 0, f0 < 0,
// alpha >= 0: f is monotone (beta >= 0) or convex with its minimum at -beta/alpha - theta0,
// so the root lies on the rising branch. Bracketed, then Newton kept inside the bracket.
double first_root(double f0, double alpha, double beta, double theta0) {
  if (f0 >= 0) return 0;
  const auto f = [&](double t) { return f0 + alpha * t + beta * std::log1p(t / theta0); };
  if (alpha <= 0) return beta > 0 ? theta0 * std::expm1(-f0 / beta) : kNever;
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

SliderState evolve(const Slider& s, SliderState x, double dt) {
  if (locked(s, x)) {
    const double t_nuc = time_to_nucleation(s, x);
    if (dt <= t_nuc) return locked_after(s, x, dt);
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

}  // namespace bkq::rsf
