// The state layouts an explicit scheme (integrate/scheme.hpp) advances. Each supplies the
// loop over its elements and the evaluation of the accelerations; the scheme supplies the
// stage formulas, so every layout runs the same operations and they agree bit for bit.
//   ChainLayout      the blocks in a set of ranges and the pad (when it moves), with the
//                    substrate at each stage's time: the general step.
//   HeldRangeLayout  the interior blocks of ranges whose end blocks are stuck, the
//                    substrate frozen, and the pad where it moves: each stage is one fused
//                    pass per range (accelerations and updates together), the stage points
//                    double-buffered; only for schemes whose stages never write the
//                    positions they are evaluated at (Method::fusable).
//   ClusterLayout    the interior entries of a fixed-size cluster (integrate/cluster.hpp),
//                    held in registers, and the pad where it moves.
#pragma once

#include <algorithm>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <vector>

#include "integrate/block_window.hpp"
#include "integrate/scheme.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"

namespace bkq {

// Scratch of the explicit steppers, indexed by block over a window of the chain that
// fit() makes hold the ranges of the step (integrate/block_window.hpp: what the entries
// hold is left over, finite): stage positions and velocities (two sets, for double
// buffering), accelerations, accumulators and the spare velocity.
struct ExplicitScratch {
  // One of the arrays: data()[j] (or [j]) is block j's entry.
  class Array {
   public:
    Array(BlockWindow& window, int k) : window_(window), k_(k) {}
    double* data() const { return window_.data(k_); }
    double& operator[](int j) const { return data()[j]; }

   private:
    BlockWindow& window_;
    int k_;
  };
  ExplicitScratch() = default;
  ExplicitScratch(const ExplicitScratch&) = delete;
  ExplicitScratch& operator=(const ExplicitScratch&) = delete;
  void fit(const ChainForces& forces, Ranges ranges) {
    window.fit(ranges, forces.n(), forces.wraps(), forces.reach());
  }

