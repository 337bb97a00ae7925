// The continuous-run loop; see continuous_run.hpp. The step count is fixed up front, so
// the end time does not depend on the rounding of t += dt; a sample is taken whenever t
// reaches the next multiple of output.every.
#include "app/continuous_run.hpp"

#include <chrono>
#include <cmath>

#include "app/observers/catalog.hpp"
#include "app/observers/histogram.hpp"
#include "app/observers/progress.hpp"
#include "app/observers/segments.hpp"
#include "app/observers/summary.hpp"
#include "app/observers/timeseries.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/continuous.hpp"
#include "engine/initial_state.hpp"
#include "io/output.hpp"

namespace bkq {

namespace {

// The scene's outputs for a continuous run, in notification order (the summary, which
// marks the run finished, after every file).
void attach_observers(Observers& obs, const RunRequest& req, const Settings& settings,
                      const OutputFolder& out) {
  obs.attach<TimeSeriesWriter>(out.path("timeseries.csv"));
  if (const char* catalog = catalog_file_name(settings.output.catalog))
    obs.attach<CatalogWriter>(settings.output.catalog, out.path(catalog), req.scene);
  if (settings.output.blocks)
    obs.attach<BlockTrajectories>(out.path("blocks.csv"), settings.model.n);
  obs.attach<PadFrictionStats>();
  const auto& hist =
      obs.attach<HistogramWriter>(settings.stats.bin_width, out.path("histogram.csv"));
  attach_segment_stats(obs, settings, out);
  obs.attach<ContinuousSummary>(req.scene, settings, out, hist.histogram(), obs);
  if (!req.quiet) obs.attach<ProgressLine>();
  for (RunObserver* o : req.observers) obs.attach_ref(*o);
}

Sample sample_of(const ContinuousDriver& driver) {
  const ChainState& st = driver.state();
  const SubstrateState sub = driver.substrate();
  return {{st.t, sub.v, sub.s, st.x, st.xd, driver.pad_friction(), driver.sliding()}, driver};
}

}  // namespace

int run_continuous(const RunRequest& req, const Settings& settings, const OutputFolder& out,
                   const ChainForces& forces, Stepper& stepper) {
  const double dt = settings.integrator.dt;
  const double duration = settings.run.duration;
  const double every = settings.output.every;
  ContinuousDriver driver(
      forces, stepper, substrate_of(settings.drive),
      initial_state(forces, settings.run.seed, settings.run.initial_disorder, false), dt);
  Observers observers;
  attach_observers(observers, req, settings, out);

  const auto steps = static_cast<std::int64_t>(std::llround(std::ceil(duration / dt - 1e-9)));
  const auto t0 = std::chrono::steady_clock::now();
  observers.start();
  observers.phase({"time", 0.0, duration});
  double next_out = 0;
  std::int64_t episodes = 0;
  for (std::int64_t i = 0; i <= steps; ++i) {
    if (driver.state().t >= next_out - 1e-9 * dt) {
      observers.sample(sample_of(driver));
      next_out += every;
    }
    if (i == steps) break;
    driver.step();
    if (auto e = driver.finished_episode()) {
      ++episodes;
      observers.event(*e);
    }
    if (!std::isfinite(driver.state().x) || !std::isfinite(driver.state().w[0])) {
      std::string msg = "non-finite state at time ";
      msg += format_real(driver.state().t);
      msg += ": the integration is unstable (reduce integrator.dt)";
      throw Error(msg);
    }
    if (observers.wants_steps()) observers.step({i + 1, driver});
    observers.advance({driver.state().t, episodes});
  }
  observers.phase_end({driver.state().t, episodes});

  RunEnd end;
  end.events = episodes;
  end.steps = steps;
  end.blocks = forces.params().n;
  end.total_load = driver.substrate().s;
  end.duration = driver.state().t;
  end.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  observers.end(end);
  return 0;
}

}  // namespace bkq
