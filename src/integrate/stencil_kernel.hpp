// The event engine's fast relaxation where the springs reach beyond j +- 1 (a lattice, a
// range- or power-coupled chain): the covered sites held in compact arrays with their
// springs as lists of partners (a run-time neighbour structure built once per call), and a
// scheme's Method advancing only the sliding ones (StencilLayout) instead of the general
// step's range loops and their per-site stencil look-ups.
//
// Each step does what the general path (engine/general_path.cpp) does, in the same order,
// so the events are the same bit for bit (tests/regression/test_stencil_path.cpp):
//  - the stages: at each stage point every sliding site's spring force, summed over its
//    springs in the stencil's order as ChainForces::spring_force sums them, and its
//    acceleration; then the Method's update of each sliding site. A stuck site's
//    acceleration and velocity are 0, so the general step leaves it where it is: here it
//    is not advanced, and its stage position is its position.
//  - the friction work: the step powers of the sliding sites, added up range by range in
//    RangePowerSum's places (a stuck site's term is 0 and changes no partial sum);
//  - the stick rule and the release test over the covered sites in site order
//    (settle_contacts), the forces from the chain's positions.
// A stuck site is tested again only when its force may have reached the threshold: the
// loop keeps, from its last test (it held), the room between a bound on |force| (the
// computed value plus the sum's rounding) and the threshold, and the drift: sum_p k_p |dx_p|
// over its sliding partners' moves since (its force is linear in their positions; its own
// position, the pad and the threshold do not move). While the drift is below the room a
// test would hold, so it is skipped, and the events are the same bit for bit. Room and drift
// are kept for the next call when nothing moved between the calls (the same event, no
// steps by other paths, the same time and substrate); otherwise the first step tests every
// stuck site.
//
// The loop returns after the first step at whose end a site broke loose, every site is
// stuck, a speed is not finite, the step budget ran out, or the engine refits its ranges
// (unless the refit keeps them: every covered site slides or has a sliding partner, and no
// site stuck); the caller then books the steps, and the next call rebuilds the structure.
// Only Crossing schemes, the pad held and no dashpots (the general path takes the rest).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "integrate/layouts.hpp"
#include "integrate/scheme.hpp"
#include "integrate/stencil_step.hpp"
#include "model/chain.hpp"
#include "model/stick.hpp"

namespace bkq {

// One spring of a site: partners l and r (r < 0: only l; a spring that reaches no site is
// left out), stiffness k.
struct StencilSpring {
  int l, r;
  double k;
};

struct StencilRelaxation {
  // Set by the caller.
  ChainState* state = nullptr;
  double* dissipated = nullptr;  // += half_dt_m * power, step by step
  double anchor = 0;             // the substrate (the pad held)
  SubstrateState sub;            // the frozen substrate
  double dt = 0, half_dt_m = 0;
  std::int64_t max_steps = 0;     // return after this many steps at most
  std::int64_t steps_before = 0;  // steps of the event before this call
  int refit_every = 1;            // the engine refits its ranges after every this many
  std::uint64_t event = 0;        // changes between events (ActiveSet::uncovers)

  // The structure (build()): the covered sites in order, each one's range and place in it
  // modulo 4 (RangePowerSum's), its springs (springs[begin[i], end[i]), global indices),
  // and whether the engine's refit would keep every covered site. Each site's springs are
  // listed once, the first time it is covered, and kept for the next calls.
  std::vector<int> site, range, place, begin, end;
  std::vector<StencilSpring> springs;
  std::vector<int> listed_begin, listed_end;  // by site; -1: not listed yet
  std::vector<unsigned char> marked;          // by covered site: slides or is a partner
  const ChainForces* listed_for = nullptr;
  bool refit_keeps = false;
  bool usable = false;  // every partner of a sliding site is covered
  // The structure of the covered ranges, from the state's stick flags.
  void build(const ChainForces& forces, Ranges ranges);