  BlockWindow window{8};
  Array x{window, 0}, y{window, 1}, x2{window, 2}, y2{window, 3}, a{window, 4}, cw{window, 5},
      cv{window, 6}, u{window, 7};
};

// Does the scene have a velocity-dependent force (verlet's closing kick needs it)?
inline bool velocity_dependent(const ModelParams& p, bool pad_moves) {
  return !law_traits(p.law).frictionless || p.c_u != 0 || (pad_moves && p.c_p != 0) ||
         p.rayleigh_alpha != 0 || p.rayleigh_beta != 0;
}

namespace layout_detail {

// One stage's pass over the blocks of the ranges at accelerations a, range by range:
// the pad's sum `earlier` (terms read before the update), the scheme's update, then the
// pad's sum `sum` (terms read after it), each sum its own loop: a sum in block order is a
// chain of dependent additions, which would keep the update loop from vectorising. Each term reads
// only its own block's entries, so taking a range's sums beside its update is the same as taking
// them over all ranges at once. The totals go to totals[0] (sum) and totals[1] (earlier).
// Out of line with restrict parameters: inlined into the stage, GCC no longer knows the
// buffers are apart and the loops stay scalar.
template <class B, class Update, class Sum, class Earlier>
[[gnu::always_inline]] inline void chain_pass_body(Ranges ranges, bool pad, double* __restrict w,
                                                   double* __restrict wd, double* __restrict x,
                                                   double* __restrict y, double* __restrict cw,
                                                   double* __restrict cv, double* __restrict u,
                                                   const double* __restrict a, Update& update,
                                                   const Sum& sum, const Earlier& earlier,
                                                   double* __restrict totals) {
  constexpr bool joint = !std::is_same_v<Earlier, NoSum>;
  constexpr bool summed = !std::is_same_v<Sum, NoSum>;
  auto element = [&](int j) {
    return StageElement<B>{w[j], wd[j], x[j], y[j], x[j], y[j], cw[j], cv[j], u[j]};
  };
  double total = 0, earlier_total = 0;
  for (const Range& r : ranges) {
    if constexpr (joint) {
      if (pad)
        for (int j = r.lo; j < r.hi; ++j) earlier_total += earlier.term(element(j));
    }
    // The copies some updates make (cw = v) stay in this loop instead of becoming calls
    // to memcpy (the optimize attribute above): the ranges are short.
    for (int j = r.lo; j < r.hi; ++j) {
      StageElement<B> e{w[j], wd[j], x[j], y[j], x[j], y[j], cw[j], cv[j], u[j]};
      update(e, a[j]);
    }
    if constexpr (summed) {
      if (pad)
        for (int j = r.lo; j < r.hi; ++j) total += sum.term(element(j));
    }
  }
  totals[0] = total;
  totals[1] = earlier_total;
}

template <class B, class Update, class Sum, class Earlier>
[[gnu::noinline, gnu::optimize("no-tree-loop-distribute-patterns")]] void chain_pass(
    Ranges ranges, bool pad, double* __restrict w, double* __restrict wd, double* __restrict x,
    double* __restrict y, double* __restrict cw, double* __restrict cv, double* __restrict u,
    const double* __restrict a, Update& update, const Sum& sum, const Earlier& earlier,
    double* __restrict totals) {
  chain_pass_body<B>(ranges, pad, w, wd, x, y, cw, cv, u, a, update, sum, earlier, totals);
}

// Blocks per piece of a fused pass: small enough that a piece's entries stay in the
// first-level cache between its accelerations and its update, and that the pad's chains
// of additions overlap the next piece's vector work.
inline constexpr int kPiece = 64;

// The update of blocks [lo, hi) (at most kPiece + 1 of them) at accelerations a, with the
// pad's terms: `earlier`'s read before each block's update, `sum`'s after it. The terms
// go to small arrays in the vectorised update loop and are added up afterwards, in block
// order, both chains side by side.
template <class B, class Update, class Sum, class Earlier>
[[gnu::always_inline]] inline void fused_piece(int lo, int hi, bool pad, double* __restrict w,
                                               double* __restrict wd, double* __restrict x,
                                               double* __restrict y, double* __restrict cw,
                                               double* __restrict cv, double* __restrict u,
                                               const double* __restrict a, Update& update,
                                               const Sum& sum, const Earlier& earlier,
                                               double& total, double& earlier_total) {
  constexpr bool joint = !std::is_same_v<Earlier, NoSum>;
  constexpr bool summed = !std::is_same_v<Sum, NoSum>;
  if constexpr (joint || summed) {
    if (pad) {
      double te[kPiece + 1], ts[kPiece + 1];
      for (int j = lo; j < hi; ++j) {
        StageElement<B> e{w[j], wd[j], x[j], y[j], x[j], y[j], cw[j], cv[j], u[j]};
        if constexpr (joint) te[j - lo] = earlier.term(e);
        update(e, a[j]);
        if constexpr (summed) ts[j - lo] = sum.term(e);
      }
      for (int k = 0; k < hi - lo; ++k) {
        if constexpr (joint) earlier_total += te[k];
        if constexpr (summed) total += ts[k];
      }
      return;
    }
  }
  for (int j = lo; j < hi; ++j) {
    StageElement<B> e{w[j], wd[j], x[j], y[j], x[j], y[j], cw[j], cv[j], u[j]};
    update(e, a[j]);
  }
}

// One stage over a single range [lo, hi) in pieces, each piece's accelerations
// (`accel(lo, hi)` fills a[lo..hi)) followed by its updates, so the entries are read from
// the first-level cache and the pad's sums run beside the vector work. A block's update
// may change the positions its neighbours' accelerations read, so the updates lag the
// accelerations by one block, and the last block's acceleration (which, on a periodic
// chain, reads the first block) is taken before any update. Each block gets the same
// acceleration and update as in the two-pass form, and the sums the same terms in the
// same order, so the results agree bit for bit.
template <class B, class Accel, class Update, class Sum, class Earlier>
[[gnu::noinline, gnu::optimize("no-tree-loop-distribute-patterns")]] void fused_chain_pass(
    Range r, bool pad, const Accel& accel, double* __restrict w, double* __restrict wd,
    double* __restrict x, double* __restrict y, double* __restrict cw, double* __restrict cv,
    double* __restrict u, double* __restrict a, Update& update, const Sum& sum,
    const Earlier& earlier, double* __restrict totals) {
  double total = 0, earlier_total = 0;
  const int last = r.hi - 1;
  accel(last, r.hi);
  int done = r.lo;
  for (int p = r.lo; p < last;) {
    const int q = std::min(p + kPiece, last);
    accel(p, q);
    const int upto = q == last ? r.hi : q - 1;
    fused_piece<B>(done, upto, pad, w, wd, x, y, cw, cv, u, a, update, sum, earlier, total,
                   earlier_total);
    done = upto;
    p = q;
  }
  if (done < r.hi)
    fused_piece<B>(done, r.hi, pad, w, wd, x, y, cw, cv, u, a, update, sum, earlier, total,
                   earlier_total);
  totals[0] = total;
  totals[1] = earlier_total;
}

}  // namespace layout_detail

// What a layout with a moving pad keeps for it besides the state: the pad's stage point,
// accumulators and spare velocity, and the stage's sum of block positions.
struct PadStage {
  double x = 0, xd = 0, cx = 0, cxd = 0, xu = 0, sum = 0;
};

// A stage's end for the moving pad (x, xd, sum_w its state): its update at acceleration ax,
// then its sum of positions from `total`, the blocks' sum of `sum`'s terms.
template <class Round, class Update, class Sum>
inline void pad_stage_end(Update& update, double ax, double& x, double& xd, double& sum_w,
                          PadStage& ps, const Sum& sum, double total) {
  StageElement<typename Round::PadRound> e{x, xd, ps.x, ps.xd, ps.x, ps.xd, ps.cx, ps.cxd, ps.xu};
  update(e, ax);
  if constexpr (!std::is_same_v<Sum, NoSum>) {
    if (sum.into_state)
      sum_w += sum.scale * total;
    else
      ps.sum = sum_w + sum.scale * total;
  }
}

template <class Round, bool Fusable = false>
class ChainLayout {
 public:
  static constexpr int kShortRange = 8;
  // A single range this long takes the fused pass in pieces (the continuous driver's
  // whole chain); shorter ones, the event engine's, the two-pass form, which costs them
  // less. Schemes whose stages never write the positions they read (Method::fusable)
  // gain from it from one piece on, the others from two (docs/validation/performance.md).
  static constexpr int kLongRange = (Fusable ? 1 : 2) * layout_detail::kPiece;
  ChainLayout(const ChainForces& forces, const Substrate& sub, ChainState& st, Ranges ranges,
              ExplicitScratch& s)
      : forces_(forces),
        sub_(sub),
        st_(st),
        ranges_(ranges),
        s_(s),
        pad_(forces.params().pad_moves()) {}

