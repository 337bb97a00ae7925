// The naive full-chain integration, as a program of its own: the yardstick that a whole
// `bkquake run` is timed against (bench/whole_run.sh). It reads a scene exactly as
// `bkquake run` does (the built-in default without SCENE, then --set overrides) and runs
// the same transient and recorded events with tests/support/reference_events: the loader scans
// every block for the next failure and each event steps every block of the chain with the
// scene's stepper (rk4 at dt = 0.01 by default) until all are stuck. It writes no files;
// it prints the events, the block-steps and the sum of the recorded moments, so a run that
// was optimised away would show.
//   build/naive_chain [SCENE] [--set section.key=value]...
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/scene_args.hpp"
#include "engine/initial_state.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "support/reference_events.hpp"

namespace {

int run_naive_chain(const bkq::Args& args) {
  bkq::Scene scene = bkq::scene_from_command_line(args);
  scene.validate();
  const bkq::Settings settings = bkq::settings_from_scene(scene);
  const bkq::ChainForces forces(settings.model);
  const auto stepper = bkq::stepper_of(settings.integrator, settings.model.n);
  bkq::check_time_step(*stepper, settings.model, settings.integrator.dt);
  bkq::ReferenceEventEngine engine(
      forces, *stepper, settings.integrator.dt,
      bkq::initial_state(forces, settings.run.seed, settings.run.initial_disorder, true));
  engine.max_steps_per_event = settings.run.max_steps_per_event;
  for (std::int64_t i = 0; i < settings.run.transient_events; ++i) engine.next_event();
  const std::int64_t block_steps0 = engine.block_steps;
  double moments = 0;
  for (std::int64_t i = 0; i < settings.run.events; ++i) moments += engine.next_event().moment;
  std::printf("naive_chain: %lld events, %lld block-steps recorded, sum of moments %.17g\n",
              static_cast<long long>(settings.run.events),
              static_cast<long long>(engine.block_steps - block_steps0), moments);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const bkq::Command naive{"naive_chain",
                             "the naive full-chain integration",
                             "[SCENE]",
                             -1,
                             "Runs the scene's events stepping every block of the chain.\n",
                             {bkq::scene_set_option()},
                             run_naive_chain};
    return bkq::run_command(naive, std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "naive_chain: %s\n", e.what());
    return 2;
  }
}
