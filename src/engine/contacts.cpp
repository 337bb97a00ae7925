// The branch-free form of the contact rule over interior blocks; see contacts.hpp.
#include "engine/contacts.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>

#include "integrate/transition_rule.hpp"

namespace bkq::contacts_detail {
namespace {

// The stick rule for blocks lo..hi-1, with the stuck blocks that break loose only
// counted, `force(j)` giving the spring force on block j. The rule has no branches, so the
// loop vectorises; Backslip is the law's flag as a constant, so the rule's tests on it fold
// (stick::settle_in_place: the form that vectorises best).
template <bool Backslip, class Force>
InteriorPass settle_run(int lo, int hi, Force force, Friction fr, bool crossing_rule,
                        const double* __restrict wd_old, double* __restrict wd,
                        double* __restrict mob, double* __restrict dir) {
  fr.backslip = Backslip;
  int sliding = 0, breaks = 0, first_break = hi;
  // The largest speed as an integer maximum over bit patterns: for doubles of positive
  // sign the pattern grows with the value and a NaN lies above infinity, so a NaN speed
  // survives into max_speed.
  std::int64_t max_bits = 0;
  for (int j = lo; j < hi; ++j) {
    const stick::Transition o = stick::settle_in_place<Backslip>(fr, crossing_rule, wd_old[j],
                                                                 force(j), wd[j], mob[j], dir[j]);
    sliding += o.slides ? 1 : 0;
    // A block that does not slide enters the maximum with the complement of its bits,
    // which is negative and so below the start value 0. (Written as a select between two
    // values the compiler cannot order, it stays a plain maximum that vectorises.)
    const std::int64_t bits = std::bit_cast<std::int64_t>(std::abs(wd[j]));
    max_bits = std::max(max_bits, o.slides ? bits : ~bits);
    breaks += o.breaks ? 1 : 0;
    first_break = std::min(first_break, o.breaks ? j : hi);
  }
  return InteriorPass{sliding, std::bit_cast<double>(max_bits), breaks, first_break};
}

// The spring force on interior blocks: spring_force's arithmetic for the scene's boundary
// written out (the same operations, so the same bits) without its end tests.
template <bool Backslip>
InteriorPass settle_interior(const ChainForces& forces, ChainState& st, const double* wd_old,
                             double anchor, int lo, int hi, bool crossing_rule) {
  const ModelParams& p = forces.params();
  const double kc = p.k_c, kp = p.k_p;
  const double* w = st.w.data();
  auto run = [&](auto force) {
    return settle_run<Backslip>(lo, hi, force, forces.friction(), crossing_rule, wd_old,
                                st.wd.data(), st.mobile.data(), st.dir.data());
  };
  if (!p.has_neighbours()) return run([=](int j) { return 0.0 - kp * (w[j] - anchor); });
  if (p.boundary == Boundary::Periodic)
    return run(
        [=](int j) { return kc * (w[j - 1] - 2.0 * w[j] + w[j + 1]) - kp * (w[j] - anchor); });
  // Free ends: neighbour_force's running sum starts from 0.
  return run([=](int j) {
    return kc * ((0.0 + (w[j - 1] - w[j])) + (w[j + 1] - w[j])) - kp * (w[j] - anchor);
  });
}

}  // namespace

InteriorPass settle_interior(const ChainForces& forces, ChainState& st, const double* wd_old,
                             double anchor, int lo, int hi, bool crossing_rule) {
  return forces.friction().backslip
             ? settle_interior<true>(forces, st, wd_old, anchor, lo, hi, crossing_rule)
             : settle_interior<false>(forces, st, wd_old, anchor, lo, hi, crossing_rule);
}

}  // namespace bkq::contacts_detail

namespace bkq {
namespace {

// The law by value: a local copy whose numbers the stores cannot change.
template <class Law>
double range_power(const Law law, double damper, const double* __restrict mobile,
                   const double* __restrict dir, const double* __restrict y0,
                   const double* __restrict y1, int lo, int hi) {
  // Four blocks at a time, the place modulo 4 a constant in the body: it vectorises.
  return transition::range_power(hi - lo, [&](int m) {
    const int j = lo + m;
    return transition::crossing_power<Law::backslip>(mobile[j], law.magnitude(y0[j]), y0[j],
                                                     law.magnitude(y1[j]), y1[j], dir[j], damper);
  });
}

}  // namespace

double dissipated_power(const ChainForces& forces, const ChainState& st, const double* wd_old,
                        Ranges ranges) {
  const double damper = forces.params().c_u / forces.params().m_u;
  const double* mobile = st.mobile.data();
  const double* dir = st.dir.data();
  const double* wd = st.wd.data();
  return forces.with_law([&](const auto& law) {
    double sum = 0;
    for (const Range& r : ranges)
      sum += range_power(law, damper, mobile, dir, wd_old, wd, r.lo, r.hi);
    return sum;
  });
}

}  // namespace bkq
