// The BK–Pad equations of motion (Ferre 2018 eq. 3.1), written in the frame of the substrate:
// w_j = u_j + s, where s is the substrate displacement. Then the friction argument
// v + u'_j is simply w'_j, a stuck block has w'_j = 0 exactly, and loading the chain is
// a change of s alone. The pulling springs pull towards the "anchor" s + x (pad at x).
//
//   m_u w''_j = k_c (w_{j-1} - 2 w_j + w_{j+1}) - k_p (w_j - s - x) - m_u phi(w'_j)
//               [- c_u (w'_j - v)  1DOF damper]  [+ m_u a_s  substrate acceleration]
//               [- (alpha_M M u' + beta_K K u')_j  Rayleigh block damping]
//   m_x x''   = -c_p x' + k_p (sum_j w_j - N s - N x) - k_p0 x  [- (alpha_M M u' + beta_K K
//   u')_pad]
//
// Rayleigh damping (model.rayleigh_alpha, _beta) is the matrix C = alpha_M M + beta_K K of
// stats/stability: M and K of blocks and pad (K with k_c, the k_p coupling and the pad row
// with k_p0), acting on the lab-frame velocities u'_j = w'_j - v and x'. K u' is minus the
// spring force evaluated at the velocities with the anchor moving at v + x', so the block
// term is beta_K/m_u spring_force(w', anchor rate) - alpha_M (w'_j - v) per unit mass. It is
// a switch (ForceTerms::rayleigh) of the continuous runs' kernels only: the event engine's
// held-range and cluster paths never instantiate it (event runs refuse the damping).
//
// Viscous coupling (model.viscosity = eta, Myers & Langer 1993): a dashpot beside each spring
// of the stencil, + sum_r eta_r (w'_{j-r} - 2 w'_j + w'_{j+r}) on block j (velocity
// differences are frame-free). beta_K K of the Rayleigh damping holds the neighbour dashpot
// beta_K k_c of nearest neighbours too, and also damps the pulling springs and the pad: the
// two compose (they add). The dashpots go through kernel_long.
//
// Coupling beyond the nearest neighbours (model.coupling = range | power, model/coupling.hpp):
// k_c (w_{j-1} - 2 w_j + w_{j+1}) becomes sum_r k_r (w_{j-r} - 2 w_j + w_{j+r}) over the
// stencil. Its kernel (kernel_long) forms every block's force with the stencil; the
// nearest-neighbour kernels and everything below that reads only j +- 1 are untouched, so
// a nearest-neighbour scene (and range or power at R = 1) keeps its bits.
//
// A lattice (ModelParams::lattice, Carlson 1991): the sites are stored row by row and the
// stencil lives in the plane (model/coupling.hpp's LatticeStencil); every force goes through
// lattice_sum and the general kernel, and the chain's fast paths, which read j +- 1, stay off
// (all but the replayed event start, engine/lone_slip.hpp, which takes a site's partners).
//
// Only the terms a scene switches on are compiled into the kernel that runs (templates
// on the friction law's policy type, model/friction_laws.hpp; on the optional terms,
// ForceTerms; and on the substrate acceleration).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "model/coupling.hpp"
#include "model/friction.hpp"
#include "model/friction_laws.hpp"
#include "model/parameters.hpp"

namespace bkq {

// A half-open range [lo, hi) of block indices that a stepper advances.
struct Range {
  int lo = 0, hi = 0;
};
using Ranges = std::span<const Range>;

// max_speed = max(max_speed, speed), except that a NaN, once in, stays: a non-finite
// velocity must survive into an event's largest speed (std::max would drop a NaN).
inline void raise_max_speed(double& max_speed, double speed) {
  if (!(speed <= max_speed) && max_speed == max_speed) max_speed = speed;
}

// Everything that evolves. Stick flags live in `mobile` (1 = sliding, 0 = stuck) as
// doubles so the kernels can multiply by them without branching. `dir` is the direction
// each sliding block slides in (+1/-1): like the stick flags it is frozen over a step, so
// friction keeps opposing the motion the block had at the start of the step even when its
// velocity passes through zero inside the step (the stick rule then sees the crossing).
struct ChainState {
  std::vector<double> w, wd;  // block position and velocity in the substrate frame
  std::vector<double> mobile;
  std::vector<double> dir;
  double x = 0, xd = 0;  // pad position and velocity (lab frame)
  double s = 0;          // substrate displacement
  double t = 0;          // time
  double sum_w = 0;      // sum of w over all blocks (kept up to date when the pad moves)

