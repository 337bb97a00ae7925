// The velocity-weakening family of Ferre 2018 eq. 3.5 and Carlson et al. 1991 eq. 2.9:
// |phi(y)| = kinetic0 / (1 + |y| inv_scale), static threshold F0 m_u. The theta scheme
// solves its implicit step in closed form for this family (integrate/theta.cpp).
#pragma once

#include <cmath>

#include "core/error.hpp"
#include "model/parameters.hpp"

namespace bkq::law {

struct Rational {
  double kinetic0 = 1;   // limit of |phi| as y -> 0 while sliding
  double inv_scale = 0;  // 1/(velocity scale of the weakening); 0 = flat law
  double threshold = 1;  // static threshold on the spring force, F0 m_u

  // |phi| at |y| = abs_y.
  double at(double abs_y) const { return kinetic0 / std::fma(abs_y, inv_scale, 1.0); }

  // F0 (1-s)/(1 + |y|/((1-s) v_c)): Ferre 2018 eq. 3.5, Carlson et al. 1991 eq. 2.9.
  static Rational weakening(const ModelParams& p) {
    return Rational{p.F0 * (1.0 - p.sigma),
                    std::isfinite(p.v_c) ? 1.0 / ((1.0 - p.sigma) * p.v_c) : 0.0, p.threshold()};
  }
  // The loader puts the failing block exactly at the threshold; without a drop from static
  // to kinetic friction the net force there is zero and the block never moves (the v -> 0
  // limit is singular, which is why Carlson et al. 1991 introduced sigma).
  static void require_drop(const ModelParams& p) {
    if (p.sigma <= 0)
      throw Error(
          "friction.sigma: 0 leaves no drop from static to kinetic friction, so event-driven "
          "runs never start an event; event-driven mode needs friction.sigma in (0, 1)");
  }
};

}  // namespace bkq::law
