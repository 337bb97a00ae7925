// The theta-method with set-valued friction: velocity-level Moreau–Jean time stepping
// (Sinou, Chiello & Charroyer 2019 §3.3; Jean 1999). Keyword `theta`, theta in [1/2, 1]
// (integrator.theta, default 1/2: trapezoidal). Implicit in the springs, the pad and the friction;
// one tridiagonal solve per contact iteration. Order 2 in smooth phases at theta = 1/2 (1
// otherwise), 1 across stick transitions. Stability: none on the linear part (A-stable;
// theta > 1/2 damps, theta = 1/2 conserves an undamped chain's energy); under weakening
// friction dt < v_c/(theta F0) (unique sliding speed), checked.
// Stick rule: Projection, exact (v+ = 0, no threshold velocity). The scheme, the friction
// rule, the contact solver and the order: docs/explanation/integrators.md, "The θ-method".
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "integrate/stepper.hpp"

namespace bkq {

class Theta final : public Stepper, public CarriedState {
 public:
  explicit Theta(int n_blocks);
  // Transitions projected inside its step, on chains of nearest-neighbour springs.
  static constexpr SchemeTraits kTraits{.stick_rule = StickRule::Projection};
  std::string_view name() const override { return "theta"; }
  std::unique_ptr<Stepper> fresh(int n_blocks) const override;
  const SchemeTraits& traits() const override { return kTraits; }
  int order() const override { return theta_ == 0.5 ? 2 : 1; }
  double stability_constant() const override { return HUGE_VAL; }
  // No linear limit; under velocity-weakening friction dt must stay below 2 v_c/F0.
  TimeStepLimit time_step_limit(const ModelParams& p) const override;
  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override;
  // Its part: the factorisation kept across steps (and what it was made of).
  CarriedState* carried() override { return this; }
  std::vector<double> save() const override;
  void restore(std::span<const double> s) override;

  // The implicit weight theta in [1/2, 1] (1/2 by default).
  void set_theta(double theta) { theta_ = theta; }
  double theta() const { return theta_; }

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
  double theta_ = 0.5;
  double ratio_ = 1;  // (1 - theta)/theta: the explicit weight over the implicit one
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
  double bb_ = 0;  // b + beta_K: the weight of the new neighbour and pad velocities in a load
  double kc_ = 0, kp_ = 0;
  double link_ = 0;  // b^2 k_c, a row's coupling to a neighbour (doubled for a periodic pair)
  double thr_ = 0, k0_ = 0, s_ = 0;
  bool backslip_ = true, frictionless_ = false, pad_ = false, periodic_ = false,
       neighbours_ = false;
  double pad_diag_ = 1, pad_rhs_ = 0, pad_col_ = 0, xdn_ = 0;
};

}  // namespace bkq