  void resize(int n) {
    w.assign(n, 0.0);
    wd.assign(n, 0.0);
    mobile.assign(n, 0.0);
    dir.assign(n, 1.0);
  }
  int n() const { return static_cast<int>(w.size()); }
  double recompute_sum_w();
};

// What the substrate does at one instant (frozen in the event-driven relaxation).
struct SubstrateState {
  double s = 0;  // displacement
  double v = 0;  // speed
  double a = 0;  // acceleration (non-zero during a ramp)
};

// The optional terms of the force on a block, as compile-time switches: a kernel is
// instantiated for each combination and computes only what is on. A new optional term is
// one more switch here, its pick in ChainForces::with_switches and its use in
// interior_force / acceleration_given.
template <bool Neighbours, bool Damper, bool Rayleigh = false>
struct ForceTerms {
  static constexpr bool neighbours = Neighbours;  // neighbour springs k_c (k_c != 0, N > 1)
  static constexpr bool damper = Damper;          // the 1DOF block damper c_u (c_u != 0)
  // Rayleigh block damping (alpha_M or beta_K != 0); picked in select_kernel only.
  static constexpr bool rayleigh = Rayleigh;
};

class ChainForces {
 public:
  explicit ChainForces(const ModelParams& p);

  const ModelParams& params() const { return p_; }
  // The static side of the law (threshold, backslip), for the stick rule and the loader.
  const Friction& friction() const { return friction_; }
  int n() const { return p_.n; }
  // The coupling's springs and dashpots (model/coupling.hpp), and whether the springs reach
  // beyond j +- 1.
  const CouplingStencil& stencil() const { return stencil_; }
  const CouplingStencil& dampers() const { return dampers_; }
  bool long_range() const { return long_range_; }
  bool viscous() const { return viscous_; }
  // A two-dimensional lattice: its stencil in the plane, and its shape.
  bool lattice() const { return lattice_; }
  const LatticeStencil& lattice_stencil() const { return grid_; }
  int nx() const { return nx_; }
  // Whether the forces need the general kernel (kernel_long): springs beyond j +- 1, dashpots
  // or a lattice. The nearest-neighbour fast paths (cluster, held ranges, lone slip, the
  // vectorised contact pass) apply only where this is false; the lone slip also on a lattice.
  bool general_kernel() const { return long_range_ || viscous_ || lattice_; }
  // Blocks on each side of a block (in the order they are stored) that its springs and
  // dashpots reach: on a lattice the farthest partner's distance in that order.
  int reach() const { return reach_; }
  // Whether a block's springs reach from one end of the storage order to the other (a
  // periodic chain, or a lattice with periodic rows).
  bool wraps() const {
    return lattice_ ? p_.boundary_y == Boundary::Periodic : p_.boundary == Boundary::Periodic;
  }
  // Calls f(i) for every site i a spring couples to site j of a lattice (each once per spring,
  // in the stencil's order, the partner at -offset first).
  template <class F>
  void for_each_partner(int j, F&& f) const {
    const int x = j % nx_, y = j / nx_;
    if (interior_site(x, y)) {
      for (const int o : grid_offset_) {
        f(j - o);
        f(j + o);
      }
      return;
    }
    for (const LatticeSpring& s : grid_) {
      if (const int i = site(x - s.dx, y - s.dy); i >= 0) f(i);
      if (const int i = site(x + s.dx, y + s.dy); i >= 0) f(i);
    }
  }
  // Whether every partner of the site at (x, y) lies inside the lattice, at j -+ offset
  // (grid_offset_), with no edge to test.
  bool interior_site(int x, int y) const {
    return x >= grid_reach_x_ && x < nx_ - grid_reach_x_ && y >= grid_reach_y_ &&
           y < ny_ - grid_reach_y_;
  }
  // The site at (x, y) of a lattice, wrapped across periodic edges; -1 past a free edge.
  int site(int x, int y) const {
    if (x < 0 || x >= nx_) {
      if (p_.boundary != Boundary::Periodic) return -1;
      x += x < 0 ? nx_ : -nx_;
    }
    if (y < 0 || y >= ny_) {
      if (p_.boundary_y != Boundary::Periodic) return -1;
      y += y < 0 ? ny_ : -ny_;
    }
    return y * nx_ + x;
  }
  // sum_s k_s ((w_{j-s} - w_j) + (w_{j+s} - w_j)) over the lattice's stencil, the edges
  // applied. Nearest neighbours give k_c (...) + k_c_y (...): a sum of two terms, the same
  // with the axes swapped.
  double lattice_sum(const double* w, int j) const {
    const int x = j % nx_, y = j / nx_;
    const double wj = w[j];
    double f = 0;
    if (interior_site(x, y)) {
      // Every partner is inside the lattice, at j -+ (dx + dy nx): no edge to test, the same
      // operations in the same order as below.
      for (std::size_t k = 0; k < grid_.size(); ++k) {
        const int o = grid_offset_[k];
        double d = 0;
        d += w[j - o] - wj;
        d += w[j + o] - wj;
        f += grid_[k].k * d;
      }
      return f;
    }
    for (const LatticeSpring& s : grid_) {
      double d = 0;
      if (const int i = site(x - s.dx, y - s.dy); i >= 0) d += w[i] - wj;
      if (const int i = site(x + s.dx, y + s.dy); i >= 0) d += w[i] - wj;
      f += s.k * d;
    }
    return f;
  }

