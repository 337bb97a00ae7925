// From an effective scene to a finished output folder: builds the model, the stepper and
// the driver the scene asks for, streams the outputs, and writes the provenance
// (scene.ini first, summary.json last, so a folder with summary.json is a finished run).
#include "engine/run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "bkquake_version.hpp"
#include "engine/continuous.hpp"
#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "engine/progress.hpp"
#include "integrate/stepper.hpp"
#include "io/catalog.hpp"
#include "io/error.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "model/chain.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

Json provenance_json(const Scene& scene, const std::string& mode) {
  Json j = Json::object();
  j.set("version", kVersion);
  j.set("git_revision", kGitRevision);
  j.set("seed", static_cast<std::int64_t>(scene.integer("run.seed")));
  j.set("scene", scene.origin);
  j.set("scene_hash", std::to_string(scene.hash()));
  j.set("mode", mode);
  j.set("written", utc_now_iso());
  return j;
}

Substrate substrate_from_scene(const Scene& scene) {
  const std::string& schedule = scene.choice("drive.schedule");
  if (schedule == "steps")
    return Substrate::steps(scene.real("drive.speed"), scene.real("drive.step_increment"),
                            scene.real("drive.step_interval"));
  if (schedule == "ramp")
    return Substrate::ramp(scene.real("drive.ramp_from"), scene.real("drive.ramp_to"),
                           scene.real("drive.ramp_duration"));
  return Substrate::constant(scene.real("drive.speed"));
}

int run_events(const RunRequest& req, const OutputFolder& out, const ChainForces& forces, Stepper& stepper,
               double dt) {
  const Scene& scene = req.scene;
  const ModelParams& p = forces.params();
  EventEngine engine(forces, stepper, dt,
                     initial_state(forces, static_cast<std::uint64_t>(scene.integer("run.seed")),
                                   scene.real("run.initial_disorder"), true));
  const auto t0 = Clock::now();
  const std::int64_t transient = scene.integer("run.transient_events");
  const std::int64_t events = scene.integer("run.events");
  {
    Progress progress(req.quiet, "transient events", static_cast<double>(transient));
    for (std::int64_t i = 0; i < transient; ++i) {
      engine.next_event();
      progress.update(static_cast<double>(i + 1));
    }
    progress.finish(static_cast<double>(transient));
  }

  MagnitudeHistogram hist(scene.real("stats.bin_width"));
  CsvStream catalog(out.path("catalog.csv"), catalog_header());
  const double load0 = engine.load();
  const auto t1 = Clock::now();
  const EngineCounters c0 = engine.counters();
  double moment_sum = 0;
  std::int64_t nonpositive = 0;
  Progress progress(req.quiet, "events", static_cast<double>(events));
  for (std::int64_t i = 0; i < events; ++i) {
    EventRecord e = engine.next_event();
    e.event = i + 1;
    catalog.row(catalog_row(e));
    moment_sum += e.moment;
    if (e.moment > 0) {
      hist.add(e.magnitude);
    } else {
      ++nonpositive;
    }
    progress.update(static_cast<double>(i + 1));
  }
  progress.finish(static_cast<double>(events));
  catalog.close();
  const double wall = seconds_since(t1);
  const double total_load = engine.load() - load0;
  hist.set_loading(total_load, p.n);
  hist.write_csv(out.path("histogram.csv"));

  const EngineCounters& c = engine.counters();
  Json summary = provenance_json(scene, "events");
  summary.set("events", events);
  summary.set("transient_events", transient);
  summary.set("blocks", p.n);
  summary.set("total_load", total_load);
  summary.set("moment_sum", moment_sum);
  summary.set("nonpositive_moments", nonpositive);
  summary.set("bin_width", hist.bin_width());
  summary.set("wall_seconds", wall);
  summary.set("wall_seconds_total", seconds_since(t0));
  summary.set("events_per_second", wall > 0 ? events / wall : 0.0);
  Json work = Json::object();
  work.set("steps", c.steps - c0.steps);
  work.set("block_steps", c.block_steps - c0.block_steps);
  work.set("sliding_block_steps", c.sliding_block_steps - c0.sliding_block_steps);
  summary.set("work", std::move(work));

  std::string fit_line = "b: not fitted (fewer than 2 events)";
  if (hist.events() >= 2) {
    try {
      std::optional<double> mu_min = scene.real_or_auto("stats.mu_min");
      std::optional<double> mu_max = scene.real_or_auto("stats.mu_max");
      const GrFit fit = fit_histogram(hist, mu_min, mu_max);
      summary.set("b_mle", fit.b_mle);
      summary.set("b_mle_err", fit.b_mle_err);
      summary.set("b_lsq", fit.b_lsq);
      summary.set("b_lsq_err", fit.b_lsq_err);
      Json window = Json::object();
      window.set("mu_min", fit.mu_min);
      window.set("mu_max", fit.mu_max);
      window.set("automatic", fit.window_auto);
      window.set("events", fit.n_in_window);
      window.set("ks_distance", fit.ks_distance);
      summary.set("fit_window", std::move(window));
      char line[200];
      std::snprintf(line, sizeof line, "b = %.3f ± %.3f (binned MLE) on mu in [%.2f, %.2f], %lld events", fit.b_mle,
                    fit.b_mle_err, fit.mu_min, fit.mu_max, static_cast<long long>(fit.n_in_window));
      fit_line = line;
    } catch (const Error& err) {
      fit_line = std::string("b: not fitted (") + err.what() + ")";
      summary.set("fit_error", err.what());
    }
  }
  write_file_atomic(out.path("summary.json"), summary.str() + "\n");

  std::printf("bkquake %s: %lld events (after %lld transient) in %.3g s, %.4g events/s\n", kVersion,
              static_cast<long long>(events), static_cast<long long>(transient), wall, wall > 0 ? events / wall : 0.0);
  std::printf("  total substrate displacement %.6g, magnitudes %.3g..%.3g\n", total_load, hist.min_mu(),
              hist.max_mu());
  std::printf("  %s\n  outputs in %s/\n", fit_line.c_str(), out.dir().c_str());
  return 0;
}