  bool velocity_dependent() const { return bkq::velocity_dependent(forces_.params(), pad_); }

  template <class Point, class Update, class Sum>
  void stage(Point p, double time_offset, Update&& update, const Sum& sum) {
    stage(p, time_offset, update, sum, no_sum);
  }
  // With `earlier`, the sum of the stage before (which that stage left out), taken in one
  // pass with this stage's: its terms are read before this stage's update, this stage's
  // own after it; the scheme vouches that the earlier terms do not change in between. The
  // pad's acceleration at this stage point then follows the pass.
  template <class Point, class Update, class Sum, class Earlier>
  void stage(Point, double time_offset, Update&& update, const Sum& sum, const Earlier& earlier) {
    constexpr bool state_positions = Point::positions == Buf::W;
    constexpr bool joint = !std::is_same_v<Earlier, NoSum>;
    const SubstrateState sub = sub_.at(st_.t + time_offset);
    const double* w_at = state_positions ? st_.w.data() : s_.x.data();
    const double* v_at = pick(Point::velocities, st_.wd.data(), s_.y.data(), s_.u.data());
    const double x_at = state_positions ? st_.x : ps_.x;
    const double xd_at = pick(Point::velocities, st_.xd, ps_.xd, ps_.xu);
    const double anchor = sub.s + (pad_ ? x_at : 0.0);
    const double anchor_v = sub.v + (pad_ ? xd_at : 0.0);
    // Rayleigh damping on the pad needs the blocks' velocities at the stage point (taken
    // before the pass changes them); blocks outside the ranges are at rest (w' = 0).
    double sum_wd = 0;
    if (pad_ && forces_.rayleigh())
      for (const Range& r : ranges_)
        for (int j = r.lo; j < r.hi; ++j) sum_wd += v_at[j];
    auto pad_acceleration = [&] {
      const double sum_w = state_positions ? st_.sum_w : ps_.sum;
      return pad_ ? forces_.pad_acceleration(x_at, xd_at, sum_w, sub.s, sum_wd, sub.v) : 0.0;
    };
    // Before the pass where it can (its division overlaps the loops).
    double ax = joint ? 0.0 : pad_acceleration();
    double totals[2];
    auto accel = [&](int lo, int hi) {
      const Range piece{lo, hi};
      forces_.block_accelerations(w_at, v_at, st_.mobile.data(), st_.dir.data(), anchor, anchor_v,
                                  sub, Ranges(&piece, 1), s_.a.data());
    };
    // The fused pass lags the updates by one block: only kernels that read j +- 1 may take it.
    if (ranges_.size() == 1 && ranges_[0].hi - ranges_[0].lo >= kLongRange &&
        !forces_.general_kernel()) {
      layout_detail::fused_chain_pass<typename Round::BlockRound>(
          ranges_[0], pad_, accel, st_.w.data(), st_.wd.data(), s_.x.data(), s_.y.data(),
          s_.cw.data(), s_.cv.data(), s_.u.data(), s_.a.data(), update, sum, earlier, totals);
    } else {
      forces_.block_accelerations(w_at, v_at, st_.mobile.data(), st_.dir.data(), anchor, anchor_v,
                                  sub, ranges_, s_.a.data());
      if (ranges_.size() == 1)
        layout_detail::chain_pass_body<typename Round::BlockRound>(
            ranges_, pad_, st_.w.data(), st_.wd.data(), s_.x.data(), s_.y.data(), s_.cw.data(),
            s_.cv.data(), s_.u.data(), s_.a.data(), update, sum, earlier, totals);
      else
        layout_detail::chain_pass<typename Round::BlockRound>(
            ranges_, pad_, st_.w.data(), st_.wd.data(), s_.x.data(), s_.y.data(), s_.cw.data(),
            s_.cv.data(), s_.u.data(), s_.a.data(), update, sum, earlier, totals);
    }
    if (!pad_) return;
    if constexpr (joint) {
      ps_.sum = st_.sum_w + earlier.scale * totals[1];
      ax = pad_acceleration();
    }
    pad_stage_end<Round>(update, ax, st_.x, st_.xd, st_.sum_w, ps_, sum, totals[0]);
  }
  void finish(double h) { st_.t += h; }

