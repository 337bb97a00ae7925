// The summary observers; see summary.hpp.
#include "app/observers/summary.hpp"

#include <signal.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

#include "app/gr_report.hpp"
#include "app/observers/segments.hpp"
#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/catalog_reader.hpp"
#include "io/checkpoint.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {

namespace {

// The provenance, then "status" (io/run_folder.hpp): finished, or interrupted with what
// the run needs to go on ("interrupted": the signal, the checkpoint, the command, and how
// far it was meant to go; the figures after it are those reached so far).
Json provenance_json(const Scene& scene, const Settings& settings, const std::string& mode,
                     const RunEnd& end, const OutputFolder& out) {
  Json j = Json::object();
  j.set("version", kVersion);
  j.set("git_revision", kGitRevision);
  j.set("seed", static_cast<std::int64_t>(settings.run.seed));
  j.set("scene", scene.provenance());
  j.set("scene_hash", std::to_string(scene.hash()));
  j.set("mode", mode);
  j.set("written", utc_now_iso());
  j.set(kStatusKey, status_text(end.signal ? RunStatus::Interrupted : RunStatus::Finished));
  if (end.signal == 0) return j;
  Json stop = Json::object();
  stop.set("signal", end.signal == SIGINT ? "SIGINT" : "SIGTERM");
  stop.set("checkpoint",
           std::filesystem::path(CheckpointFiles(out.dir()).current()).filename().string());
  stop.set("resume", "bkquake run " + out.path("scene.ini") + " --out " + out.dir() + " --resume");
  if (settings.drive.mode == DriveMode::Events) {
    stop.set("events_planned", settings.run.events);
    stop.set("transient_events_planned", settings.run.transient_events);
  } else {
    stop.set("duration_planned", settings.run.duration);
  }
  j.set("interrupted", std::move(stop));
  return j;
}

}  // namespace

SummaryOfEvents::SummaryOfEvents(const Scene& scene, const Settings& settings,
                                 const OutputFolder& out, const MagnitudeHistogram& hist,
                                 const Observers& all, std::function<bool()> stop_requested)
    : scene_(scene),
      settings_(settings),
      out_(out),
      hist_(hist),
      all_(all),
      stop_requested_(std::move(stop_requested)) {}

void SummaryOfEvents::on_start() {
  // A resumed run's summary (interrupted) no longer describes it: the folder holds a run
  // under way until this one ends and writes its own. A temporary of a summary write cut
  // short by a second signal goes too.
  const std::string summary = out_.path("summary.json");
  std::error_code ec;
  std::filesystem::remove(summary, ec);
  if (ec) throw Error("cannot remove '" + summary + "': " + ec.message());
  remove_temporaries_of(summary);
}

void SummaryOfEvents::on_phase(const Phase& p) {
  if (std::string_view(p.what) == "events") events_total_ = p.total;
}

void SummaryOfEvents::on_phase_end(const Advance& a) {
  if (events_total_ < 0 || a.done < events_total_) return;
  fit();
}

void SummaryOfEvents::fit() {
  if (fitted_ || hist_.events() < 2) return;
  GrFitOptions opt;
  opt.cancelled = stop_requested_;
  try {
    fit_ = fit_histogram(hist_, settings_.stats.mu_min, settings_.stats.mu_max, opt);
    if (!fit_->b_ok) {  // no b rather than a meaningless one (docs/explanation/b-fit.md)
      fit_error_ = "no acceptable fit window: " + fit_->no_b_reason;
      fit_.reset();
    }
    const bool lattice = settings_.lattice.nx > 1 && settings_.lattice.ny > 1;
    if (settings_.ofc.on || lattice) tau_measure_ = settings_.ofc.on ? "topplings" : "blocks";
    Ordered ordered;
    if (fit_ || !tau_measure_.empty()) ordered = read_ordered();
    if (fit_ && ordered.note.empty()) {
      const BootstrapError boot = block_bootstrap_b(ordered.mu, fit_->bin_width, fit_->mu_min,
                                                    fit_->mu_max, fit_->truncated, opt);
      fit_->b_mle_boot_err = boot.err;
      fit_->boot_block = boot.block;
      fit_->boot_tau_int = boot.tau_int;
      fit_->boot_resamples = boot.resamples;
    } else if (fit_) {
      fit_->boot_note = ordered.note;
    }
    // tau of the avalanche sizes: topplings of an OFC run, blocks of a lattice's events.
    if (!tau_measure_.empty()) {
      if (ordered.note.empty()) {
        PowerLawOptions po;
        po.discrete = true;
        po.cancelled = stop_requested_;
        tau_ = fit_power_law(ordered.size, po);
        if (!tau_->ok) {
          tau_error_ = tau_->no_fit_reason;
          tau_.reset();
        }
      } else {
        tau_error_ = ordered.note;
      }
    }
    fitted_ = true;
  } catch (const FitCancelled&) {
    // The run stops after this phase (a checkpoint, no summary); a resume fits again.
  } catch (const Error& err) {
    fit_error_ = err.what();
    fitted_ = true;
  }
}

