// The theta-method (theta = 1/2) with set-valued friction: velocity-level Moreau–Jean
// time stepping (seed 004 §3.3; Jean 1999). Keyword `theta`.
//
// Scheme. With h = dt and b = h/2, every block j in the ranges and the pad obey
//   m (v+ - v) = b [L(q+, v+, t+h) + L(q, v, t)] + b (r+ + r),   q+ = q + b (v + v+),
// where L is everything but friction (neighbour and pulling springs, the 1DOF damper
// c_u, the substrate's position, speed and acceleration; chain.hpp) and r, r+ are the
// friction forces at the two ends of the step. The linear part is the trapezoidal rule:
// substituting q+ gives a linear system in v+ that is tridiagonal over each contiguous
// segment of the ranges (cyclic when a periodic chain is advanced whole: Sherman–Morrison),
// bordered by the pad's row; the pad is eliminated by a Schur complement, so one solve
// costs O(blocks in the ranges). Blocks outside the ranges are held: they enter only
// through the springs to their neighbours.
//
// Friction. r is known from the start of the step: -m phi(v) for a sliding block, and
// for a stuck one the reaction that held it, -L projected on the admissible set. r+ comes
// from the set-valued law at the end of the step:
//   sliding (v+ != 0):  r+ = -m phi(v+), phi velocity-weakening (friction.hpp);
//   stuck   (v+ == 0):  friction holds the block's force at the end of the step, f+ =
//                       L(q+, 0, t+h), with a reaction in [-F0 m, F0 m] (thesis, cl89)
//                       or [-F0 m, inf) (clst91: friction may push a block forward
//                       without limit, so it never slides backwards).
// For a block stuck throughout, r+ = -f+ exactly; for one that stops within the step r+
// also absorbs its remaining momentum (the impulse of Moreau–Jean), so the stick test is
// on f+, the reaction it needs from then on. Row j reads D_j v+_j - b r+_j = c_j, with
// D_j = m + b c_u + b^2 (k_p + k_c #neighbours) and c_j known from the start of the step
// and the neighbours' and the pad's new velocities; sliding in direction e has a speed
// > 0 iff e c_j > b m F0 (1 - sigma) (the kinetic level; thesis/clst91, F0 for cl89).
// Between the kinetic level and the static threshold both sticking and sliding solve the
// law; the block's state at the start of the step settles it:
//   - a block stuck at the start stays stuck while friction can hold f+ (static friction
//     holds it); above the threshold it breaks inside this step and slides the way it is
//     pulled (mobile = 1, dir set), so a block breaks only above F0;
//   - a block sliding in direction d keeps sliding while its sliding solution keeps
//     d v+ > 0; if that would reach or cross zero it sticks when friction can hold f+ —
//     in particular whenever f+ lies in the band (1 - sigma) F0 .. F0 — and otherwise
//     slides back (backslip laws; never clst91).
// When friction cannot hold f+ but the step's momentum allows no sliding speed the way the
// block is pulled (the pull reversed while it was stopping), the block is left stuck for
// this step with a force beyond the threshold and breaks loose at the next step (the
// engine's settle_contacts releases it first). Where the discrete contact problem has two
// solutions (a block at the threshold whose breaking drags a sliding neighbour that pulls
// it over), the active set and the Gauss–Seidel fallback may pick different ones; both
// satisfy the law.
// Stick is exact: a stuck block ends the step with v+ = 0 exactly (mobile = 0, wd = 0)
// and does not move while it stays stuck; there is no threshold velocity and no
// chattering. The stepper applies the whole rule itself (StickRule::Projection).
//
// Contact solver. The coupled problem is solved by an active-set iteration that is
// Newton's method on the velocity-weakening friction at the same time: guess every
// block's state (stuck, or sliding with phi linearised about its current speed), solve
// the linear system, re-decide each block from c_j and f+ by the rule above, re-linearise,
// repeat until no state changes and every sliding speed has converged (s |dv| <= 1e-10,
// s the weakening rate: friction then within ~1e-10 of itself). The factorisation of the
// linear system is kept while its blocks' states, the ranges and dt stay the same: later
// iterations and steps only substitute, with the change of the friction slopes carried on
// the right-hand side (a chord step; refactored after three of them without settling).
// So a step in a smooth phase costs one or two substitutions, O(range) without divisions,
// and each stick/slip change a refactorisation. If the iteration has not settled after
// set_max_active_set_iterations() rounds (default 50) it falls back to projected
// (nonlinear) Gauss–Seidel: each block solves its scalar problem exactly in turn, the pad
// after each sweep, to a relative change of 1e-14; the system is diagonally dominant, so
// that converges.
//
// Order. The linear part and the friction are both trapezoidal (friction is implicit,
// iterated to convergence, not lagged), so smooth phases are second order; observed 2.00
// on the frictionless tests and on a sliding block with weakening friction, a damper and
// an accelerating substrate (tests/numeric/test_theta.cpp). A stick or slip transition
// is resolved within its step: the release or re-stick happens at a step boundary, which
// costs O(dt^2) in position per transition (at a turning point at most a dt^2/8, a the
// deceleration), so across transitions the scheme is first order like every fixed-step
// scheme (stepper.hpp).
//
// Stability. None on the linear part: the trapezoidal rule is A-stable and conserves the
// energy of an undamped linear chain exactly (to rounding) at any dt, so
// stability_constant() is HUGE_VAL. Velocity-weakening friction is negative damping of
// rate at most F0/v_c; the sliding speed is unique (and Newton converges) only for
// dt < 2 v_c/F0, which step() checks (Carlson–Langer alpha = 2.5: dt < 0.4).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "integrate/stepper.hpp"

