// The stepper of an explicit Crossing scheme, from its Method (integrate/scheme.hpp): the
// general step, the fused step over held ranges and the cluster form are the method's one
// advance() run over the three layouts of integrate/layouts.hpp. A new explicit scheme
// is a Method in its own header, instantiated in its .cpp, and one line in registry.cpp.
#pragma once

#include <string_view>

#include "integrate/cluster.hpp"
#include "integrate/layouts.hpp"
#include "integrate/stepper.hpp"

namespace bkq {

template <class Method>
class ExplicitScheme final : public Stepper {
 public:
  explicit ExplicitScheme(int) {}
  std::string_view name() const override { return Method::name; }
  int order() const override { return Method::order; }
  double stability_constant() const override { return Method::stability_constant; }

  void step(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override {
    scratch_.fit(forces, ranges);
    ChainLayout<typename Method::Round> layout(forces, sub, st, ranges, scratch_);
    Method::advance(layout, dt);
  }

  void step_held(const ChainForces& forces, const Substrate& sub, ChainState& st, double dt,
                 Ranges ranges) override {
    if constexpr (!Method::fusable) {
      step(forces, sub, st, dt, ranges);
    } else {
      scratch_.fit(forces, ranges);
      const SubstrateState frozen = sub.at(st.t);
      // The anchor as the general step forms it (substrate + held pad at 0).
      const HeldInput in{st.mobile.data(), st.dir.data(), frozen.s + 0.0, frozen};
      forces.with_switches([&]<class Law, class Terms>(const Law&) {
        for (const Range& r : ranges) {
          HeldRangeLayout<typename Method::Round, Law, Terms> layout(forces, in, r, st, scratch_);
          Method::advance(layout, dt);
        }
      });
      st.t += dt;
    }
  }

  bool relax_cluster(const ChainForces& forces, ClusterRelaxation& r) const override {
    const bool velocity_dependent = bkq::velocity_dependent(forces.params(), false);
    return run_cluster(
        forces, r,
        [velocity_dependent](const auto& acceleration, auto& w, auto& v, auto& a, double h) {
          ClusterLayout<typename Method::Round, std::remove_cvref_t<decltype(acceleration)>,
                        std::remove_reference_t<decltype(w)>>
              layout(acceleration, w, v, a, velocity_dependent);
          Method::advance(layout, h);
        });
  }

 private:
  ExplicitScratch scratch_;
};

}  // namespace bkq
