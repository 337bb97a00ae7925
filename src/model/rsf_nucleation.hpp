// One rate-and-state slider between events, in closed form (Dieterich, J. Geophys. Res. 99,
// 2601, 1994; Dieterich, J. Geophys. Res. 100, 1995): what the event-driven engine
// (engine/rsf_loader.hpp) uses instead of time steps. Log form of the law, aging law, quasi-
// static balance (radiation damping and inertia left out: the engine hands a block over to the
// full integration below speeds where eta V << a sigma), constant stressing rate tau_dot:
//
//   a sigma d ln V/dt = tau_dot - k_eff V - b sigma d ln theta/dt
//
// with k_eff the stiffness a block's own slip unloads it by (loader plus coupling springs:
// the neighbours' creep is left out, as in RSQSim). Two phases, by Omega = V theta/D_c:
//
//   locked (Omega < 1)       d theta/dt = 1 (healing; the aging law with V theta/D_c << 1) and
//                            k_eff V left out of the balance (V << V_pl while locked), so
//                            ln V = ln V0 + tau_dot t/(a sigma) - (b/a) ln(1 + t/theta0),
//                            theta = theta0 + t;
//   sliding (Omega >= 1), by the sign of a - b:
//     nucleating (a <= b)    d theta/dt = -V theta/D_c (the aging law with V theta/D_c >> 1),
//                            which with H = b/D_c - k_eff/sigma gives, u = 1/V,
//                            u(t) = (u0 + c) exp(-alpha t) - c, alpha = tau_dot/(a sigma),
//                            c = H/(a alpha), slip = -(1/(alpha c)) ln[1 - c V0 (e^{alpha t} - 1)],
//                            ln theta = ln theta0 - slip/D_c;
//     steady state (a > b)   theta = D_c/V (the aging law's fixed point, which a velocity-
//                            strengthening block is drawn to), so (a - b) sigma d ln V/dt =
//                            tau_dot - k_eff V: the logistic V(t) = V_inf/(1 + (V_inf/V0 - 1)
//                            e^{-beta t}), V_inf = tau_dot/k_eff, beta = tau_dot/((a - b) sigma),
//                            slip (V_inf/beta) ln[1 + (V0/V_inf)(e^{beta t} - 1)]. A velocity-
//                            strengthening block with Omega > 1 is taken at steady state at its V.
//
// A block locked goes over to sliding when Omega reaches 1, and stays there until the engine
// takes it over. With H > 0 a nucleating block's slip rate runs away at t_inst =
// ln(1 + 1/(c V0))/alpha (Dieterich 1994, eq. 9's form); with H <= 0 it tends to the creep
// V = tau_dot/(sigma |H|), which is not the aging law's (that is V_inf: the nucleation form drops
// the 1 of d theta/dt = 1 - Omega, wrong near steady state; hence the steady-state phase for
// velocity-strengthening blocks, and velocity-weakening blocks near Omega = 1 left to the engine's
// integrator, engine/rsf_loader.hpp).
// A shear-stress step dtau multiplies V by exp(dtau/(a sigma)) at constant theta (the law's
// direct effect; theta changes only with a normal-stress step, Linker & Dieterich 1992); in the
// steady-state phase it moves V along steady state, by exp(dtau/((a - b) sigma)), theta = D_c/V
// (the evolution over D_c of slip that follows the direct effect, taken at once).
//
// The slip of the nucleating phase follows from the balance itself: with d ln theta/dt = -V/D_c
// it reads d ln V/dt = alpha + (H/a) V, so V = (a/H)(d ln V/dt - alpha) and
//   slip(t) = (a/H) [ln(V(t)/V0) - alpha t] = -ln[1 - c V0 (e^{alpha t} - 1)]/(alpha c),
// which tends to V0 (e^{alpha t} - 1)/alpha as H -> 0 and to the creep's
// tau_dot t/(sigma |H|) for H < 0. The locked phase's slip (V << V_pl) is left out: zero.
#pragma once

