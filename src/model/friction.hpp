// The three friction laws phi(y) of SPEC §1, y the velocity of a block relative to the
// substrate. Sliding friction only: at y = 0 friction is set-valued (whatever holds the
// block, up to the threshold F0), which the engine enforces through stick flags.
//   thesis (eq. 3.5):  F0 (1-s)/(1 + |y|/((1-s) v_c)) sgn y      backslip allowed
//   clst91 (eq. 2.9):  F0 (1-s)/(1 + y/((1-s) v_c)),  y > 0 only  backslip forbidden
//   cl89   (eq. 2.3):  F0 sgn y/(1 + |y|/v_c)                    backslip allowed
//   none:              0 (frictionless; for verification against analytic solutions)
#pragma once

#include <algorithm>
#include <cmath>

#include "model/parameters.hpp"

namespace bkq {

struct Friction {
  double kinetic0 = 1;   // limit of |phi| as y -> 0 while sliding
  double inv_scale = 0;  // 1/(velocity scale of the weakening); 0 = flat law
  double threshold = 1;  // static threshold on the spring force, F0 m_u
  bool backslip = true;  // may a block slide against the substrate (y < 0)?

  explicit Friction(const ModelParams& p)
      : threshold(p.threshold()), backslip(p.law != FrictionLaw::Clst91) {
    if (p.law == FrictionLaw::None) {
      kinetic0 = 0;
      threshold = -1;  // nothing holds a block: it never sticks
    } else if (p.law == FrictionLaw::Cl89) {
      kinetic0 = p.F0;
      inv_scale = std::isfinite(p.v_c) ? 1.0 / p.v_c : 0.0;
    } else {
      kinetic0 = p.F0 * (1.0 - p.sigma);
      inv_scale = std::isfinite(p.v_c) ? 1.0 / ((1.0 - p.sigma) * p.v_c) : 0.0;
    }
  }

  // |phi(y)| for a sliding block (per unit mass).
  double magnitude(double abs_y) const { return kinetic0 / std::fma(abs_y, inv_scale, 1.0); }

  // What the energy balance adds up for a sliding block over a step: the power dissipated
  // per unit mass at the step's two ends, friction phi(y) y with phi frozen to oppose
  // `dir` (clst91 always opposes y > 0) plus a block damper (c_u/m_u) y^2 (damper = 0
  // without one). The sums are explicit fused multiply-adds: left to the compiler, which
  // product it fuses depends on where the function is inlined, and the event engine's
  // paths must agree bit for bit.
  double step_power(double y0, double y1, double dir, double damper) const {
    return step_power_given(magnitude_at(y0), y0, magnitude_at(y1), y1, dir, damper);
  }
  // The same with the magnitudes m0 = magnitude_at(y0), m1 = magnitude_at(y1) known.
  double step_power_given(double m0, double y0, double m1, double y1, double dir,
                          double damper) const {
    auto force = [&](double m) { return backslip ? m * dir : m; };
    const double friction = std::fma(force(m0), y0, force(m1) * y1);
    return std::fma(damper, std::fma(y0, y0, y1 * y1), friction);
  }
  // |phi(y)| at relative velocity y as the law sees it (clst91 only opposes y > 0).
  double magnitude_at(double y) const {
    return magnitude(backslip ? std::abs(y) : std::max(y, 0.0));
  }

  // The static threshold, both ways (model/stick.hpp applies them).
  // Would a stuck block with spring force f break loose?
  bool breaks(double f) const { return backslip ? std::abs(f) > threshold : f > threshold; }
  // Can a block whose velocity has just reached zero stay stuck under spring force f?
  bool holds(double f) const { return !breaks(f); }
};

// The order in which the event engine adds up the step powers of a range's blocks, the
// same in every path: four partial sums by the block's place in the range modulo 4, in
// block order, added as (s0 + s1) + (s2 + s3). It vectorises, and one sliding block among
// stuck ones (whose terms are 0) sums to its own power exactly.
struct RangePowerSum {
  double part[4] = {0.0, 0.0, 0.0, 0.0};
  void add(int place, double power) { part[place % 4] += power; }
  double total() const { return (part[0] + part[1]) + (part[2] + part[3]); }
};

}  // namespace bkq
