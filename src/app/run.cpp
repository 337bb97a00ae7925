// From an effective scene to a finished output folder: reads the typed settings once,
// builds the model and the stepper, checks a --resume against the folder (nothing is
// changed before everything is checked), writes scene.ini first and hands over to the
// drive mode's run (app/event_run, app/continuous_run), whose observers write the rest;
// summary.json comes last and says whether the run finished or was interrupted (its
// "status", io/run_folder.hpp): --resume continues an interrupted run, and extends a
// finished run to a larger run.events or run.duration from its final state
// (checkpoint.final.bin).
#include "app/run.hpp"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>

#include "app/continuous_run.hpp"
#include "app/event_run.hpp"
#include "app/observers/catalog.hpp"
#include "app/observers/segments.hpp"
#include "app/rsf_run.hpp"
#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/event_engine.hpp"
#include "engine/ofc.hpp"
#include "io/catalog.hpp"
#include "io/catalog_file.hpp"
#include "io/catalog_h5.hpp"
#include "io/checkpoint.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/scene_keys.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"

namespace bkq {

namespace {

// The final state of the finished run in `dir`, checked for an extension: to a larger
// run.events (event runs) or a longer run.duration (continuous runs). Only that key may
// differ from the finished run's scene, and it must be larger; a continuous run's segment
// statistics are adapted to the longer schedule. Throws bkq::Error (the folder untouched)
// otherwise.
Checkpoint finished_state(const std::string& dir, const CheckpointFiles& checkpoints,
                          const Scene& scene, const Settings& settings, bool events) {
  const std::string finished =
      "--resume: output folder '" + dir + "' holds a finished run (summary.json)";
  if (!checkpoints.final_exists())
    throw Error(finished +
                " without its final state (checkpoint.final.bin): nothing to continue; use "
                "--force to run it again");
  Checkpoint saved = checkpoints.read_final();
  const Scene before = Scene::from_text(saved.scene_ini, checkpoints.final_state());
  const Key length = events ? key::run_events : key::run_duration;
  Scene same = scene;
  same.set(length, before.text(length), "the finished run");
  if (events) {
    const std::int64_t n1 = scene_values(before).run.events;
    const std::int64_t n2 = settings.run.events;
    if (n2 <= n1)
      throw Error(finished + " of " + std::to_string(n1) + " events: run.events = " +
                  std::to_string(n2) + " would not extend it (allowed: more than " +
                  std::to_string(n1) + "); nothing to continue");
    // Every other key must match, as for an interrupted run.
    check_checkpoint_matches(saved, same, checkpoints.final_state());
    return saved;
  }
  const double t1 = scene_values(before).run.duration;
  const double t2 = settings.run.duration;
  // A rate-and-state run ends at run.duration exactly (its final state is the one before the
  // step clipped there); a fixed-step run after ceil(duration / dt) steps, so equal step counts
  // are no extension.
  const bool fixed_step = !settings.rsf.on;
  if (t2 <= t1 || (fixed_step && saved.engine.counters.steps >= continuous_steps(settings)))
    throw Error(finished + " of duration " + format_real(t1) + ": run.duration = " +
                format_real(t2) + " would not extend it (allowed: more than " + format_real(t1) +
                (fixed_step ? " by at least one integrator.dt" : "") + "); nothing to continue");
  check_checkpoint_matches(saved, same, checkpoints.final_state());
  if (fixed_step) extend_segment_state(saved, settings_from_scene(same), settings);
  return saved;
}

// An extension makes the finished run an interrupted run of the longer scene: its final state
// becomes the checkpoint (now of this scene), scene.ini says the new run.events or
// run.duration and summary.json goes until the run ends again. A crash from here on resumes
// like any interruption. Returns the checkpoint's file.
std::string adopt_extension(Checkpoint& saved, const Scene& scene, const OutputFolder& out,
                            const CheckpointFiles& checkpoints) {
  saved.scene_hash = scene.hash();
  saved.scene_ini = scene.to_ini();
  checkpoints.write(saved);
  write_file_atomic(out.path("scene.ini"), scene.to_ini(provenance_lines(scene)));
  std::filesystem::remove(out.path("summary.json"));
  std::filesystem::remove(checkpoints.final_state());
  return checkpoints.current();
}

}  // namespace

int run_scene(const RunRequest& req) {
  const Scene& scene = req.scene;
  const Settings settings = settings_from_scene(scene);
  const ModelParams& p = settings.model;
  const bool ofc = settings.ofc.on;
  if (settings.rsf.on) {
    // Rate-and-state friction runs on its own path (app/rsf_run.hpp).
    if (settings.output.catalog == CatalogFormat::Hdf5 && !hdf5_available())
      throw Error(
          "output.catalog = hdf5: this bkquake was built without HDF5 (libhdf5-dev); "
          "allowed: csv, none");
    const OutputFolder out(req.out_dir, req.force, req.resume);
    if (req.force) std::filesystem::remove(out.path("summary.json"));
    if (req.resume && run_status(out.dir()) == RunStatus::Finished) {
      const CheckpointFiles checkpoints(out.dir());
      return run_rsf(req, settings, out,
                     RsfExtension{finished_state(out.dir(), checkpoints, scene, settings,
                                                 settings.rsf.event_driven),
                                  checkpoints.final_state(), [&](Checkpoint& saved) {
                                    return adopt_extension(saved, scene, out, checkpoints);
                                  }});
    }
    return run_rsf(req, settings, out);
  }
  const ChainForces forces(p);
  const std::unique_ptr<Stepper> stepper = stepper_of(settings.integrator, p.n);
  const bool events = settings.drive.mode == DriveMode::Events;
  if (ofc) {
    OfcEngine::check(settings.ofc.lattice);
  } else {
    check_time_step(*stepper, p, settings.integrator.dt);
    if (events) EventEngine::check_model(p);
  }
  if (settings.output.catalog == CatalogFormat::Hdf5 && !hdf5_available())
    throw Error(
        "output.catalog = hdf5: this bkquake was built without HDF5 (libhdf5-dev); allowed: "
        "csv, none");

  const OutputFolder out(req.out_dir, req.force, req.resume);
  // A wide stencil's setup (the engine's tree of times to failure, from every block's force)
  // and each event spanning the chain sum every block's springs: seconds, near the bound the
  // scene check sets (io/scene.cpp). Said before they pass in silence.
  if (!req.quiet && !ofc && p.long_range()) {
    const std::size_t springs =
        2 * (p.lattice() ? forces.lattice_stencil().size() : forces.stencil().size());
    const double terms = static_cast<double>(springs) * static_cast<double>(p.n);
    if (terms > 1e7) {
      std::fprintf(stderr,
                   "bkquake: %d blocks, %zu springs each (%.3g terms per force evaluation): "
                   "setting up takes seconds, and so may an event that spans the chain\n",
                   p.n, springs, terms);
      std::fflush(stderr);
    }
  }
  const CheckpointFiles checkpoints(out.dir());
  if (req.resume) {
    // Everything is checked before anything is changed: a refused resume leaves the folder as it
    // was.
    std::string from;
    Checkpoint saved;
    const bool extend = run_status(out.dir()) == RunStatus::Finished;
    if (extend) {
      saved = finished_state(out.dir(), checkpoints, scene, settings, events);
      from = checkpoints.final_state();
    } else {
      saved = checkpoints.read(&from);
      check_checkpoint_matches(saved, scene, from);
    }
    validate_checkpoint(saved, settings.ofc.on ? 0 : p.n, scene_values(scene).stats.bin_width,
                        from);
    if (settings.ofc.on) validate_ofc_state(saved, settings.ofc.lattice, from);
    const CatalogFormat format = settings.output.catalog;
    const std::string catalog =
        format == CatalogFormat::None ? "" : out.path(catalog_file_name(format));
    if (format == CatalogFormat::Csv)
      check_csv_prefix(catalog, catalog_header(catalog_layout(settings)),
                       saved.progress.events_done, saved.progress.catalog_bytes,
                       saved_catalog_checksum(saved));
    else if (format == CatalogFormat::Hdf5)  // cut back when the catalog observer opens it
      check_catalog_h5(catalog, saved.progress.events_done, saved_catalog_checksum(saved),
                       catalog_layout(settings));
    if (saved.git_revision != kGitRevision)
      std::fprintf(stderr,
                   "bkquake: warning: the checkpoint was written by git revision %s, this is %s; "
                   "the continuation "
                   "is exact only if the engine did not change in between\n",
                   saved.git_revision.c_str(), kGitRevision);
    const auto adopt = [&] { from = adopt_extension(saved, scene, out, checkpoints); };
    if (!events)
      return resume_continuous(req, settings, out, forces, *stepper, saved, from,
                               extend ? std::function<void()>(adopt) : std::function<void()>());
    if (extend) adopt();
    // Rows written after the checkpoint are computed again, so they go.
    std::error_code ec;
    if (format == CatalogFormat::Csv)
      std::filesystem::resize_file(catalog, saved.progress.catalog_bytes, ec);
    if (ec) throw Error("cannot truncate '" + catalog + "' to its checkpoint: " + ec.message());
    std::printf(
        "bkquake: resuming '%s' from %s: %lld of %lld events done (%lld of %lld transient)\n",
        out.dir().c_str(), from.c_str(), static_cast<long long>(saved.progress.events_done),
        static_cast<long long>(settings.run.events),
        static_cast<long long>(saved.progress.transient_done),
        static_cast<long long>(settings.run.transient_events));
    std::fflush(stdout);
    if (ofc) return run_ofc_events(req, settings, out, &saved);
    return run_events(req, settings, out, forces, *stepper, &saved);
  }

  if (checkpoints.exist() && !req.force)
    throw Error("output folder '" + out.dir() + "' holds an interrupted run (" +
                checkpoints.current() + "); use --resume to continue it or --force to start over");
  // Overwriting a run starts by removing its summary (finished or interrupted).
  if (req.force) {
    std::filesystem::remove(out.path("summary.json"));
    checkpoints.remove();
    // A catalogue of another format would pass for this run's.
    for (const CatalogFormat f : {CatalogFormat::Csv, CatalogFormat::Hdf5})
      if (f != settings.output.catalog) std::filesystem::remove(out.path(catalog_file_name(f)));
  }
  write_file_atomic(out.path("scene.ini"), scene.to_ini(provenance_lines(scene)));
  if (!events) return run_continuous(req, settings, out, forces, *stepper);
  if (ofc) return run_ofc_events(req, settings, out, nullptr);
  return run_events(req, settings, out, forces, *stepper, nullptr);
}

}  // namespace bkq