int run_continuous(const RunRequest& req, const OutputFolder& out, const ChainForces& forces, Stepper& stepper,
                   double dt) {
  const Scene& scene = req.scene;
  const ModelParams& p = forces.params();
  ContinuousDriver driver(forces, stepper, substrate_from_scene(scene),
                          initial_state(forces, static_cast<std::uint64_t>(scene.integer("run.seed")),
                                        scene.real("run.initial_disorder"), false),
                          dt);
  const double duration = scene.real("run.duration");
  const double every = scene.real("output.every");
  const bool blocks = scene.flag("output.blocks");

  CsvStream series(out.path("timeseries.csv"), "t,speed,substrate,pad_x,pad_v,pad_friction,sliding");
  CsvStream catalog(out.path("catalog.csv"), catalog_header());
  std::unique_ptr<CsvStream> trajectories;
  if (blocks) {
    std::string header = "t";
    for (int j = 0; j < p.n; ++j) {
      header += ",u";
      header += std::to_string(j);
    }
    trajectories = std::make_unique<CsvStream>(out.path("blocks.csv"), header);
  }
  auto sample = [&] {
    const ChainState& st = driver.state();
    const SubstrateState sub = driver.substrate();
    std::string row;
    for (double v : {st.t, sub.v, sub.s, st.x, st.xd, driver.pad_friction()}) {
      row += format_real(v);
      row += ',';
    }
    row += std::to_string(driver.sliding());
    series.row(row);
    if (trajectories) {
      row = format_real(st.t);
      for (int j = 0; j < p.n; ++j) {
        row += ',';
        row += format_real(driver.displacement(j));
      }
      trajectories->row(row);
    }
  };

  // Step count fixed up front so the end time does not depend on rounding of t += dt.
  const auto steps = static_cast<std::int64_t>(std::llround(std::ceil(duration / dt - 1e-9)));
  const auto t0 = Clock::now();
  Progress progress(req.quiet, "time", duration);
  double next_out = 0;
  std::int64_t episodes = 0;
  double friction_sum = 0, friction_sq = 0;
  std::int64_t samples = 0;
  for (std::int64_t i = 0; i <= steps; ++i) {
    if (driver.state().t >= next_out - 1e-9 * dt) {
      sample();
      const double f = driver.pad_friction();
      friction_sum += f;
      friction_sq += f * f;
      ++samples;
      next_out += every;
    }
    if (i == steps) break;
    driver.step();
    if (auto e = driver.finished_episode()) {
      ++episodes;
      catalog.row(catalog_row(*e));
    }
    if (!std::isfinite(driver.state().x) || !std::isfinite(driver.state().w[0]))
      {
      std::string msg = "non-finite state at time ";
      msg += format_real(driver.state().t);
      msg += ": the integration is unstable (reduce integrator.dt)";
      throw Error(msg);
    }
    progress.update(driver.state().t);
  }
  progress.finish(driver.state().t);
  series.close();
  catalog.close();
  if (trajectories) trajectories->close();
  const double wall = seconds_since(t0);

  Json summary = provenance_json(scene, "continuous");
  summary.set("duration", driver.state().t);
  summary.set("steps", steps);
  summary.set("blocks", p.n);
  summary.set("events", episodes);
  summary.set("total_load", driver.substrate().s);
  summary.set("wall_seconds", wall);
  summary.set("block_steps_per_second", wall > 0 ? static_cast<double>(steps) * p.n / wall : 0.0);
  const double mean = samples ? friction_sum / samples : 0.0;
  const double var = samples ? std::max(0.0, friction_sq / samples - mean * mean) : 0.0;
  summary.set("pad_friction_mean", mean);
  summary.set("pad_friction_amplitude", std::sqrt(2.0 * var));
  write_file_atomic(out.path("summary.json"), summary.str() + "\n");
  std::printf("bkquake %s: continuous run to t = %.6g (%lld steps) in %.3g s; %lld slip episodes\n", kVersion,
              driver.state().t, static_cast<long long>(steps), wall, static_cast<long long>(episodes));
  std::printf("  outputs in %s/\n", out.dir().c_str());
  return 0;
}

}  // namespace

int run_scene(const RunRequest& req) {
  const Scene& scene = req.scene;
  const ModelParams p = model_from_scene(scene);
  const ChainForces forces(p);
  const std::unique_ptr<Stepper> stepper = make_stepper(scene.choice("integrator.scheme"), p.n);
  const double dt = scene.real("integrator.dt");
  check_time_step(*stepper, p, dt);
  if (req.resume) throw Error("--resume: checkpoints are not implemented yet");
  if (scene.choice("drive.mode") == "events") EventEngine::check_model(p);

  const OutputFolder out(req.out_dir, req.force, req.resume);
  // A folder with summary.json is a finished run; overwriting one starts by unmarking it.
  if (req.force) std::filesystem::remove(out.path("summary.json"));
  std::vector<std::string> header = provenance_lines(scene);
  write_file_atomic(out.path("scene.ini"), scene.to_ini(header));
  if (scene.choice("drive.mode") == "continuous") return run_continuous(req, out, forces, *stepper, dt);
  return run_events(req, out, forces, *stepper, dt);
}

}  // namespace bkq
