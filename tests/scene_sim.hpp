// Test helper: a scene built from key/value settings, and the model, stepper and event
// engine set up from it exactly the way `bkquake run` does (dt checked against the
// stepper's stability limit, the seeded initial state). Header-only.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "integrate/located.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "model/parameters.hpp"

namespace bkq::test {

using Settings = std::vector<std::pair<std::string, std::string>>;

inline Scene make_scene(const Settings& settings) {
  Scene scene;
  for (const auto& [k, v] : settings) scene.set(k, v);
  scene.validate();
  return scene;
}

struct Sim {
  explicit Sim(const Scene& scene)
      : p(model_from_scene(scene)),
        forces(p),
        stepper(with_transitions(scene, make_stepper(scene.choice("integrator.scheme"), p.n,
                                                     scene.real("integrator.tolerance")))),
        engine(forces, *stepper, checked_dt(scene),
               initial_state(forces, static_cast<std::uint64_t>(scene.integer("run.seed")),
                             scene.real("run.initial_disorder"), true)) {}
  explicit Sim(const Settings& settings) : Sim(make_scene(settings)) {}
  double checked_dt(const Scene& scene) const {
    const double dt = scene.real("integrator.dt");
    check_time_step(*stepper, p, dt);
    return dt;
  }
  // integrator.transitions as the run applies it (io/settings.cpp, stepper_of).
  std::unique_ptr<Stepper> with_transitions(const Scene& scene, std::unique_ptr<Stepper> s) const {
    if (scene.applies("integrator.transitions") &&
        scene.choice("integrator.transitions") == "located")
      return with_located_transitions(std::move(s), p.n);
    return s;
  }
  void run(int events) {
    for (int i = 0; i < events; ++i) engine.next_event();
  }

  ModelParams p;
  ChainForces forces;
  std::unique_ptr<Stepper> stepper;
  EventEngine engine;
};

// Sum of the spring forces on all blocks (neighbour springs cancel with free ends).
inline double total_spring_force(const Sim& sim) {
  const ChainState& st = sim.engine.state();
  const double anchor = st.s + (sim.p.pad_moves() ? st.x : 0.0);
  double f = 0;
  for (int j = 0; j < sim.p.n; ++j) f += sim.forces.spring_force(st.w.data(), j, anchor);
  return f;
}

}  // namespace bkq::test
