// Dormand & Prince 1980, RK5(4)7FM: nodes, stages, 5th-order weights (= the last stage row,
// FSAL) and e = b5 - b4 (the error estimate's weights). Shared by the cycle integrator
// (engine/rsf_cycle.hpp) and the active-block one (engine/rsf_active.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bkq::dopri {

constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                 a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784,
                 b6 = 11.0 / 84;
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                 e6 = 22.0 / 525, e7 = -1.0 / 40;

// One step's stages from (t, y), k[0] = y' there (FSAL): k[1]..k[5], the 5th-order solution
// into ytmp and its derivative into k[6] (the next step's k[0]), and the embedded error
// estimate h sum e_i k_i into err. rhs(t, y, dy) on raw arrays of y's size. Vec: a
// std::vector<double>, or a std::array<double, n> (one slider's state: loops of fixed length).
template <class Vec, class Rhs>
void stages(double t, double h, const Vec& y, Vec (&k)[7], Vec& ytmp, Vec& err, Rhs&& rhs) {
  const std::size_t size = y.size();
  const auto stage = [&](Vec& out, double c, auto combine) {
    for (std::size_t i = 0; i < size; ++i) ytmp[i] = y[i] + h * combine(i);
    rhs(t + c * h, ytmp.data(), out.data());
  };
  auto &k1 = k[0], &k2 = k[1], &k3 = k[2], &k4 = k[3], &k5 = k[4], &k6 = k[5], &k7 = k[6];
  stage(k2, c2, [&](std::size_t i) { return a21 * k1[i]; });
  stage(k3, c3, [&](std::size_t i) { return a31 * k1[i] + a32 * k2[i]; });
  stage(k4, c4, [&](std::size_t i) { return a41 * k1[i] + a42 * k2[i] + a43 * k3[i]; });
  stage(k5, c5,
        [&](std::size_t i) { return a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]; });
  stage(k6, 1.0, [&](std::size_t i) {
    return a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i];
  });
  stage(k7, 1.0, [&](std::size_t i) {
    return b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i];
  });
  for (std::size_t i = 0; i < size; ++i)
    err[i] = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
}

// The running maximum of an error norm's terms, where a NaN (a stage past the range of exp)
// wins and sticks, so that the step is rejected (std::max would drop it and accept the step).
inline double worse(double e, double q) {
  return std::isnan(e) || q <= e ? e : q;
}

// The step-size control: the factor 0.9 err^(-1/5) on h, within [0.2, 5] after an accepted
// step (at most 1 if a rejection came before it), within [0.2, 1] after a rejection.
inline double grow_factor(double err, bool accepted, bool rejected_before) {
  const double grow = err > 0 ? 0.9 * std::pow(err, -0.2) : 5.0;
  if (!accepted) return std::max(0.2, std::min(1.0, grow));
  return std::min(rejected_before ? 1.0 : 5.0, std::max(0.2, grow));
}

// An adaptive integration's state: the time and the next step size, the state y and its
// derivative (FSAL) now and before the last accepted step, the stages and the counters; step()
// is the rate-and-state integrators' step (the cycle integrator's over the whole grid, the
// active-block one's over its slots, a slider's alone: Vec = std::array<double, 3>).
template <class Vec = std::vector<double>>
struct Adaptive {
  double t = 0, t_prev = 0, h = 0;
  Vec y, dy, y_prev, dy_prev, k[7], ytmp, err;
  std::int64_t accepted = 0, rejected = 0;

  // One accepted step of at most t_max - t (clipped there), retried with smaller steps while
  // norm() of the embedded error (in err, the proposal in ytmp) exceeds 1; returns the step
  // taken. A clipped step keeps h unless h was itself too large. rhs(t, y, dy) on raw arrays;
  // fail(t) is called (and must throw) when the step no longer moves the clock.
  template <class Rhs, class Norm, class Fail>
  double step(double t_max, Rhs&& rhs, Norm&& norm, Fail&& fail) {
    const double hh = propose(t_max, rhs, norm, fail);
    accept();
    return hh;
  }

  // step() in two halves: propose() finds the step (ytmp and k[6] hold its end, proposed_t its
  // time) and changes nothing but h and the counters of rejections; accept() takes it. A
  // proposal not taken is dropped by changing y or proposing again.
  template <class Rhs, class Norm, class Fail>
  double propose(double t_max, Rhs&& rhs, Norm&& norm, Fail&& fail) {
    k[0] = dy;  // FSAL: the last stage of the previous step
    bool rejected_before = false;
    while (true) {
      const bool clipped = t + h >= t_max;
      const double hh = clipped ? t_max - t : h;
      if (!(hh > 0) || t + hh == t) fail(t);
      stages(t, hh, y, k, ytmp, err, rhs);
      double e = norm();
      if (!std::isfinite(e)) e = 1e10;  // a stage left the range of exp: reject, shrink
      if (e <= 1) {
        proposed_t = clipped ? t_max : t + hh;
        const double next = hh * grow_factor(e, true, rejected_before);
        proposed_h = !clipped || next < h ? next : h;
        return hh;
      }
      ++rejected;
      rejected_before = true;
      h = hh * grow_factor(e, false, rejected_before);
    }
  }
  void accept() {
    t_prev = t;
    y_prev.swap(y);
    dy_prev.swap(dy);
    y.swap(ytmp);
    dy = k[6];
    t = proposed_t;
    h = proposed_h;
    ++accepted;
  }
  double proposed_t = 0, proposed_h = 0;
};

}  // namespace bkq::dopri