 private:
  template <class T>
  static T pick(Buf b, T v, T y, T u) {
    return b == Buf::V ? v : b == Buf::Y ? y : u;
  }

  const ChainForces& forces_;
  const Substrate& sub_;
  ChainState& st_;
  Ranges ranges_;
  ExplicitScratch& s_;
  bool pad_;
  PadStage ps_;
};

// What a held range's fused stages read besides the stage point.
struct HeldInput {
  const double* mobile;
  const double* dir;
  double anchor;
  SubstrateState frozen;
};

namespace layout_detail {

// One fused pass over the inner blocks [lo, hi): the acceleration at the stage point
// (x, v) as the chain's kernel forms it, the scheme's update, and (unless Sum is NoSum)
// the block's term of the pad's sum, added to `total` in block order; returns the total.
// Everything is a restrict parameter, so the compiler knows the stores cannot change what
// the pass reads and vectorises it.
// At the state (AtState) the stage point is (w, wd) itself and x, v are not read.
// Kept out of line: inlined into the scheme's advance(), the restrict qualifiers no
// longer tell the compiler the arrays are apart and the pass stays scalar. Not cloned:
// GCC's clone without the unused sum (IPA-SRA) checked the arrays against the forces at
// run time instead of loading the force constants once.
template <class Law, class Terms, class B, bool AtState, class Update, class Sum>
[[gnu::noinline, gnu::noclone]] double fused_stage(
    const ChainForces& forces, const HeldInput& in, int lo, int hi, double* __restrict w,
    double* __restrict wd, const double* __restrict x_in, const double* __restrict v_in,
    double* __restrict xo, double* __restrict yo, double* __restrict cw, double* __restrict cv,
    double* __restrict u, Update& update, const Sum& sum, double total) {
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

template <bool Summed, class Sum>
const auto& sum_if(const Sum& sum) {
  if constexpr (Summed)
    return sum;
  else
    return no_sum;
}

}  // namespace layout_detail

// The interior blocks of ranges whose end blocks are stuck, the substrate frozen, and with
// Pad the pad moving: each stage is one fused pass per range (accelerations at the anchor
// substrate + the pad's stage position, the update, the pad's sum's terms) and then the
// pad's update, as ChainLayout does them, so the result is step()'s bit for bit. The stuck
// end blocks are left out: their accelerations, updates and terms of the pad's sum are
// exactly zero (their velocities are 0, their stage positions their positions). Without
// the pad the pad's parts compile away.
template <class Round, class Law, class Terms, bool Pad>
class HeldRangeLayout {
 public:
  HeldRangeLayout(const ChainForces& forces, SubstrateState frozen, ChainState& st, Ranges ranges,
                  ExplicitScratch& s)
      : forces_(forces),
        st_(st),
        ranges_(ranges),
        w_(st.w.data()),
        wd_(st.wd.data()),
        x_in_(s.x2.data()),
        y_in_(s.y2.data()),
        x_out_(s.x.data()),
        y_out_(s.y.data()),
        cw_(s.cw.data()),
        cv_(s.cv.data()),
        u_(s.u.data()),
        // The anchor as ChainLayout forms it (substrate + held pad at 0; stage() adds the
        // moving pad's stage position).
        in_{st.mobile.data(), st.dir.data(), frozen.s + 0.0, frozen} {
    // The end blocks are stuck: their stage positions are their positions.
    for (const Range& r : ranges) {
      x_out_[r.lo] = x_in_[r.lo] = w_[r.lo];
      x_out_[r.hi - 1] = x_in_[r.hi - 1] = w_[r.hi - 1];
    }
  }

