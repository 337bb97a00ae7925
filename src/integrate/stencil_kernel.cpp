// The stencil kernel's neighbour structure, and its code for each explicit scheme (see
// stencil_kernel.hpp): compiled here once per scheme and law.
#include "integrate/stencil_kernel.hpp"

#include <algorithm>
#include <utility>

#include "integrate/rk2.hpp"
#include "integrate/rk4.hpp"
#include "integrate/verlet.hpp"

namespace bkq {

void append_site_springs(const ChainForces& forces, int j, std::vector<StencilSpring>& out) {
  auto add = [&](int l, int r, double k) {
    if (l < 0) std::swap(l, r);
    if (l >= 0) out.push_back({l, r, k});
  };
  if (forces.lattice()) {
    // lattice_sum's order: each spring's partner at -(dx, dy), then at +(dx, dy).
    const int x = j % forces.nx(), y = j / forces.nx();
    for (const LatticeSpring& s : forces.lattice_stencil())
      add(forces.site(x - s.dx, y - s.dy), forces.site(x + s.dx, y + s.dy), s.k);
    return;
  }
  // stencil_sum's order, and neighbour_force's chain without springs.
  const ModelParams& p = forces.params();
  const int n = p.n;
  if (n < 2 || p.k_c == 0) return;
  const bool ring = p.boundary == Boundary::Periodic;
  for (const CouplingSpring& s : forces.stencil()) {
    int l = j - s.offset, r = j + s.offset;
    if (ring) {
      if (l < 0) l += n;
      if (r >= n) r -= n;
    } else {
      if (l < 0) l = -1;
      if (r >= n) r = -1;
    }
    add(l, r, s.k);
  }
}

void StencilRelaxation::build(const ChainForces& forces, Ranges ranges) {
  const ChainState& st = *state;
  const int n = forces.n();
  if (listed_for != &forces || static_cast<int>(slot.size()) != n) {
    listed_for = &forces;
    slot.assign(n, -1);
    listed_begin.assign(n, -1);
    listed_end.assign(n, -1);
    end_state = nullptr;
    springs.clear();
    site.clear();
  }
  for (const int j : site) slot[j] = -1;
  site.clear();
  range.clear();
  place.clear();
  begin.clear();
  end.clear();
  for (std::size_t k = 0; k < ranges.size(); ++k)
    for (int j = ranges[k].lo; j < ranges[k].hi; ++j) {
      slot[j] = static_cast<int>(site.size());
      site.push_back(j);
      range.push_back(static_cast<int>(k));
      place.push_back((j - ranges[k].lo) % 4);
      if (listed_begin[j] < 0) {
        listed_begin[j] = static_cast<int>(springs.size());
        append_site_springs(forces, j, springs);
        listed_end[j] = static_cast<int>(springs.size());
      }
      begin.push_back(listed_begin[j]);
      end.push_back(listed_end[j]);
    }
  // Every partner of a sliding site is covered (ActiveSet::cover), which the kernel's
  // compact springs need; said so here, not assumed. The refit keeps a covered site that
  // slides or has a sliding partner (the sites a sliding one covers are its partners:
  // ActiveSet::cover), which are the sliding sites' partners (the stencils are symmetric).
  const int c = static_cast<int>(site.size());
  marked.assign(c, 0);
  usable = true;
  refit_keeps = false;
  for (int i = 0; i < c; ++i)
    if (st.mobile[site[i]] != 0.0) {
      marked[i] = 1;
      for (int k = begin[i]; k < end[i]; ++k) {
        const int l = slot[springs[k].l], r = springs[k].r >= 0 ? slot[springs[k].r] : c;
        if (l < 0 || r < 0) {
          usable = false;
          return;
        }
        marked[l] = 1;
        if (r < c) marked[r] = 1;
      }
    }
  refit_keeps = std::find(marked.begin(), marked.end(), 0) == marked.end();
}

template bool run_stencil<Rk2Method>(const ChainForces&, StencilRelaxation&);
template bool run_stencil<Rk4Method>(const ChainForces&, StencilRelaxation&);
template bool run_stencil<VerletMethod>(const ChainForces&, StencilRelaxation&);

}  // namespace bkq