namespace bkq::rsf {

// One slider's constants.
struct Slider {
  double a = 0.01, b_rsf = 0.015, dc = 1e-5;               // the law's a, b and D_c [m]
  double sigma = 5e6;                                      // normal stress [Pa]
  double stressing_rate = 2e3;                             // tau_dot [Pa/s], > 0
  double k_eff = 2e9;                                      // unloading stiffness [Pa/m]
  double h() const { return b_rsf / dc - k_eff / sigma; }  // H [1/m]
  bool strengthening() const { return a > b_rsf; }         // steady state, not nucleation
};

// The first t > 0 at which f(t) = f0 + alpha t + beta ln(1 + t/theta0) reaches 0 (0 if f0 >= 0,
// +inf if never), theta0 > 0: the locked phase's clocks, ln V or ln(V theta/D_c) reaching a
// target (beta = -b/a or 1 - b/a). To a relative 1e-15: Halley's method from bounds on the
// root, in t where f is convex (beta < 0, the root on its rising branch) and in
// s = ln(1 + t/theta0) where it is concave (beta > 0).
double first_root(double f0, double alpha, double beta, double theta0);

struct SliderState {
  double ln_v = 0, ln_theta = 0;
};

// ln Omega = ln(V theta/D_c), which sets the phase.
double ln_omega(const Slider& s, const SliderState& x);
bool locked(const Slider& s, const SliderState& x);  // Omega = V theta/D_c < 1

// The state dt seconds on (dt >= 0; the slip rate is +inf past the instability).
SliderState evolve(const Slider& s, SliderState x, double dt);
// The first time from now at which V reaches exp(ln_v_target) from below (0 if it is there or
// above already; +inf if never).
double time_to_speed(const Slider& s, SliderState x, double ln_v_target);
// The closed form's slip over the next dt seconds (the sliding phase's only; +inf past the
// instability).
double slip(const Slider& s, SliderState x, double dt);
// The first time from now at which that slip reaches `amount` > 0 (+inf if never).
double time_to_slip(const Slider& s, SliderState x, double amount);
// Where a velocity-strengthening block above steady state (Omega > 1, e.g. handed back by the
// integrator after an event's stress step) enters its steady-state phase: at constant friction
// a ln V + b ln theta (its stress kept), theta evolved to D_c/V, so V_ss = V Omega^{b/(a-b)}.
// Taking it at its V instead (theta jumping to D_c/V) would drop its stress by b sigma ln Omega
// and leave out the afterslip that theta's evolution drives. Any other state is returned as is.
SliderState onto_steady_state(const Slider& s, SliderState x);
// Both: the times to the speed and to the slip, sharing the locked phase's time to nucleation
// (the same numbers as the two calls).
struct Clocks {
  double to_speed = 0, to_slip = 0;
};
Clocks clocks(const Slider& s, SliderState x, double ln_v_target, double amount);
// A shear-stress step dtau [Pa]: V times exp(dtau/(a sigma)), theta kept; in the steady-state
// phase V times exp(dtau/((a - b) sigma)), theta = D_c/V.
SliderState stress_step(const Slider& s, SliderState x, double dtau);
// The first time from now at which a locked block's V theta/D_c reaches exp(ln_target) <= 1
// (0 if it is there or above, or not locked; +inf if never).
double time_to_omega(const Slider& s, SliderState x, double ln_target);

// What the event-driven loader asks of a block each time its state changes, in one pass: the
// earliest of the times to the speed exp(ln_v_target), to the slip `amount` (+inf: none) and,
// while locked, to V theta/D_c = exp(ln_omega_target) (< 0; 0 or above: none), and whether the
// earliest is the slip's (strictly before the others). The same values as the minimum of
// clocks (or time_to_speed, without a slip) and time_to_omega, with the roots that cannot give
// it left out: a locked block reaches Omega = exp(ln_omega_target) < 1 before it nucleates, so
// before it slips and before it reaches the speed in the sliding phase.
struct NextClock {
  double time = 0;
  bool slip = false;
};
NextClock next_clock(const Slider& s, SliderState x, double ln_v_target, double amount,
                     double ln_omega_target);

}  // namespace bkq::rsf