namespace bkq {

class Theta final : public Stepper {
 public:
  explicit Theta(int n_blocks);
  std::string_view name() const override { return "theta"; }
  int order() const override { return 2; }
  double stability_constant() const override { return HUGE_VAL; }
  StickRule stick_rule() const override { return StickRule::Projection; }
  // No linear limit; under velocity-weakening friction dt must stay below 2 v_c/F0.
  TimeStepLimit time_step_limit(const ModelParams& p) const override;
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override;

  // Active-set rounds before falling back to projected Gauss–Seidel (0: Gauss–Seidel only).
  void set_max_active_set_iterations(int k) { max_active_set_ = k; }

 private:
  // A contiguous run of advanced blocks lo, lo+1, ... (len of them, indices mod n for a
  // periodic chain); cyclic when it is a whole periodic chain.
  struct Segment {
    int lo = 0, len = 0;
    bool cyclic = false;
    bool operator==(const Segment&) const = default;
  };

  void resize(int n);
  void build_segments(const ModelParams& p, Ranges ranges);
  void prepare(const ChainForces& forces, const Substrate& sub, const ChainState& st, double dt);
  bool solve_active_set();
  void solve_gauss_seidel();
  void solve_linear(bool refactor);
  void solve_segment(const Segment& g, bool refactor, double& sum_y);
  void finish(ChainState& st, double dt);

  // Row j's right-hand side c_j and the block's force at the end of the step if it is
  // stuck then (what friction must hold), given the current neighbour and pad velocities.
  struct Load {
    double c, f;
  };
  Load load(int j) const;
  // The block's state at the end of the step (0 stuck, +-1 sliding that way).
  int decide(int j, Load l) const;
  // The speed a > 0 of block j sliding in direction d: D a + b m |phi|(a) = d c.
  double slide_speed(int j, double c, int d) const;

  int block(const Segment& g, int i) const { return g.lo + i < n_ ? g.lo + i : g.lo + i - n_; }
  // Sum of the new velocities of block j's neighbours (held blocks count as 0).
  double neighbour_velocities(int j) const;

  template <class F>
  void for_each_block(F&& f) const {
    for (const Segment& g : segments_)
      for (int i = 0; i < g.len; ++i) f(block(g, i));
  }

  int n_ = 0;
  int max_active_set_ = 50;
  std::vector<Segment> segments_;

  // Per block (indexed by block number; v0_ and vn_ are zero outside the ranges between
  // steps, so neighbour sums over them see held blocks at rest).
  std::vector<double> v0_;          // velocity at the start of the step
  std::vector<double> vn_;          // iterate of the velocity at the end
  std::vector<double> impulse0_;    // m v + b (L + r) at the start of the step
  std::vector<double> force_pred_;  // L at the end with the new velocities left out
  std::vector<double> diag0_;       // D_j
  std::vector<double> a_hat_;       // sliding speed the friction is linearised about
  // The factorisation of the linear system (kept across iterations and steps while the
  // matrix stays the same but for the friction slopes gamma_f it was made with): pad
  // column z = T^-1 e, Thomas factors, cyclic correction q = A^-1 u.
  std::vector<double> z_, cp_, inv_, q_, gamma_f_, diag_f_;
  std::vector<std::int8_t> status_f_;
  std::vector<Segment> segments_f_;
  bool factored_ = false;
  double link_f_ = 0, pad_col_f_ = 0, pad_diag_f_ = 0, sum_z_ = 0, sm_ratio_ = 0, sm_denom_ = 1;
  std::vector<std::int8_t> start_;   // state at the start: 0 stuck, +-1 sliding
  std::vector<std::int8_t> status_;  // state at the end (current guess)

  // Per step.
  double m_ = 1, b_ = 0;
  double kc_ = 0, kp_ = 0;
  double link_ = 0;  // b^2 k_c, a row's coupling to a neighbour (doubled for a periodic pair)
  double thr_ = 0, k0_ = 0, s_ = 0;
  bool backslip_ = true, frictionless_ = false, pad_ = false, periodic_ = false,
       neighbours_ = false;
  double pad_diag_ = 1, pad_rhs_ = 0, pad_col_ = 0, xdn_ = 0;
};

}  // namespace bkq