  // Spring force on block j (neighbours and pulling spring), the force friction must hold.
  double spring_force(const double* w, int j, double anchor) const {
    return neighbour_force(w, j) - p_.k_p * (w[j] - anchor);
  }
  // k_c (w_{j-1} - 2 w_j + w_{j+1}) with the scene's boundary (free ends: no spring).
  double neighbour_force(const double* w, int j) const {
    if (lattice_) return lattice_sum(w, j);
    const int n = p_.n;
    if (n < 2 || p_.k_c == 0) return 0.0;
    if (long_range_) return stencil_force(w, j);
    if (p_.boundary == Boundary::Periodic) {
      const double left = w[j == 0 ? n - 1 : j - 1];
      const double right = w[j == n - 1 ? 0 : j + 1];
      return p_.k_c * (left - 2.0 * w[j] + right);
    }
    // Free ends: a missing neighbour contributes no spring.
    double f = 0;
    if (j > 0) f += w[j - 1] - w[j];
    if (j < n - 1) f += w[j + 1] - w[j];
    return p_.k_c * f;
  }
  // sum_r k_r ((w_{j-r} - w_j) + (w_{j+r} - w_j)) over the stencil, with the scene's
  // boundary (free ends: the springs reaching past the chain are missing).
  double stencil_force(const double* w, int j) const { return stencil_sum(stencil_, w, j); }
  double stencil_sum(const CouplingStencil& stencil, const double* w, int j) const {
    const int n = p_.n;
    const double wj = w[j];
    double f = 0;
    if (p_.boundary == Boundary::Periodic) {
      for (const CouplingSpring& s : stencil) {
        const int l = j - s.offset < 0 ? j - s.offset + n : j - s.offset;
        const int r = j + s.offset >= n ? j + s.offset - n : j + s.offset;
        f += s.k * ((w[l] - wj) + (w[r] - wj));
      }
      return f;
    }
    for (const CouplingSpring& s : stencil) {
      double d = 0;
      if (j - s.offset >= 0) d += w[j - s.offset] - wj;
      if (j + s.offset < n) d += w[j + s.offset] - wj;
      f += s.k * d;
    }
    return f;
  }
  // The dashpots' force on block j at velocities wd: sum_r eta_r ((wd_{j-r} - wd_j) +
  // (wd_{j+r} - wd_j)) (0 without viscosity).
  double damper_force(const double* wd, int j) const {
    return viscous_ ? stencil_sum(dampers_, wd, j) : 0.0;
  }
  // The force friction must hold on block j if it is (or becomes) stuck: the springs' and
  // the dashpots' from its neighbours' velocities, its own taken as 0 (a stuck block moves
  // with the substrate). Without viscosity spring_force itself, bit for bit.
  double holding_force(const double* w, const double* wd, int j, double anchor) const {
    const double f = spring_force(w, j, anchor);
    if (!viscous_) return f;
    const int n = p_.n;
    double d = 0;
    const bool ring = p_.boundary == Boundary::Periodic;
    for (const CouplingSpring& c : dampers_) {
      double v = 0;
      if (j - c.offset >= 0)
        v += wd[j - c.offset];
      else if (ring)
        v += wd[j - c.offset + n];
      if (j + c.offset < n)
        v += wd[j + c.offset];
      else if (ring)
        v += wd[j + c.offset - n];
      d += c.k * v;
    }
    return f + d;
  }
  // Power the dashpots dissipate, sum over their bonds of eta_r (wd_k - wd_j)^2, counting
  // the bonds from the blocks of `ranges` to the right (the event engine's ranges hold
  // every moving block with R stuck ones each side; pass {0, N} for the whole chain).
  double damper_power(const double* wd, Ranges ranges) const;
  // The part of the spring force that does not depend on the anchor:
  // g_j = neighbour_force - k_p w_j, so that f_j = g_j + k_p anchor.
  double local_force(const double* w, int j) const { return neighbour_force(w, j) - p_.k_p * w[j]; }