  bool velocity_dependent() const { return bkq::velocity_dependent(forces_.params(), Pad); }

  // With `earlier` (ChainLayout's meaning): the sum of the stage point this stage evaluates
  // at, which the stage before left out, its terms read before this stage's update.
  template <class Point, class Update, class Sum, class Earlier = NoSum>
  void stage(Point, double, Update&& update, const Sum& sum, const Earlier& earlier = no_sum) {
    static_assert(
        Point::positions == Buf::W ? Point::velocities == Buf::V : Point::velocities == Buf::Y,
        "a held range evaluates at the state or at the last stage point");
    constexpr bool at_state = Point::positions == Buf::W;
    constexpr bool summed = Pad && !std::is_same_v<Sum, NoSum>;
    if constexpr (Pad && !std::is_same_v<Earlier, NoSum>) {
      double earlier_total = 0;
      for (const Range& r : ranges_)
        for (int j = r.lo + 1; j < r.hi - 1; ++j) {
          StageElement<typename Round::BlockRound> e{w_[j],    wd_[j], x_in_[j], y_in_[j], x_in_[j],
                                                     y_in_[j], cw_[j], cv_[j],   u_[j]};
          earlier_total += earlier.term(e);
        }
      ps_.sum = st_.sum_w + earlier.scale * earlier_total;
    }
    const double x_at = at_state ? st_.x : ps_.x;
    const double xd_at = at_state ? st_.xd : ps_.xd;
    double ax = 0;
    if constexpr (Pad) {
      ax = forces_.pad_acceleration(x_at, xd_at, at_state ? st_.sum_w : ps_.sum, in_.frozen.s);
      in_.anchor = in_.frozen.s + x_at;  // ChainLayout's anchor
    }
    // Without the pad the blocks' pass adds no terms.
    const auto& block_sum = layout_detail::sum_if<summed>(sum);
    double total = 0;
    for (const Range& r : ranges_)
      total = layout_detail::fused_stage<Law, Terms, typename Round::BlockRound, at_state>(
          forces_, in_, r.lo + 1, r.hi - 1, w_, wd_, x_in_, y_in_, x_out_, y_out_, cw_, cv_, u_,
          update, block_sum, total);
    std::swap(x_in_, x_out_);
    std::swap(y_in_, y_out_);
    if constexpr (Pad) pad_stage_end<Round>(update, ax, st_.x, st_.xd, st_.sum_w, ps_, sum, total);
  }
  void finish(double) {}