  // What happened.
  std::int64_t steps = 0;
  std::int64_t sliding_block_steps = 0;  // sliding sites at the end of each step, summed
  double max_speed = 0;                  // NaN if a speed became NaN
  int sliding = 0;                       // sliding sites after the last step
  std::vector<int> released;             // sites that broke loose then, in order

  // The kernel's scratch, kept between calls.
  std::vector<int> slot;  // site -> compact index, -1 elsewhere (size n)
  std::vector<double> w, v, x, y, cw, cv, u, y0, mobile, dir, a, magnitude, magnitude0;
  // A stuck site's room and drift (above; room -inf: test it, as for a sliding site).
  std::vector<double> room, drift, w0;
  // The last call's covered sites with their rooms and drifts at its end (compact, so that
  // nothing by site is touched beyond slot), and where it left the state.
  std::vector<int> end_site;
  std::vector<double> end_room, end_drift;
  const ChainState* end_state = nullptr;
  double end_t = 0, end_anchor = 0;
  std::int64_t end_steps = -1;
  std::uint64_t end_event = 0;
  std::vector<int> moving;  // compact indices of the sliding sites, in order
  std::vector<int> local_begin;
  std::vector<StencilSpring> local;  // the moving sites' springs in compact indices

  // Release tests of stuck sites taken and skipped by the bound (a study count).
  std::int64_t tests = 0, skipped = 0;
  // Tests only: each skipped test is taken anyway and compared with the bound.
  struct SkipCheck {
    std::int64_t broke = 0;       // skipped, but the test would have released the site
    std::int64_t over_bound = 0;  // |force| above the bound the skip relied on
    std::int64_t close = 0;       // skipped with less than a tenth of the room left
  };
  SkipCheck* check = nullptr;
};

// The springs of site j in the order ChainForces::neighbour_force sums them.
void append_site_springs(const ChainForces& forces, int j, std::vector<StencilSpring>& out);

namespace stencil_detail {

// sum_s k_s (x_l - x_j) [+ (x_r - x_j)]: neighbour_force's sum (a spring's first partner
// added to 0 is that partner's term; a spring that reaches no site adds k 0, which leaves
// the sum as it is, as does the 0 that starts it, so both are left out).
inline double spring_sum(const double* x, double xj, const StencilSpring* s,
                         const StencilSpring* end) {
  double f = 0;
  for (; s != end; ++s) {
    double d = x[s->l] - xj;
    if (s->r >= 0) d += x[s->r] - xj;
    f += s->k * d;
  }
  return f;
}

// spring_sum's f, the same bits, and scale += sum_s |k_s| (|x_l - x_j| [+ |x_r - x_j|]), which
// bounds the sum's rounding: |f - exact| <= (n + 2) 2^-53 scale over n springs.
inline double spring_sum_scaled(const double* x, double xj, const StencilSpring* s,
                                const StencilSpring* end, double& scale) {
  double f = 0, a = 0;
  for (; s != end; ++s) {
    const double dl = x[s->l] - xj;
    double d = dl, e = std::abs(dl);
    if (s->r >= 0) {
      const double dr = x[s->r] - xj;
      d += dr;
      e += std::abs(dr);
    }
    f += s->k * d;
    a += std::abs(s->k) * e;
  }
  scale += a;
  return f;
}

// The drift's own rounding (its sums, |dx| and k |dx|, each within 2^-52 of exact) for up
// to ~10^9 steps between tests, and the room's.
inline constexpr double kDriftGrow = 1 + 0x1p-20;

// The room below `threshold` of a force f computed over n springs with scale: a bound on
// the rounding of its computation (the spring sum and the pad's term: at most
// (n + 4) 2^-53 scale, taken four times over, which also covers the rounding of the bound's
// own arithmetic) added to |f|, over kDriftGrow. A drift below it cannot move f, computed
// again, above the threshold. Negative or NaN: none.
inline double force_room(double threshold, double f, double scale, int n) {
  return (threshold - (std::abs(f) + static_cast<double>(n + 4) * 0x1p-51 * scale)) / kDriftGrow;
}

// The sliding sites in compact arrays, advanced by a Method's stages.
template <class Round, class Law>
class StencilLayout {
 public:
  StencilLayout(const ChainForces& forces, const Law& law, StencilRelaxation& r)
      : forces_(forces), law_(law), r_(r), kp_(forces.params().k_p) {}

