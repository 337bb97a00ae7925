// Where located transitions spend their steps: the carlson-langer scene (N = 100, l = 10,
// alpha = 2.5, sigma = 0.01, clst91) with rk4 and integrator.transitions = located at each
// dt given, past a transient of 2000 events, then EVENTS events counted. Prints per event:
// the engine's steps, those replayed from the lone-slip record, those run in the cluster
// kernels and those on the general path; the transitions the located stepper located and
// the scheme steps it took for them (attempts, steps to the instants, Newton steps, the
// rest of each step); the share of events the record finished and of events of more than
// one block. The first row is today's default for comparison: rk4 at dt = 0.01 with
// transitions at the step (no located transitions, no scheme steps for them). Counts, not
// times: they do not depend on the machine.
//   build/located_counts [EVENTS=50000] [DT...]   (default DT: 0.04 0.03 0.02 0.01)
// (the step-mode row is marked "0.01s").
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "integrate/located.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"

int main(int argc, char** argv) {
  using namespace bkq;
  const long events = argc > 1 ? std::atol(argv[1]) : 50000;
  std::vector<double> dts;
  for (int i = 2; i < argc; ++i) dts.push_back(std::atof(argv[i]));
  if (dts.empty()) dts = {0.04, 0.03, 0.02, 0.01};
  if (events < 1) {
    std::fprintf(stderr, "usage: located_counts [EVENTS=50000] [DT...]\n");
    return 2;
  }
  Scene scene;
  scene.validate();
  const ModelParams p = model_from_scene(scene);
  const ChainForces forces(p);
  std::printf("%7s %8s %8s %8s %8s %11s %12s %9s %9s\n", "dt", "steps", "replayed", "cluster",
              "general", "transitions", "scheme steps", "finished", "multi");
  dts.insert(dts.begin(), -0.01);  // negative: at the step
  for (double signed_dt : dts) {
    const bool at_step = signed_dt < 0;
    const double dt = at_step ? -signed_dt : signed_dt;
    auto stepper = at_step ? make_stepper("rk4", p.n)
                           : with_located_transitions(make_stepper("rk4", p.n), p.n);
    check_time_step(*stepper, p, dt);
    const auto* located = dynamic_cast<const LocatedTransitions*>(stepper.get());
    EventEngine engine(forces, *stepper, dt, initial_state(forces, 7, 0.01, true));
    for (int i = 0; i < 2000; ++i) engine.next_event();
    const EngineCounters c0 = engine.counters();
    const auto cluster0 = engine.cluster_steps().all;
    const auto lone0 = engine.lone_slip_starts();
    const auto transitions0 = located ? located->located_transitions() : 0;
    const auto scheme0 = located ? located->scheme_steps() : 0;
    long multi = 0;
    for (long i = 0; i < events; ++i) multi += engine.next_event().blocks > 1;
    const double n = static_cast<double>(events);
    const double steps = static_cast<double>(engine.counters().steps - c0.steps) / n;
    const double replayed = static_cast<double>(engine.lone_slip_starts().steps - lone0.steps) / n;
    const double cluster = static_cast<double>(engine.cluster_steps().all - cluster0) / n;
    const double transitions =
        located ? static_cast<double>(located->located_transitions() - transitions0) / n : 0.0;
    const double scheme =
        located ? static_cast<double>(located->scheme_steps() - scheme0) / n : 0.0;
    std::printf("%6g%s %8.2f %8.2f %8.2f %8.2f %11.2f %12.2f %9.3f %9.3f\n", dt,
                at_step ? "s" : " ", steps, replayed, cluster, steps - replayed - cluster,
                transitions, scheme,
                static_cast<double>(engine.lone_slip_starts().finished - lone0.finished) / n,
                static_cast<double>(multi) / n);
  }
  return 0;
}