  // Spring force on an interior block at w with neighbours at wl and wr (what the kernels
  // compute).
  template <class Terms>
  double interior_force(double wl, double w, double wr, double anchor) const {
    double f = p_.k_p * (anchor - w);
    if constexpr (Terms::neighbours) f += p_.k_c * (wl - 2.0 * w + wr);
    return f;
  }
  // Acceleration of a sliding block with spring force f and relative velocity y.
  template <class Law, class Terms, bool Inertial>
  double acceleration(const Law& law, double f, double y, double dir,
                      const SubstrateState& sub) const {
    return acceleration_given<Law, Terms, Inertial>(f, law.magnitude(y), y, dir, sub);
  }
  // The same with |phi(y)| = law.magnitude(y) already known, bit for bit.
  template <class Law, class Terms, bool Inertial>
  double acceleration_given(double f, double magnitude, double y, double dir,
                            const SubstrateState& sub) const;
  // Calls `f.template operator()<Law, Terms>(law)` with the scene's law (its policy type
  // and its numbers) and a ForceTerms of the scene's switches, so the code it instantiates
  // computes only what is on.
  template <class F>
  decltype(auto) with_switches(F&& f) const;
  // The scene's law as type Law, which must be the scene's (the callers dispatch on it).
  // Said so to the compiler: a pointer that might be null keeps GCC from hoisting the
  // law's numbers out of the kernels' loops.
  template <class Law>
  const Law& law() const {
    const Law* law = std::get_if<Law>(&law_);
    if (law == nullptr) __builtin_unreachable();
    return *law;
  }
  // Calls `f(law)` with the scene's law.
  template <class F>
  decltype(auto) with_law(F&& f) const {
    return visit_law(p_.law, [&]<class L>() -> decltype(auto) { return f(law<L>()); });
  }

  // Block accelerations a[j] for every j in `ranges`; stuck blocks get exactly 0.
  // anchor_rate is the anchor's velocity v + x' (read only with Rayleigh damping).
  void block_accelerations(const double* w, const double* wd, const double* mobile,
                           const double* dir, double anchor, double anchor_rate,
                           const SubstrateState& sub, Ranges ranges, double* a) const;

  // Pad acceleration given the sum of w over all blocks.
  double pad_acceleration(double x, double xd, double sum_w, double s) const {
    return (-p_.c_p * xd + p_.k_p * (sum_w - p_.n * s - p_.n * x) - p_.k_p0 * x) / p_.m_x;
  }
  // The same with the pad's Rayleigh damping, given also the sum of w' over all blocks
  // and the substrate speed v (identical to the above without damping).
  double pad_acceleration(double x, double xd, double sum_w, double s, double sum_wd,
                          double v) const {
    const double a = pad_acceleration(x, xd, sum_w, s);
    return rayleigh_ ? a + pad_rayleigh_acceleration(xd, sum_wd, v) : a;
  }

