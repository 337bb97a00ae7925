// The fused step over held ranges (layouts.hpp, HeldRangeLayout) with the pad moving: the
// BK–Pad event engine's common situation, every range ending in stuck blocks, the
// substrate frozen, and the pad swinging. Each stage is one fused pass per range
// (accelerations at the stage point with the anchor s + pad's stage position, the scheme's
// update, and the stage's term of the pad's sum of positions) and then the pad's update,
// exactly as ChainLayout does them: the same operations in the same order, so the result
// is step()'s bit for bit (tests/unit/test_pad_held.cpp). The stuck end blocks are left
// out: their accelerations, their updates and their terms of the pad's sum are exactly
// zero (their velocities are 0, their stage positions their positions).
#pragma once

#include <type_traits>
#include <utility>

#include "integrate/layouts.hpp"

namespace bkq {

namespace layout_detail {

// One fused pass over the inner blocks [lo, hi) (fused_stage's), which also adds each
// block's term of the pad's sum, after its update and in block order, to `total`.
template <class Law, class Terms, class B, bool AtState, class Update, class Sum>
[[gnu::noinline]] double fused_pad_stage(const ChainForces& forces, const HeldInput& in, int lo,
                                         int hi, double* __restrict w, double* __restrict wd,
                                         const double* __restrict x_in,
                                         const double* __restrict v_in, double* __restrict xo,
                                         double* __restrict yo, double* __restrict cw,
                                         double* __restrict cv, double* __restrict u,
                                         Update& update, const Sum& sum, double total) {
  const Law& law = forces.law<Law>();
  const double* x = AtState ? w : x_in;
  const double* v = AtState ? wd : v_in;
  const double* __restrict mobile = in.mobile;
  const double* __restrict dir = in.dir;
  const double anchor = in.anchor;
  const SubstrateState frozen = in.frozen;
  for (int j = lo; j < hi; ++j) {
    const double a =
        mobile[j] * forces.acceleration<Law, Terms, false>(
                        law, forces.interior_force<Terms>(x[j - 1], x[j], x[j + 1], anchor), v[j],
                        dir[j], frozen);
    StageElement<B> e{w[j], wd[j], x[j], v[j], xo[j], yo[j], cw[j], cv[j], u[j]};
    update(e, a);
    if constexpr (!std::is_same_v<Sum, NoSum>) total += sum.term(e);
  }
  return total;
}

}  // namespace layout_detail

template <class Round, class Law, class Terms>
class HeldPadLayout {
 public:
  HeldPadLayout(const ChainForces& forces, SubstrateState frozen, ChainState& st, Ranges ranges,
                ExplicitScratch& s)
      : forces_(forces), frozen_(frozen), st_(st), ranges_(ranges), s_(s) {
    x_in_ = s.x2.data();
    y_in_ = s.y2.data();
    x_out_ = s.x.data();
    y_out_ = s.y.data();
    // The end blocks are stuck: their stage positions are their positions.
    for (const Range& r : ranges) {
      s.x[r.lo] = s.x2[r.lo] = st.w[r.lo];
      s.x[r.hi - 1] = s.x2[r.hi - 1] = st.w[r.hi - 1];
    }
  }

  bool velocity_dependent() const { return bkq::velocity_dependent(forces_.params(), true); }

  template <class Point, class Update, class Sum>
  void stage(Point p, double time_offset, Update&& update, const Sum& sum) {
    stage(p, time_offset, update, sum, no_sum);
  }
  // With `earlier` (ChainLayout's meaning): the sum of the stage point this stage evaluates
  // at, which the stage before left out, its terms read before this stage's update.
  template <class Point, class Update, class Sum, class Earlier>
  void stage(Point, double, Update&& update, const Sum& sum, const Earlier& earlier) {
    static_assert(
        Point::positions == Buf::W ? Point::velocities == Buf::V : Point::velocities == Buf::Y,
        "a held range evaluates at the state or at the last stage point");
    constexpr bool at_state = Point::positions == Buf::W;
    if constexpr (!std::is_same_v<Earlier, NoSum>) {
      double earlier_total = 0;
      for (const Range& r : ranges_)
        for (int j = r.lo + 1; j < r.hi - 1; ++j) {
          StageElement<typename Round::BlockRound> e{st_.w[j], st_.wd[j], x_in_[j],
                                                     y_in_[j], x_in_[j],  y_in_[j],
                                                     s_.cw[j], s_.cv[j],  s_.u[j]};
          earlier_total += earlier.term(e);
        }
      sum_ = st_.sum_w + earlier.scale * earlier_total;
    }
    const double x_at = at_state ? st_.x : x_;
    const double xd_at = at_state ? st_.xd : xd_;
    const double ax = forces_.pad_acceleration(x_at, xd_at, at_state ? st_.sum_w : sum_, frozen_.s);
    // The anchor as ChainLayout forms it (substrate + the pad's stage position).
    const HeldInput in{st_.mobile.data(), st_.dir.data(), frozen_.s + x_at, frozen_};
    double total = 0;
    for (const Range& r : ranges_)
      total = layout_detail::fused_pad_stage<Law, Terms, typename Round::BlockRound, at_state>(
          forces_, in, r.lo + 1, r.hi - 1, st_.w.data(), st_.wd.data(), x_in_, y_in_, x_out_,
          y_out_, s_.cw.data(), s_.cv.data(), s_.u.data(), update, sum, total);
    std::swap(x_in_, x_out_);
    std::swap(y_in_, y_out_);
    StageElement<typename Round::PadRound> e{st_.x, st_.xd, x_, xd_, x_, xd_, cx_, cxd_, xu_};
    update(e, ax);
    if constexpr (!std::is_same_v<Sum, NoSum>) {
      if (sum.into_state)
        st_.sum_w += sum.scale * total;
      else
        sum_ = st_.sum_w + sum.scale * total;
    }
  }
  void finish(double h) { st_.t += h; }

 private:
  const ChainForces& forces_;
  SubstrateState frozen_;
  ChainState& st_;
  Ranges ranges_;
  ExplicitScratch& s_;
  double *x_in_, *y_in_, *x_out_, *y_out_;
  // The pad's stage point, accumulators and spare velocity, and the stage's sum of w.
  double x_ = 0, xd_ = 0, cx_ = 0, cxd_ = 0, xu_ = 0, sum_ = 0;
};

// One step of a fusable Method over held ranges with the pad moving.
template <class Method>
void step_held_with_pad(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                        Ranges ranges, ExplicitScratch& scratch) {
  static_assert(Method::fusable);
  const SubstrateState frozen = sub.at(st.t);
  forces.with_switches([&]<class Law, class Terms>(const Law&) {
    HeldPadLayout<typename Method::Round, Law, Terms> layout(forces, frozen, st, ranges, scratch);
    Method::advance(layout, dt);
  });
}

}  // namespace bkq
