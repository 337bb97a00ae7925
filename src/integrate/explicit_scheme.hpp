// The stepper of an explicit Crossing scheme, from its Method (integrate/scheme.hpp): the
// general step, the fused step over held ranges and the cluster form are the method's one
// advance() run over the three layouts of integrate/layouts.hpp. A new explicit scheme
// is a Method in its own header, instantiated in its .cpp, and one line in registry.cpp.
#pragma once

#include <algorithm>
#include <memory>
#include <string_view>

#include "integrate/cluster.hpp"
#include "integrate/layouts.hpp"
#include "integrate/stencil_step.hpp"
#include "integrate/stepper.hpp"

namespace bkq {

// Method's cluster form (integrate/cluster.hpp), the scheme's traits().cluster_kernel:
// compiled once, with the scheme, in the scheme's .cpp (extern in its header).
template <class Method>
bool relax_cluster(const ChainForces& forces, ClusterRelaxation& r) {
  return forces.params().pad_moves() ? run_cluster<Method, true>(forces, r)
                                     : run_cluster<Method, false>(forces, r);
}

template <class Method>
class ExplicitScheme final : public Stepper {
 public:
  explicit ExplicitScheme(int) {}
  // Transitions at the step (the Crossing rule), locatable, on every force kernel, with the
  // cluster form and the stencil form; fused over held ranges where the Method's stages
  // allow it.
  static constexpr SchemeTraits kTraits{.stick_rule = StickRule::Crossing,
                                        .locatable = true,
                                        .general_kernels = true,
                                        .cluster_kernel = &relax_cluster<Method>,
                                        .fused_kernels = Method::fusable,
                                        .stencil_kernel = &run_stencil<Method>};
  std::string_view name() const override { return Method::name; }
  std::unique_ptr<Stepper> fresh(int n_blocks) const override {
    return std::make_unique<ExplicitScheme>(n_blocks);
  }
  const SchemeTraits& traits() const override { return kTraits; }
  int order() const override { return Method::order; }
  double stability_constant() const override { return Method::stability_constant; }
  double damped_stability_constant() const override {
    if constexpr (requires { Method::damped_stability_constant; })
      return Method::damped_stability_constant;
    else
      return Method::stability_constant;
  }

  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override {
    if (!separable(forces, ranges)) return step_together(forces, sub, st, dt, ranges);
    // Ranges far apart: one range at a time, each from the same time (the ranges do not
    // interact, so this is the same step bit for bit), so that the scratch holds one range,
    // not the span of all.
    const double t = st.t;
    for (const Range& r : ranges) {
      st.t = t;
      step_together(forces, sub, st, dt, Ranges(&r, 1));
    }
  }

  void step_held(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                 Ranges ranges) override {
    if constexpr (!Method::fusable)
      step(forces, sub, st, dt, ranges);
    else if (forces.params().pad_moves())
      step_held_ranges<true>(forces, sub, st, dt, ranges);
    else
      step_held_ranges<false>(forces, sub, st, dt, ranges);
  }

 private:
  // Whether the ranges are better stepped one by one, and can be: their span is much wider
  // than the blocks in them, no moving pad couples them, no range reaches across a periodic
  // chain's ends to another, and they are not rows of a lattice (springs across strike
  // couple them).
  static bool separable(const ChainForces& forces, Ranges ranges) {
    if (ranges.size() < 2 || forces.lattice()) return false;
    int lo = ranges.front().lo, hi = ranges.front().hi, blocks = 0;
    for (const Range& r : ranges) lo = std::min(lo, r.lo), hi = std::max(hi, r.hi);
    for (const Range& r : ranges) blocks += r.hi - r.lo;
    const ModelParams& p = forces.params();
    return hi - lo > 4 * blocks + 256 && !p.pad_moves() &&
           !(p.boundary == Boundary::Periodic && (lo == 0 || hi == forces.n()));
  }
  // step_held's fused step: with the pad moving all ranges in one layout (the pad couples
  // them), without it one range at a time (the scratch then holds one range). Not compiled
  // where the event engine never asks (laws that drive no events, the 1DOF damper): there
  // the general step, which is the same step, is taken.
  template <bool Pad>
  void step_held_ranges(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                        Ranges ranges) {
    const SubstrateState frozen = sub.at(st.t);
    const bool fused_step = forces.with_switches([&]<class Law, class Terms>(const Law&) {
      if constexpr (!Law::drives_events || Terms::damper) {
        return false;
      } else {
        auto fused = [&](Ranges rs) {
          scratch_.fit(forces, rs);
          HeldRangeLayout<typename Method::Round, Law, Terms, Pad> layout(forces, frozen, st, rs,
                                                                          scratch_);
          Method::advance(layout, dt);
        };
        if constexpr (Pad)
          fused(ranges);
        else
          for (const Range& r : ranges) fused(Ranges(&r, 1));
        return true;
      }
    });
    if (fused_step)
      st.t += dt;
    else
      step(forces, sub, st, dt, ranges);
  }
  void step_together(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                     Ranges ranges) {
    scratch_.fit(forces, ranges);
    ChainLayout<typename Method::Round, Method::fusable> layout(forces, sub, st, ranges, scratch_);
    Method::advance(layout, dt);
  }

  ExplicitScratch scratch_;
};

}  // namespace bkq
