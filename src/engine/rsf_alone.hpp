// One rate-and-state slider integrated alone: what the event-driven loader (engine/
// rsf_loader.hpp) uses for a velocity-weakening block where neither closed form holds
// (model/rsf_nucleation.hpp: near steady sliding, V theta/D_c between 0.05 and 10, or locked
// above 3 V_pl after an event), instead of carrying it with an event's active blocks at their
// step size.
//
// The slider's own law, as the closed forms have it but with the full aging law: log form,
// quasi-static balance (radiation damping left out: eta V << a sigma at these speeds), constant
// stressing rate tau_dot, its own slip unloading it through k_eff:
//
//   d ln theta/dt = 1/theta - V/D_c,
//   a sigma d ln V/dt = tau_dot - k_eff V - b sigma d ln theta/dt,
//
// integrated by Dormand-Prince 5(4) (engine/dormand_prince.hpp: the cycle integrator's step and
// step-size control) over (slip, ln V, ln theta), the cycle integrator's error norm (slip relative
// to D_c + |slip|, ln V and ln theta absolute). A forecast runs from a state until the first of: ln
// V reaching a target (the hand-over), the slip reaching an amount (the next creep quantum), the
// state entering a closed form's domain at a step's end (nucleating, or locked and slow), or a
// number of steps (the horizon: a stress step from a neighbour would make the steps past it
// wasted). The accepted steps are kept with their dense output, so that the state at any time of
// the forecast costs no right-hand side; crossings are roots of the dense output. Order 5 (4
// between the steps), the error per step within the tolerance; the scheme is explicit (its
// stability limit bounds the step where the block runs away), and the forecast hands the block over
// (Exit::Speed) before that.
#pragma once

#include <array>
#include <vector>

#include "engine/dormand_prince.hpp"
#include "model/rsf_nucleation.hpp"

namespace bkq::rsf {

class AloneSlider {
 public:
  explicit AloneSlider(double tolerance);

  // An accepted step's end, dt from the forecast's start.
  struct Point {
    double dt = 0, y[3] = {0, 0, 0}, dy[3] = {0, 0, 0};  // (slip, ln V, ln theta) and rates
    double dense[3] = {0, 0, 0};  // the step to here: sum d_l k_l (integrate/dopri5_dense.hpp)
  };
  struct Limits {
    double ln_v_target = 0;  // ln V reaching it: Exit::Speed
    double amount = 0;       // slip reaching it (> 0; +inf: none): Exit::Slip
    // Exit::Phase where ln Omega >= hi, or ln Omega < lo with ln V < ln_v_locked (the locked
    // form's domain).
    double ln_omega_lo = 0, ln_omega_hi = 0, ln_v_locked = 0;
    int horizon = 16;  // steps, then Exit::Phase
  };
  enum class Exit { Speed, Slip, Phase };
  struct Forecast {
    double dt = 0;
    Exit exit = Exit::Phase;
    double h_next = 0;  // the step size the control proposes after the path's last step (0: none)
  };
  // From state x (slip 0) until the first exit; the path's points into `path` (the start first).
  // The first step tried is h_first if > 0 (the caller's: the last forecast's h_next, kept in a
  // checkpoint so that a resumed run takes the same steps), else a twentieth of the shorter of
  // D_c/V and theta.
  Forecast forecast(const Slider& s, SliderState x, const Limits& lim, std::vector<Point>& path,
                    double h_first = 0);
  // The state and slip dt along a path (0 <= dt): inside it the steps' dense output (Dormand &
  // Prince's fourth-order interpolant, Hairer, Norsett & Wanner 1993, II.6), past its end steps
  // from there.
  Point at(const Slider& s, const std::vector<Point>& path, double dt);

  double tolerance() const { return tol_; }
  long long steps() const { return steps_; }   // accepted steps, all forecasts
  void set_steps(long long n) { steps_ = n; }  // a checkpoint's

 private:
  void rhs(const Slider& s, const double* y, double* dy) const;
  // One accepted step of the integration in dp_ (at most to dt_max), its end as a path point.
  Point step(const Slider& s, double dt_max);

  double tol_;
  // The integration (its time: dt from the forecast's start).
  dopri::Adaptive<std::array<double, 3>> dp_;
  long long steps_ = 0;
};

}  // namespace bkq::rsf
