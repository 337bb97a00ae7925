// The special speed of Ferre 2018 eq. 4.8. The chain is equally spaced, every block pulled
// back to the slip threshold (spring force F0 m_u, displacement D0 = F0 m_u / k_p), the
// substrate at rest and the pad held still (for bkp, as in the plain BK model: the
// thesis's "system of one spring"); equally spaced, the neighbour springs carry nothing
// and the chain moves as one block. It is released and integrated (rk4, dt a 1/20000 of
// the pulling-spring period) until the velocity relative to the substrate first returns
// to zero: t_death, the zero located by extrapolating the last two steps' velocities.
//   v_special = F0 m_u / (k_p t_death)   (thesis: F0 / (k_p t_death), m_u = 1)
// With constant kinetic friction below F0 the release is half an oscillation of the
// pulling spring: t_death = pi sqrt(m_u / k_p).
#pragma once

#include "model/parameters.hpp"

namespace bkq {

struct SpecialSpeed {
  double t_death = 0, v_special = 0, dt = 0;
};

// Throws bkq::Error when the block never comes back to rest relative to the substrate
// within 1000 periods (friction law none, or a damper that never lets it turn).
SpecialSpeed special_speed(ModelParams p);

}  // namespace bkq