  // Rayleigh block damping: is it on, and its parts. The block's acceleration given the
  // spring force fv evaluated at the velocities (anchor at v + x'), its own w' and v.
  bool rayleigh() const { return rayleigh_; }
  double rayleigh_acceleration(double fv, double y, double v) const {
    return beta_m_ * fv - p_.rayleigh_alpha * (y - v);
  }
  // -(alpha_M m_x x' + beta_K (k_p sum_j (x' - u'_j) + k_p0 x')) / m_x, u'_j = w'_j - v.
  double pad_rayleigh_acceleration(double xd, double sum_wd, double v) const {
    const double n = p_.n;
    return -(p_.rayleigh_alpha * p_.m_x * xd +
             p_.rayleigh_beta * (p_.k_p * (n * xd - (sum_wd - n * v)) + p_.k_p0 * xd)) /
           p_.m_x;
  }
  // Power the Rayleigh damping dissipates, u'^T C u' (blocks and pad), at velocities wd
  // (substrate frame), pad velocity xd (0 for a held pad) and substrate speed v.
  double rayleigh_power(const double* wd, double xd, double v) const;
  // Pad position at rest with every block stuck (quasi-static balance of its springs).
  double pad_equilibrium(double sum_w, double s) const {
    return p_.k_p * (sum_w - p_.n * s) / (p_.k_p0 + p_.n * p_.k_p);
  }

  // Energy stored in the springs (neighbour, pulling, caliper) and kinetic energy in the
  // lab frame (u' = w' - v); used by tests and the energy balance.
  double spring_energy(const ChainState& st) const;
  double kinetic_energy(const ChainState& st, double v) const;

 private:
  using Kernel = void (*)(const ChainForces&, const double*, const double*, const double*,
                          const double*, double, double, const SubstrateState&, int, int, double*);
  template <class Law, class Terms, bool Inertial>
  static void kernel(const ChainForces& self, const double* w, const double* wd,
                     const double* mobile, const double* dir, double anchor, double anchor_rate,
                     const SubstrateState& sub, int lo, int hi, double* a);
  // The same with the coupling's stencil (long_range()): every block's force by spring_force.
  template <class Law, class Terms, bool Inertial>
  static void kernel_long(const ChainForces& self, const double* w, const double* wd,
                          const double* mobile, const double* dir, double anchor,
                          double anchor_rate, const SubstrateState& sub, int lo, int hi, double* a);
  Kernel select_kernel(bool inertial) const;
  // 1/2 u^T K u for positions w with the anchor at `anchor` and the pad at x.
  double stiffness_energy(const double* w, double anchor, double x) const;

  ModelParams p_;
  LawVariant law_;
  Friction friction_;
  CouplingStencil stencil_, dampers_;
  LatticeStencil grid_;
  // Each lattice spring's partner offset in storage order (dx + dy nx), and the stencil's
  // largest |dx| and |dy|: a site that far from every edge has all its partners.
  std::vector<int> grid_offset_;
  int grid_reach_x_ = 0, grid_reach_y_ = 0;
  bool long_range_ = false;
  bool viscous_ = false;
  bool lattice_ = false;
  int nx_ = 1, ny_ = 1;
  int reach_ = 1;
  double inv_m_ = 1;
  bool rayleigh_ = false;
  double beta_m_ = 0;  // beta_K / m_u
  Kernel kernel_ = nullptr;
  Kernel kernel_inertial_ = nullptr;
};

template <class Law, class Terms, bool Inertial>
double ChainForces::acceleration_given(double f, double magnitude, double y, double dir,
                                       const SubstrateState& sub) const {
  double acc = f * inv_m_;
  if constexpr (!Law::frictionless) acc -= signed_friction<Law::backslip>(magnitude, dir);
  if constexpr (Terms::damper) acc -= p_.c_u * inv_m_ * (y - sub.v);
  if constexpr (Inertial) acc += sub.a;
  return acc;
}

template <class F>
decltype(auto) ChainForces::with_switches(F&& f) const {
  const bool nb = p_.has_neighbours();
  const bool damper = p_.c_u != 0;
  return with_law([&]<class L>(const L& law) -> decltype(auto) {
    if (nb)
      return damper ? f.template operator()<L, ForceTerms<true, true>>(law)
                    : f.template operator()<L, ForceTerms<true, false>>(law);
    return damper ? f.template operator()<L, ForceTerms<false, true>>(law)
                  : f.template operator()<L, ForceTerms<false, false>>(law);
  });
}

}  // namespace bkq
