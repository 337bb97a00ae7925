// What every friction law shares (the laws themselves are policy types, one file each
// under model/laws/, listed in model/law_list.hpp; model/friction_laws.hpp says what a
// law supplies). phi(y) is the friction per unit block mass at velocity y relative to the
// substrate. Sliding friction only: at y = 0 friction is set-valued (whatever holds the
// block, up to the static threshold), which the engine enforces through stick flags.
#pragma once

#include <cmath>

namespace bkq {

// The static side of a law, the part the stick rule (model/stick.hpp) and the loader
// read: the threshold on the spring force and whether a block may slide backwards.
struct Friction {
  double threshold = 1;  // static threshold on the spring force, F0 m_u (< 0: never sticks)
  bool backslip = true;  // may a block slide against the substrate (y < 0)?

  // Would a stuck block with spring force f break loose?
  bool breaks(double f) const { return backslip ? std::abs(f) > threshold : f > threshold; }
  // Can a block whose velocity has just reached zero stay stuck under spring force f?
  bool holds(double f) const { return !breaks(f); }
};

// The friction force per unit mass on a block sliding in direction dir with |phi| =
// magnitude: it opposes dir (a law without backslip only ever opposes y > 0).
template <bool Backslip>
inline double signed_friction(double magnitude, double dir) {
  if constexpr (Backslip)
    return std::copysign(magnitude, dir);
  else
    return magnitude;
}

// What the energy balance adds up for a sliding block over a step: the power dissipated
// per unit mass at the step's two ends, friction phi(y) y with phi frozen to oppose `dir`
// plus a block damper (c_u/m_u) y^2 (damper = 0 without one), given the magnitudes
// m0 = |phi(y0)| and m1 = |phi(y1)|. The sums are explicit fused multiply-adds: left to
// the compiler, which product it fuses depends on where the function is inlined, and the
// event engine's paths must agree bit for bit.
template <bool Backslip>
inline double step_power_given(double m0, double y0, double m1, double y1, double dir,
                               double damper) {
  auto force = [&](double m) { return Backslip ? m * dir : m; };
  const double friction = std::fma(force(m0), y0, force(m1) * y1);
  return std::fma(damper, std::fma(y0, y0, y1 * y1), friction);
}
// The same with the law's magnitudes at y0 and y1.
template <class Law>
inline double step_power(const Law& law, double y0, double y1, double dir, double damper) {
  return step_power_given<Law::backslip>(law.magnitude(y0), y0, law.magnitude(y1), y1, dir, damper);
}

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
