// Steady sliding (Sinou, Chiello & Charroyer 2019 §2.3 applied to Ferre 2018 eq. 3.1): at disc
// speed v > 0 every block slides with relative speed v and rests in the lab frame, the pad is at
// rest, friction is m_u phi(v) on every block. The static equations are the chain's tridiagonal
// (cyclic for a periodic chain) stiffness k_p I + k_c L bordered by the pad row:
//   k_c (u_{j-1} - 2u_j + u_{j+1}) - k_p (u_j - x) = m_u phi_j,
//   k_p sum_j (u_j - x) - k_p0 x = 0                    (bkp; x = 0 for bk and 1dof),
// solved in O(N): the uniform part of the load exactly (k_p I + k_c L maps the uniform
// vector to k_p times itself), the rest by Thomas (Sherman–Morrison for the ring). For a
// uniform chain the answer is u_j = x - m_u phi(v)/k_p, x = -N m_u phi(v)/k_p0.
#pragma once

#include <vector>

#include "model/parameters.hpp"

namespace bkq {

// The kinetic branch of the scene's law at relative velocity v > 0, per unit block mass:
// phi(v) and its slope phi'(v) (negative for velocity weakening: negative damping).
struct KineticBranch {
  double phi = 0;
  double slope = 0;
};

// Why there is no steady sliding state, if there is none.
enum class NoEquilibrium {
  None,         // it exists
  NotSliding,   // v <= 0: friction at zero relative velocity is set-valued, the blocks stick
  NoPadSpring,  // bkp with k_p0 = 0 and nonzero friction: nothing holds the pad back
  NoKinetic,    // the law has no smooth kinetic branch at v (unsupported law)
};

struct SlidingEquilibrium {
  NoEquilibrium why = NoEquilibrium::None;
  double v = 0;
  KineticBranch friction;
  std::vector<double> u;  // lab-frame block displacements
  double x = 0;           // pad position (0 unless the pad moves)
  bool exists() const { return why == NoEquilibrium::None; }
};

// phi(v), phi'(v); `why` set to NotSliding / NoKinetic when the law has no branch there.
KineticBranch kinetic_branch(const ModelParams& p, double v, NoEquilibrium* why = nullptr);

// The steady sliding state at disc speed v (see the file comment).
SlidingEquilibrium sliding_equilibrium(const ModelParams& p, double v);

// Solves (k_p I + k_c L) u - k_p x 1 = -f with the pad row (bkp) in O(N): the structure
// the equilibrium uses, exposed for forces f_j that differ from block to block. Returns
// false when the bordered system is singular (bkp without a caliper spring).
bool solve_static(const ModelParams& p, const std::vector<double>& f, std::vector<double>& u,
                  double& x);

}  // namespace bkq