  bool velocity_dependent() const { return bkq::velocity_dependent(forces_.params(), false); }

  template <class Point, class Update, class Sum, class Earlier = NoSum>
  void stage(Point, double, Update&& update, const Sum&, const Earlier& = no_sum) {
    constexpr bool state_positions = Point::positions == Buf::W;
    StencilRelaxation& r = r_;
    const double* pos = state_positions ? r.w.data() : r.x.data();
    const double* vel = Point::velocities == Buf::V   ? r.v.data()
                        : Point::velocities == Buf::Y ? r.y.data()
                                                      : r.u.data();
    const int m = static_cast<int>(r.moving.size());
    const StencilSpring* local = r.local.data();
    const int* begin = r.local_begin.data();
    const double anchor = r.anchor;
    const SubstrateState sub = r.sub;
    // The first stage at the state reads each site's friction magnitude at its velocity,
    // which the loop keeps (the same value: acceleration() is acceleration_given() of it).
    const bool known = at_start_ && Point::velocities == Buf::V;
    at_start_ = false;
    for (int s = 0; s < m; ++s) {
      const int i = r.moving[s];
      const double xi = pos[i];
      const double f =
          spring_sum(pos, xi, local + begin[s], local + begin[s + 1]) - kp_ * (xi - anchor);
      const double magnitude = known ? r.magnitude[i] : law_.magnitude(vel[i]);
      r.a[s] = forces_.acceleration_given<Law, ForceTerms<true, false>, false>(f, magnitude, vel[i],
                                                                               r.dir[i], sub);
    }
    for (int s = 0; s < m; ++s) {
      const int i = r.moving[s];
      StageElement<typename Round::BlockRound> e{r.w[i], r.v[i],  r.x[i],  r.y[i], r.x[i],
                                                 r.y[i], r.cw[i], r.cv[i], r.u[i]};
      update(e, r.a[s]);
    }
  }
  void finish(double) {}
  // A step begins: r.magnitude holds the magnitudes at the state's velocities.
  void begin_step() { at_start_ = true; }

