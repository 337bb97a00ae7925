// Forces of the BK–Pad chain (Ferre 2018 eq. 3.1) in the substrate frame; see chain.hpp.
#include "model/chain.hpp"

#include <algorithm>
#include <cmath>

namespace bkq {

double ChainState::recompute_sum_w() {
  double s = 0;
  for (double v : w) s += v;
  sum_w = s;
  return s;
}

ChainForces::ChainForces(const ModelParams& p)
    : p_(p),
      law_(make_law(p)),
      friction_(friction_of(p)),
      stencil_(p.lattice() ? CouplingStencil{} : coupling_stencil(p)),
      dampers_(damper_stencil(p)),
      grid_(bkq::lattice_stencil(p)),
      long_range_(p.long_range() && !p.lattice()),
      viscous_(p.viscous()),
      lattice_(p.lattice()),
      nx_(p.nx()),
      ny_(p.rows),
      inv_m_(1.0 / p.m_u),
      rayleigh_(p.rayleigh_alpha != 0 || p.rayleigh_beta != 0),
      beta_m_(p.rayleigh_beta / p.m_u) {
  for (const CouplingStencil* st : {&stencil_, &dampers_})
    for (const CouplingSpring& c : *st) reach_ = std::max(reach_, c.offset);
  // A lattice site's partners lie within max |dy| + 1 rows of it in the storage order (a
  // periodic row's wrap included).
  for (const LatticeSpring& c : grid_) {
    reach_ = std::max(reach_, (std::abs(c.dy) + 1) * nx_);
    grid_offset_.push_back(c.dx + c.dy * nx_);
    grid_reach_x_ = std::max(grid_reach_x_, std::abs(c.dx));
    grid_reach_y_ = std::max(grid_reach_y_, std::abs(c.dy));
  }
  kernel_ = select_kernel(false);
  kernel_inertial_ = select_kernel(true);
}

template <class Law, class Terms, bool Inertial>
void ChainForces::kernel(const ChainForces& self, const double* __restrict w,
                         const double* __restrict wd, const double* __restrict mobile,
                         const double* __restrict dir, double anchor, double anchor_rate,
                         const SubstrateState& sub, int lo, int hi, double* __restrict a) {
  const int n = self.p_.n;
  const Law& law = self.law<Law>();
  // The chain ends (and the periodic wrap) go through the scalar path. `fv()` is the
  // spring force at the velocities, which only the Rayleigh damping reads.
  auto at = [&](int j, double f, auto fv) {
    if constexpr (Terms::rayleigh)
      a[j] = mobile[j] * (self.acceleration<Law, Terms, Inertial>(law, f, wd[j], dir[j], sub) +
                          self.rayleigh_acceleration(fv(), wd[j], sub.v));
    else
      a[j] = mobile[j] * self.acceleration<Law, Terms, Inertial>(law, f, wd[j], dir[j], sub);
  };
  if (lo == 0 && hi > 0) {
    at(0, self.spring_force(w, 0, anchor), [&] { return self.spring_force(wd, 0, anchor_rate); });
    lo = 1;
  }
  if (hi == n && hi > lo) {
    at(n - 1, self.spring_force(w, n - 1, anchor),
       [&] { return self.spring_force(wd, n - 1, anchor_rate); });
    hi = n - 1;
  }
  // Interior blocks: branch-free so the compiler vectorises it.
  for (int j = lo; j < hi; ++j)
    at(j, self.interior_force<Terms>(w[j - 1], w[j], w[j + 1], anchor),
       [&] { return self.interior_force<Terms>(wd[j - 1], wd[j], wd[j + 1], anchor_rate); });
}

template <class Law, class Terms, bool Inertial>
void ChainForces::kernel_long(const ChainForces& self, const double* __restrict w,
                              const double* __restrict wd, const double* __restrict mobile,
                              const double* __restrict dir, double anchor, double anchor_rate,
                              const SubstrateState& sub, int lo, int hi, double* __restrict a) {
  const Law& law = self.law<Law>();
  for (int j = lo; j < hi; ++j) {
    // A stuck block's acceleration is 0 whatever its force: with a stencil of R springs the
    // event's 2R stuck blocks around each sliding one would otherwise cost R each.
    if (mobile[j] == 0.0) {
      a[j] = 0.0;
      continue;
    }
    const double f = self.spring_force(w, j, anchor);
    double acc = self.acceleration<Law, Terms, Inertial>(
        law, self.viscous_ ? f + self.damper_force(wd, j) : f, wd[j], dir[j], sub);
    if constexpr (Terms::rayleigh)
      acc += self.rayleigh_acceleration(self.spring_force(wd, j, anchor_rate), wd[j], sub.v);
    a[j] = mobile[j] * acc;
  }
}

ChainForces::Kernel ChainForces::select_kernel(bool inertial) const {
  return with_switches([&]<class L, class Terms>(const L&) -> Kernel {
    // The Rayleigh switch is picked here, not in with_switches: only the continuous runs'
    // kernels take it (the event engine's paths refuse the damping).
    using Damped = ForceTerms<Terms::neighbours, Terms::damper, true>;
    if (long_range_ || viscous_ || lattice_) {
      if (rayleigh_)
        return inertial ? &kernel_long<L, Damped, true> : &kernel_long<L, Damped, false>;
      return inertial ? &kernel_long<L, Terms, true> : &kernel_long<L, Terms, false>;
    }
    if (rayleigh_) return inertial ? &kernel<L, Damped, true> : &kernel<L, Damped, false>;
    return inertial ? &kernel<L, Terms, true> : &kernel<L, Terms, false>;
  });
}

void ChainForces::block_accelerations(const double* w, const double* wd, const double* mobile,
                                      const double* dir, double anchor, double anchor_rate,
                                      const SubstrateState& sub, Ranges ranges, double* a) const {
  const Kernel k = sub.a != 0.0 ? kernel_inertial_ : kernel_;
  for (const Range& r : ranges)
    k(*this, w, wd, mobile, dir, anchor, anchor_rate, sub, r.lo, r.hi, a);
}

double ChainForces::stiffness_energy(const double* w, double anchor, double x) const {
  const int n = p_.n;
  double e_c = 0, e_p = 0;
  for (int j = 0; j < n; ++j) {
    const double d = w[j] - anchor;
    e_p += d * d;
  }
  if (lattice_ || long_range_) {
    // Each spring once: on a lattice from every site to its partner at +offset, on a chain
    // from every block to the block `offset` to its right (a periodic chain's wrap included;
    // 2R < N keeps the springs distinct).
    double e = 0;
    if (lattice_) {
      for (int j = 0; j < n; ++j) {
        const int x = j % nx_, y = j / nx_;
        for (const LatticeSpring& s : grid_)
          if (const int i = site(x + s.dx, y + s.dy); i >= 0) {
            const double d = w[i] - w[j];
            e += s.k * d * d;
          }
      }
    } else {
      const bool ring = p_.boundary == Boundary::Periodic;
      for (const CouplingSpring& s : stencil_) {
        double sum = 0;
        for (int j = 0; j < n; ++j) {
          int r = j + s.offset;
          if (r >= n) {
            if (!ring) break;
            r -= n;
          }
          const double d = w[r] - w[j];
          sum += d * d;
        }
        e += s.k * sum;
      }
    }
    double total = 0.5 * e + 0.5 * p_.k_p * e_p;
    if (p_.pad_moves()) total += 0.5 * p_.k_p0 * x * x;
    return total;
  }
  if (p_.has_neighbours()) {
    for (int j = 0; j + 1 < n; ++j) {
      const double d = w[j + 1] - w[j];
      e_c += d * d;
    }
    if (p_.boundary == Boundary::Periodic && n > 2) {
      const double d = w[0] - w[n - 1];
      e_c += d * d;
    }
  }
  double e = 0.5 * p_.k_c * e_c + 0.5 * p_.k_p * e_p;
  if (p_.pad_moves()) e += 0.5 * p_.k_p0 * x * x;
  return e;
}

double ChainForces::spring_energy(const ChainState& st) const {
  return stiffness_energy(st.w.data(), st.s + (p_.pad_moves() ? st.x : 0.0), st.x);
}

double ChainForces::rayleigh_power(const double* wd, double xd, double v) const {
  if (!p_.pad_moves()) xd = 0.0;
  double mass = 0;
  for (int j = 0; j < p_.n; ++j) mass += (wd[j] - v) * (wd[j] - v);
  mass = p_.m_u * mass + (p_.pad_moves() ? p_.m_x * xd * xd : 0.0);
  return p_.rayleigh_alpha * mass + 2.0 * p_.rayleigh_beta * stiffness_energy(wd, v + xd, xd);
}

double ChainForces::damper_power(const double* wd, Ranges ranges) const {
  if (!viscous_) return 0.0;
  const int n = p_.n;
  const bool ring = p_.boundary == Boundary::Periodic;
  double power = 0;
  for (const Range& r : ranges)
    for (int j = r.lo; j < r.hi; ++j)
      for (const CouplingSpring& c : dampers_) {
        int k = j + c.offset;
        if (k >= n) {
          if (!ring) continue;
          k -= n;
        }
        const double d = wd[k] - wd[j];
        power += c.k * d * d;
      }
  return power;
}

double ChainForces::kinetic_energy(const ChainState& st, double v) const {
  double e = 0;
  for (double y : st.wd) e += (y - v) * (y - v);
  e *= 0.5 * p_.m_u;
  if (p_.pad_moves()) e += 0.5 * p_.m_x * st.xd * st.xd;
  return e;
}

}  // namespace bkq