void SummaryOfEvents::on_resume(const Checkpoint& c) {
  moment_sum_ = c.progress.moment_sum;
  nonpositive_ = c.progress.nonpositive;
}

SummaryOfEvents::Ordered SummaryOfEvents::read_ordered() const {
  Ordered o;
  std::string file;
  for (const char* name : {"catalog.csv", "catalog.h5"})
    if (std::filesystem::exists(out_.path(name))) file = out_.path(name);
  if (file.empty()) {
    o.note = "no catalogue written (output.catalog = none): no order of events";
    return o;
  }
  if (hist_.events() > kMaxOrderedEvents) {
    o.note = "more than " + std::to_string(kMaxOrderedEvents) +
             " events: fit the catalogue with bkquake fit";
    return o;
  }
  try {
    CatalogReader reader(file);
    CatalogEvent e;
    while (reader.next(e)) {
      if (!(e.moment > 0)) continue;  // as the histogram
      o.mu.push_back(e.magnitude);
      o.size.push_back(settings_.ofc.on ? static_cast<double>(e.topplings) : e.blocks);
    }
  } catch (const Error& err) {
    o.mu.clear();
    o.size.clear();
    o.note = std::string("the catalogue does not read: ") + err.what();
    return o;
  }
  if (static_cast<std::int64_t>(o.mu.size()) != hist_.events()) {
    o.note = "the catalogue holds " + std::to_string(o.mu.size()) + " events, the histogram " +
             std::to_string(hist_.events());
    o.mu.clear();
    o.size.clear();
  }
  return o;
}

void SummaryOfEvents::on_checkpoint(Checkpoint& c) {
  c.progress.moment_sum = moment_sum_;
  c.progress.nonpositive = nonpositive_;
}

void SummaryOfEvents::add_moments(Json& summary) const {
  summary.set("moment_sum", moment_sum_);
  summary.set("nonpositive_moments", nonpositive_);
  summary.set("bin_width", hist_.bin_width());
}

void SummaryOfEvents::add_tau(Json& summary) const {
  if (tau_measure_.empty()) return;
  if (tau_) {
    summary.set("tau", power_law_json(*tau_, tau_measure_));
  } else {
    summary.set("tau", Json::null());
    summary.set("tau_error", tau_error_);
  }
}

std::string SummaryOfEvents::add_fit(Json& summary, const RunEnd& end) {
  if (end.signal != 0) {
    summary.set("b_mle", Json::null());
    summary.set("fit_error", kInterruptedFit);
    return kInterruptedFit;
  }
  if (hist_.events() < 2) {
    summary.set("b_mle", Json::null());
    summary.set("fit_error", kTooFewToFit);
    return std::string("b: not fitted (") + kTooFewToFit + ")";
  }
  fit();
  add_tau(summary);
  if (!fit_) {
    summary.set("b_mle", Json::null());
    summary.set("fit_error", fit_error_);
    return "b: not fitted (" + fit_error_ + ")";
  }
  const GrFit& fit = *fit_;
  summary.set("b_mle", fit.b_mle);
  summary.set("b_mle_err", fit.b_mle_err);
  summary.set("b_mle_sys_err", fit.b_mle_sys_err);
  // The statistical error of correlated events (block bootstrap), beside Shi & Bolt's.
  summary.set("b_mle_boot_err", fit_number(fit.b_mle_boot_err));
  if (std::isfinite(fit.b_mle_boot_err))
    summary.set("boot_block", fit.boot_block);
  else
    summary.set("boot_note", fit.boot_note);
  // The same slope per unit of moment magnitude Mw (b_mw = 1.5 b_mle; b_mle is per mu = ln M).
  summary.set("b_mw", b_moment_magnitude(fit.b_mle));
  summary.set("b_mw_err", b_moment_magnitude(fit.b_mle_err));
  if (std::isfinite(fit.b_lsq)) {
    summary.set("b_lsq", fit.b_lsq);
    summary.set("b_lsq_err", fit.b_lsq_err);
  } else {
    summary.set("b_lsq", Json::null());
  }
  if (!fit.b_lsq_reason.empty()) summary.set("b_lsq_reason", fit.b_lsq_reason);
  Json window = Json::object();
  window.set("mu_min", fit.mu_min);
  window.set("mu_max", fit.mu_max);
  window.set("automatic", fit.window_auto);
  window.set("events", fit.n_in_window);
  window.set("ks_distance", fit.ks_distance);
  window.set("mu_max_reason", fit.mu_max_reason);
  summary.set("fit_window", std::move(window));
  if (!fit.warnings.empty()) summary.set("fit_warnings", Json::strings(fit.warnings));
  char line[200];
  std::snprintf(line, sizeof line, " (binned MLE) on mu in [%.2f, %.2f], %lld events", fit.mu_min,
                fit.mu_max, static_cast<long long>(fit.n_in_window));
  // An error that rounds to zero gets more digits; no estimate, a reason.
  if (std::isfinite(fit.b_mle) && std::isfinite(fit.b_mle_err)) {
    char sys[120];
    std::snprintf(sys, sizeof sys, " (sys. +/- %.2g; b_mw = 1.5 b = %.4g per unit of Mw)",
                  fit.b_mle_sys_err, b_moment_magnitude(fit.b_mle));
    return "b = " + format_with_error(fit.b_mle, fit.b_mle_err) + line + sys;
  }
  return "b: no fit (the estimate is not finite: too few events or too few bins in the window" +
         std::string(line) + ")";
}

