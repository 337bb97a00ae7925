// The event benchmarks' common set-up: the carlson-langer scene (l = 10, alpha = 2.5,
// sigma = 0.01, clst91) with N blocks, RK4 at dt = 0.01, seed 7, and an event engine
// taken past its transient (twenty events per block, ten loading cycles' worth); the
// transitions at the step (today's default) or located inside it.
#pragma once

#include <memory>
#include <string>

#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "integrate/located.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"

namespace bkq::bench {

inline Scene carlson_langer_scene(int n, const char* kind) {
  Scene scene;
  scene.set("model.blocks", std::to_string(n));
  scene.set("model.kind", kind);
  scene.validate();
  return scene;
}

struct CarlsonLangerEvents {
  static constexpr double kDt = 0.01;
  // replay_starts: EventEngine::lone_slip_path, set before the transient; located:
  // integrator.transitions = located (the rk4 stepper wrapped by with_located_transitions).
  explicit CarlsonLangerEvents(int n, const char* kind = "bk", bool replay_starts = true,
                               bool located = false)
      : p(model_from_scene(carlson_langer_scene(n, kind))),
        forces(p),
        stepper(located ? with_located_transitions(make_stepper("rk4", n), n)
                        : make_stepper("rk4", n)),
        engine(forces, *stepper, kDt, initial_state(forces, 7, 0.01, true)) {
    engine.lone_slip_path = replay_starts;
    for (int i = 0; i < 20 * n; ++i) engine.next_event();
  }
  ModelParams p;
  ChainForces forces;
  std::unique_ptr<Stepper> stepper;
  EventEngine engine;
};

}  // namespace bkq::bench
