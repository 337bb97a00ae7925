// The vocabulary in which each explicit Crossing scheme (rk2, rk4, verlet) is written once,
// over any state layout (integrate/layouts.hpp: the whole chain with its pad, a held range
// stepped with fused stages, a fixed-size cluster).
//
// A scheme is a `Method`: a struct with its name, order, stability constant, rounding
// and a template `advance(layout, h)` that calls, once per stage,
//   layout.stage(point, time_offset, update, sum)
// The layout evaluates the accelerations at `point` (which positions and velocities,
// at time t + time_offset) and calls update(e, a) for every element it advances: each
// block, and the pad where it moves. `e` is a StageElement, the element's entries in the
// layout's buffers; update holds the stage's formulas, so they are written once for every
// layout. `sum` says how the pad's sum of block positions follows the stage (only a layout
// with a moving pad keeps it). The layouts and the stepper wrapper are in layouts.hpp and
// explicit_scheme.hpp.
#pragma once

#include <cmath>

namespace bkq {

// Rounding policies of a stage formula y + a x: one rounding (the blocks of rk4, whose
// one-block stages are a chain of dependent operations) or two (everything else).
struct Fused {
  static double axpy(double a, double x, double y) { return std::fma(a, x, y); }
};
struct Plain {
  static double axpy(double a, double x, double y) { return y + a * x; }
};
// Which policy the blocks and the pad of a scheme use.
template <class Block, class Pad>
struct Rounding {
  using BlockRound = Block;
  using PadRound = Pad;
};

// One element's entries in a layout's buffers: the state (w, v), the stage point the
// accelerations were evaluated at (x, y), where this stage's point goes (xo, yo: the same
// entries as x, y except where the layout double-buffers), two accumulators (cw, cv) and
// a spare velocity (u).
template <class Round>
struct StageElement {
  // y + a x with this element's rounding: the stage formulas write e.axpy(a, x, y).
  static double axpy(double a, double x, double y) { return Round::axpy(a, x, y); }
  double& w;
  double& v;
  const double& x;
  const double& y;
  double& xo;
  double& yo;
  double& cw;
  double& cv;
  double& u;
};

// The buffers a stage point takes its positions (W state, X stage) and velocities
// (V state, Y stage, U spare) from.
enum class Buf { W, V, X, Y, U };
template <Buf P, Buf Q>
struct At {
  static constexpr Buf positions = P;
  static constexpr Buf velocities = Q;
};
inline constexpr At<Buf::W, Buf::V> at_state{};
inline constexpr At<Buf::X, Buf::Y> at_stage{};
inline constexpr At<Buf::W, Buf::Y> at_state_positions{};
inline constexpr At<Buf::W, Buf::U> at_state_positions_spare{};

// How the pad's sum of block positions follows a stage, for a layout with a moving pad:
// with S the sum of term(e) over the blocks (after the update, in block order),
//   into the stage point: sum_stage = sum_w + scale S;   into the state: sum_w += scale S.
template <class Term>
struct PadSum {
  double scale;
  Term term;
  bool into_state;
};
template <class Term>
PadSum<Term> sum_to_stage(double scale, Term term) {
  return {scale, term, false};
}
template <class Term>
PadSum<Term> sum_to_state(double scale, Term term) {
  return {scale, term, true};
}
// A stage that moves no position.
struct NoSum {};
inline constexpr NoSum no_sum{};

}  // namespace bkq