void EventSummary::on_end(const RunEnd& end) {
  const double wall = end.wall_seconds;
  Json summary = provenance_json(scene_, settings_, "events", end, out_);
  summary.set("events", end.events);
  summary.set("transient_events", end.transient_events);
  summary.set("blocks", end.blocks);
  summary.set("total_load", end.total_load);
  add_moments(summary);
  summary.set("wall_seconds", wall);
  summary.set("wall_seconds_total", end.wall_seconds_total);
  summary.set("events_per_second", wall > 0 ? end.events / wall : 0.0);
  summary.set("resumes", end.resumes);
  Json work = Json::object();
  work.set("steps", end.steps_recorded);
  work.set("block_steps", end.block_steps);
  work.set("sliding_block_steps", end.sliding_block_steps);
  summary.set("work", std::move(work));
  const std::string fit_line = add_fit(summary, end);
  all_.add_to_summary(summary);
  write_file_atomic(out_.path("summary.json"), summary.str() + "\n");
  if (end.signal != 0) return;  // the run's own stderr line says where it stopped

  std::printf("bkquake %s: %lld events (after %lld transient) in %.3g s, %.4g events/s\n", kVersion,
              static_cast<long long>(end.events), static_cast<long long>(end.transient_events),
              wall, wall > 0 ? end.events / wall : 0.0);
  // An OFC run's load is the uniform stress added to every site, in thresholds.
  std::printf("  total %s %.6g, magnitudes %.3g..%.3g\n",
              settings_.ofc.on ? "drive (stress per site)" : "substrate displacement",
              end.total_load, hist_.min_mu(), hist_.max_mu());
  std::printf("  %s\n  outputs in %s/\n", fit_line.c_str(), out_.dir().c_str());
}

void ContinuousSummary::on_end(const RunEnd& end) {
  const double wall = end.wall_seconds;
  // An event-driven rate-and-state run (closed forms between events) shares this summary.
  const bool rsf_events = settings_.rsf.on && settings_.rsf.event_driven;
  Json summary =
      provenance_json(scene_, settings_, rsf_events ? "events" : "continuous", end, out_);
  summary.set("duration", end.duration);
  summary.set("steps", end.steps);
  summary.set("blocks", end.blocks);
  summary.set("events", end.events);
  summary.set("total_load", end.total_load);
  add_moments(summary);
  summary.set("wall_seconds", wall);
  summary.set("block_steps_per_second",
              wall > 0 ? static_cast<double>(end.steps) * end.blocks / wall : 0.0);
  summary.set("resumes", end.resumes);
  const std::string fit_line = add_fit(summary, end);
  all_.add_to_summary(summary);
  write_file_atomic(out_.path("summary.json"), summary.str() + "\n");
  if (end.signal != 0) return;  // the run's own stderr line says where it stopped
  std::printf("bkquake %s: %s run to t = %.6g (%lld steps) in %.3g s; %lld %s\n", kVersion,
              rsf_events ? "event-driven" : "continuous", end.duration,
              static_cast<long long>(end.steps), wall, static_cast<long long>(end.events),
              rsf_events ? "events" : "slip episodes");
  // A run with a pad (bkp, 1dof: the brake side, Ferre 2018 ch. 4) is read through the pad's
  // segment statistics and time series; its slip episodes' b (in summary.json) is not what
  // such a run is for, so the line says where its figures are instead.
  std::string what = fit_line;
  if (settings_.model.kind != ModelKind::BK) {
    const std::size_t n = segment_spans(settings_.drive, settings_.run.duration).size();
    what = n == 0 ? std::string(
                        "the pad's motion and friction in timeseries.csv (a ramp has no "
                        "speed segments)")
                  : std::to_string(n) + (n == 1 ? " speed segment" : " speed segments") +
                        ": the pad's mean and amplitude in segments.csv";
  }
  std::printf("  %s\n  outputs in %s/\n", what.c_str(), out_.dir().c_str());
}

}  // namespace bkq