 private:
  bool at_start_ = false;
  const ChainForces& forces_;
  const Law& law_;
  StencilRelaxation& r_;
  double kp_;
};

// The sliding sites' springs in compact indices (every partner of a sliding site is
// covered), in r.local from r.local_begin.
inline void compact_springs(StencilRelaxation& r) {
  r.local.clear();
  r.local_begin.clear();
  for (const int i : r.moving) {
    r.local_begin.push_back(static_cast<int>(r.local.size()));
    for (int k = r.begin[i]; k < r.end[i]; ++k) {
      const StencilSpring& s = r.springs[k];
      r.local.push_back({r.slot[s.l], s.r >= 0 ? r.slot[s.r] : -1, s.k});
    }
  }
  r.local_begin.push_back(static_cast<int>(r.local.size()));
}

// Tests only: the skipped test of stuck site i taken anyway, and compared with the bound.
template <class Force>
void check_skip(StencilRelaxation& r, int i, Force& spring_force, const Friction& fr) {
  double scale = 0;
  const double f = spring_force(i, scale);
  if (fr.breaks(f)) ++r.check->broke;
  if (!(std::abs(f) <= fr.threshold - (r.room[i] - r.drift[i]))) ++r.check->over_bound;
  if (r.room[i] - r.drift[i] < 0.1 * r.room[i]) ++r.check->close;
}

template <class Method, class Law>
void stencil_steps(const ChainForces& forces, const Law law, StencilRelaxation& r) {
  ChainState& st = *r.state;
  const Friction& fr = forces.friction();
  const ModelParams& p = forces.params();
  const double damper = p.c_u / p.m_u, kp = p.k_p, anchor = r.anchor, dt = r.dt;
  const int c = static_cast<int>(r.site.size());
  for (std::vector<double>* b : {&r.w, &r.v, &r.x, &r.y, &r.cw, &r.cv, &r.u, &r.y0, &r.mobile,
                                 &r.dir, &r.a, &r.magnitude, &r.magnitude0, &r.w0})
    if (static_cast<int>(b->size()) < c) b->resize(c);
  r.room.resize(c);
  r.drift.resize(c);
  r.moving.clear();
  // Nothing moved since the last call ended: its rooms and drifts hold.
  const bool carry = r.end_state == &st && r.end_event == r.event && r.end_t == st.t &&
                     r.end_anchor == r.anchor && r.end_steps == r.steps_before;
  std::fill(r.room.begin(), r.room.begin() + c, -INFINITY);
  std::fill(r.drift.begin(), r.drift.begin() + c, 0.0);
  if (carry)
    for (std::size_t k = 0; k < r.end_site.size(); ++k) {
      const int j = r.end_site[k], i = r.slot[j];
      if (i >= 0 && st.mobile[j] == 0.0) {
        r.room[i] = r.end_room[k];
        r.drift[i] = r.end_drift[k];
      }
    }
  for (int i = 0; i < c; ++i) {
    const int j = r.site[i];
    r.w[i] = r.x[i] = st.w[j];
    r.v[i] = st.wd[j];
    r.mobile[i] = st.mobile[j];
    r.dir[i] = st.dir[j];
    if (r.mobile[i] != 0.0) {
      r.moving.push_back(i);
      r.magnitude[i] = law.magnitude(r.v[i]);
    }
  }
  compact_springs(r);
  double* w_all = st.w.data();
  // The spring force on covered site i from the chain's positions (spring_force's).
  // With scale (spring_sum_scaled's, the pad's term added) for the bound on its rounding.
  auto spring_force = [&](int i, double& scale) {
    const int j = r.site[i];
    const double wj = w_all[j];
    const double pad = wj - anchor;
    scale = std::abs(kp) * std::abs(pad);
    return spring_sum_scaled(w_all, wj, r.springs.data() + r.begin[i], r.springs.data() + r.end[i],
                             scale) -
           kp * pad;
  };
  const double threshold = fr.threshold;
  std::int64_t tests = 0, skipped = 0;
  double t = st.t, dissipated = *r.dissipated, max_speed = 0;
  std::int64_t steps = 0, sliding_block_steps = 0;
  int sliding = 0;
  bool stuck_in_call = false;
  r.released.clear();
  StencilLayout<typename Method::Round, Law> layout(forces, law, r);
  for (bool done = false; !done;) {
    const int m = static_cast<int>(r.moving.size());
    for (int s = 0; s < m; ++s) {
      const int i = r.moving[s];
      r.y0[i] = r.v[i];
      r.magnitude0[i] = r.magnitude[i];
      r.w0[i] = r.w[i];
    }
    layout.begin_step();
    Method::advance(layout, dt);
    t += dt;
    ++steps;
    // The forces below read the new positions; each partner of a sliding site gets k |dx|
    // per spring that reaches it (the stencils are symmetric: j's spring to i is i's to j).
    for (int s = 0; s < m; ++s) {
      const int i = r.moving[s];
      w_all[r.site[i]] = r.w[i];
      const double dx = std::abs(r.w[i] - r.w0[i]);
      for (int k = r.local_begin[s]; k < r.local_begin[s + 1]; ++k) {
        const StencilSpring& sp = r.local[k];
        const double d = std::abs(sp.k) * dx;
        r.drift[sp.l] += d;
        if (sp.r >= 0) r.drift[sp.r] += d;
      }
    }

    // dissipated_power's sum: range by range, in RangePowerSum's places.
    double power = 0;
    RangePowerSum part;
    int range = m > 0 ? r.range[r.moving[0]] : 0;
    for (const int i : r.moving) {
      if (r.range[i] != range) {
        power += part.total();
        part = RangePowerSum{};
        range = r.range[i];
      }
      r.magnitude[i] = law.magnitude(r.v[i]);
      part.add(r.place[i], step_power_given<Law::backslip>(r.magnitude0[i], r.y0[i], r.magnitude[i],
                                                           r.v[i], r.dir[i], damper));
    }
    power += part.total();
    dissipated += r.half_dt_m * power;

    // settle_contacts' rule over the covered sites in order.
    sliding = 0;
    for (int i = 0; i < c; ++i) {
      // A stuck site with room left (a sliding one has none; NaN: tested).
      if (r.drift[i] < r.room[i]) {
        ++skipped;
        if (r.check != nullptr) check_skip(r, i, spring_force, fr);
        continue;
      }
      const bool was_sliding = r.mobile[i] != 0.0;
      if (!was_sliding) ++tests;
      double f = 0, scale = 0;
      const stick::Outcome o =
          stick::settle_one(fr, true, r.mobile[i], r.dir[i], r.y0[i], r.v[i], [&] {
            f = spring_force(i, scale);
            return f;
          });
      if (!o.slides && !o.breaks) {
        // Stuck, its force tested (it held): the room starts again from it.
        r.room[i] = force_room(threshold, f, scale, r.end[i] - r.begin[i]);
        r.drift[i] = 0;
      } else if (o.breaks) {
        r.room[i] = -INFINITY;
      }
      const double y1 = r.v[i];
      r.v[i] = o.y;
      r.mobile[i] = o.mobile;
      r.dir[i] = o.dir;
      if (o.slides) {
        // The rule may have set the velocity to 0 (a crossing without backslip).
        if (o.y != y1 || o.y == 0.0) r.magnitude[i] = law.magnitude(o.y);
        ++sliding;
        raise_max_speed(max_speed, std::abs(o.y));
      } else if (o.breaks) {
        ++sliding;
        r.released.push_back(r.site[i]);
      } else if (was_sliding) {
        r.x[i] = r.w[i];  // stuck: its stage position is its position
        stuck_in_call = true;
      }
    }
    sliding_block_steps += sliding;
    const bool refit = (r.steps_before + steps) % r.refit_every == 0;
    done = sliding == 0 || !r.released.empty() || !std::isfinite(max_speed) ||
           steps >= r.max_steps || (refit && (stuck_in_call || !r.refit_keeps));
    if (!done && stuck_in_call) {
      // Sites stuck: the moving list and its springs lose them.
      r.moving.clear();
      for (int i = 0; i < c; ++i)
        if (r.mobile[i] != 0.0) r.moving.push_back(i);
      compact_springs(r);
    }
  }
  for (int i = 0; i < c; ++i) {
    const int j = r.site[i];
    st.w[j] = r.w[i];
    st.wd[j] = r.v[i];
    st.mobile[j] = r.mobile[i];
    st.dir[j] = r.dir[i];
  }
  r.end_site.assign(r.site.begin(), r.site.end());
  r.end_room.assign(r.room.begin(), r.room.begin() + c);
  r.end_drift.assign(r.drift.begin(), r.drift.begin() + c);
  r.end_state = &st;
  r.end_t = t;
  r.end_anchor = anchor;
  r.end_steps = r.steps_before + steps;
  r.end_event = r.event;
  st.t = t;
  *r.dissipated = dissipated;
  r.max_speed = max_speed;
  r.steps = steps;
  r.sliding_block_steps = sliding_block_steps;
  r.sliding = sliding;
  r.tests += tests;
  r.skipped += skipped;
}

}  // namespace stencil_detail

// The laws the stencil kernel is compiled for: those that drive events, but the table
// (which pays for its own look-ups); no block damper (the 1DOF model's single block).
template <class Law, class Terms>
inline constexpr bool kStencilKernel =
    Law::drives_events && !Terms::damper && !std::is_same_v<Law, law::Table>;

template <class Method>
bool run_stencil(const ChainForces& forces, StencilRelaxation& r) {
  return forces.with_switches([&]<class Law, class Terms>(const Law& law) {
    if constexpr (!kStencilKernel<Law, Terms>) {
      return false;
    } else {
      stencil_detail::stencil_steps<Method, Law>(forces, law, r);
      return true;
    }
  });
}

}  // namespace bkq
