// DOPRI5's continuous extension (Shampine 1986, as in Hairer's CONTD5; Hairer, Norsett & Wanner
// 1993, II.6): fourth order between a step's ends, from the step's seven stage rates. Shared by
// the adaptive chain stepper (integrate/adaptive.hpp) and the rate-and-state slider integrated
// alone (engine/rsf_alone.hpp).
#pragma once

namespace bkq::dopri {

// The weights d_l of the extension's fifth coefficient, sum_l d_l k_l.
inline constexpr double kDense[7] = {-12715105075.0 / 11282082432,  0.0,
                                     87487479700.0 / 32700410799,   -10690763975.0 / 1880347072,
                                     701980252875.0 / 199316789632, -1453857185.0 / 822651844,
                                     69997945.0 / 29380423};

// One component at t0 + theta h: ends y0, y1, the first and last stage rates f0 = k_1 and
// f1 = k_7 (FSAL: the rate at y1), and c5 = sum_l kDense[l] k_l.
inline double dense(double y0, double y1, double f0, double f1, double c5, double h, double theta) {
  const double dy = y1 - y0;
  const double bspl = h * f0 - dy;
  const double c4 = dy - h * f1 - bspl;
  const double theta1 = 1.0 - theta;
  return y0 + theta * (dy + theta1 * (bspl + theta * (c4 + theta1 * h * c5)));
}

}  // namespace bkq::dopri