 private:
  const ChainForces& forces_;
  ChainState& st_;
  Ranges ranges_;
  double *w_, *wd_, *x_in_, *y_in_, *x_out_, *y_out_, *cw_, *cv_, *u_;
  HeldInput in_;
  PadStage ps_;
};

// The pad's state while a cluster runs with the pad moving (written back at the end).
struct PadStageState {
  double x, xd, sum_w;
};

// `acceleration(x, v, anchor, a)` sets a[1..K] at stage positions x and velocities v; on
// entry `a` holds the accelerations at the state (the first stage's, which the cluster
// loop has already formed). With Pad the pad is one more element, advanced and summed as
// ChainLayout does it, and the anchor is `base` (the substrate) plus the pad's stage
// position; without, `base` is the anchor and the pad's parts compile away.
template <class Round, class Acceleration, class Array, bool Pad>
class ClusterLayout {
 public:
  static constexpr int K = static_cast<int>(std::tuple_size_v<Array>) - 2;

  ClusterLayout(const ChainForces& forces, double base, const Acceleration& acceleration, Array& w,
                Array& v, Array& a, PadStageState& pad, bool velocity_dependent)
      : forces_(forces),
        base_(base),
        acceleration_(acceleration),
        w_(w),
        v_(v),
        a_(a),
        x_(w),
        y_(v),
        cw_(w),
        cv_(w),
        u_(v),
        pad_(pad),
        velocity_dependent_(velocity_dependent) {}

  bool velocity_dependent() const { return velocity_dependent_; }

  template <class Point, class Update, class Sum, class Earlier = NoSum>
  void stage(Point, double, Update&& update, const Sum& sum, const Earlier& earlier = no_sum) {
    constexpr bool state_positions = Point::positions == Buf::W;
    constexpr bool at_state = state_positions && Point::velocities == Buf::V;
    constexpr bool joint = Pad && !std::is_same_v<Earlier, NoSum>;
    constexpr bool summed = Pad && !std::is_same_v<Sum, NoSum>;
    const double x_at = state_positions ? pad_.x : ps_.x;
    const double xd_at = pick<Point::velocities>(pad_.xd, ps_.xd, ps_.xu);
    if (!at_state || evaluated_)
      acceleration_(state_positions ? w_ : x_, pick<Point::velocities>(v_, y_, u_),
                    Pad ? base_ + x_at : base_, a_);
    evaluated_ = true;
    auto pad_acceleration = [&] {
      return forces_.pad_acceleration(x_at, xd_at, state_positions ? pad_.sum_w : ps_.sum, base_);
    };
    double ax = !Pad || joint ? 0.0 : pad_acceleration();
    auto element = [&](int i) {
      return StageElement<typename Round::BlockRound>{w_[i], v_[i],  x_[i],  y_[i], x_[i],
                                                      y_[i], cw_[i], cv_[i], u_[i]};
    };
    double total = 0, earlier_total = 0;
    // ChainLayout's order: `earlier`'s terms before the update, `sum`'s after it.
    if constexpr (joint) {
      for (int i = 1; i <= K; ++i) earlier_total += earlier.term(element(i));
    }
    for (int i = 1; i <= K; ++i) {
      auto e = element(i);
      update(e, a_[i]);
    }
    if constexpr (summed) {
      for (int i = 1; i <= K; ++i) total += sum.term(element(i));
    }
    if constexpr (Pad) {
      if constexpr (joint) {
        ps_.sum = pad_.sum_w + earlier.scale * earlier_total;
        ax = pad_acceleration();
      }
      pad_stage_end<Round>(update, ax, pad_.x, pad_.xd, pad_.sum_w, ps_, sum, total);
    }
  }
  void finish(double) {}

 private:
  template <Buf B, class T>
  static T& pick(T& v, T& y, T& u) {
    if constexpr (B == Buf::V)
      return v;
    else if constexpr (B == Buf::Y)
      return y;
    else
      return u;
  }

  const ChainForces& forces_;
  double base_;
  const Acceleration& acceleration_;
  Array &w_, &v_, &a_;
  Array x_, y_, cw_, cv_, u_;
  PadStageState& pad_;
  PadStage ps_;
  bool velocity_dependent_;
  bool evaluated_ = false;
};

}  // namespace bkq
