// The rate-and-state run loop; see rsf_run.hpp. The loop owns the integrator and the event
// detector and notifies the observers; summary.json gains an "rsf" object (the integrator's
// steps, the critical stiffness, the event times of the last event).
#include "app/rsf_run.hpp"

#include <signal.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>

#include "app/observers/catalog.hpp"
#include "app/observers/checkpoint_timer.hpp"
#include "app/observers/histogram.hpp"
#include "app/observers/progress.hpp"
#include "app/observers/summary.hpp"
#include "app/rsf_stability.hpp"
#include "app/stop_signals.hpp"
#include "app/wall_clock.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/rsf_events.hpp"
#include "engine/rsf_loader.hpp"
#include "io/catalog.hpp"
#include "io/catalog_file.hpp"
#include "io/catalog_h5.hpp"
#include "io/checkpoint.hpp"
#include "io/json.hpp"
#include "io/rsf_blocks.hpp"
#include "io/run_folder.hpp"
#include "io/stability_csv.hpp"
#include "stats/rsf_stability.hpp"

namespace bkq {

namespace {

// The integrator's and the law's figures in summary.json.
class RsfFigures : public RunObserver {
 public:
  RsfFigures(const RsfCycle& cycle, const RsfEventDetector& events)
      : cycle_(cycle), events_(events) {}
  void add_to_summary(Json& summary) const override {
    const RsfModel& m = cycle_.model();
    Json r = Json::object();
    r.set("scheme", "dopri5");
    r.set("tolerance", cycle_.tolerance());
    r.set("steps", cycle_.accepted());
    r.set("rejected_steps", cycle_.rejected());
    r.set("k", m.k);
    if (rsf_homogeneous(m)) {  // per-block laws have no one k_crit (app/rsf_stability.hpp)
      r.set("k_crit_quasi_static", rsf::critical_stiffness(m.law[0].params(), m.sigma));
      r.set("k_crit", rsf_critical_stiffness(m));
    }
    r.set("eta", m.eta);
    r.set("last_hypocentre_time", events_.events() > 0 ? events_.times().hypocentre : 0.0);
    r.set("last_peak_time", events_.events() > 0 ? events_.times().peak : 0.0);
    r.set("rows", m.rows);
    r.set("springs_per_block", static_cast<std::int64_t>(2 * m.stencil().size()));
    summary.set("rsf", std::move(r));
  }

 private:
  const RsfCycle& cycle_;
  const RsfEventDetector& events_;
};

}  // namespace

RsfStabilityReport rsf_stability(const Settings& settings) {
  const RsfModel& m = settings.rsf.chain;
  if (!rsf_homogeneous(m)) return rsf_dense_stability(settings);  // the modes are not waves
  const rsf::Params& law = m.law.at(0).params();
  const double quasi_static = rsf::critical_stiffness(law, m.sigma);
  RsfModel qd = m;
  qd.dynamics = RsfDynamics::QuasiDynamic;
  const double with_damping = rsf_critical_stiffness(qd);
  const double k_crit = rsf_critical_stiffness(m);
  const double f_crit = rsf_critical_frequency(m);
  RsfStabilityReport r;
  r.modes_csv = header_of(stability_schema()) + "\n";
  int unstable = 0;
  double top_growth = -HUGE_VAL, top_freq = 0;
  const int n = m.n();
  // One mode per wavenumber pair (q_x, q_y): the chain's q, or a lattice's pair.
  for (int q = 0; q < n; ++q) {
    const int qx = q % m.nx(), qy = q / m.nx();
    const double k_q = m.k + rsf_mode_stiffness(m, qx, qy);
    const std::complex<double> s = rsf_eigenvalues(m, k_q)[0];
    const double freq = std::fabs(s.imag()) / (2 * std::numbers::pi);
    unstable += s.real() > 0 ? 1 : 0;
    if (s.real() > top_growth) top_growth = s.real(), top_freq = freq;
    const std::string name = m.rows > 1 ? "lattice " + std::to_string(qx) + " " + std::to_string(qy)
                                        : "chain " + std::to_string(q);
    r.modes_csv += format_real(m.v_pl) + "," + name + "," + format_real(s.real()) + "," +
                   format_real(std::fabs(s.imag())) + "," + format_real(freq) + "," +
                   (s.real() > 0 ? "1" : "0") + "\n";
  }
  r.summary_csv =
      "v_pl,k,k_c,k_crit_quasi_static,k_crit_radiation_damping,k_crit,frequency_at_k_crit,"
      "modes,unstable,max_growth,its_frequency\n" +
      format_real(m.v_pl) + "," + format_real(m.k) + "," + format_real(m.k_c) + "," +
      format_real(quasi_static) + "," + format_real(with_damping) + "," + format_real(k_crit) +
      "," + format_real(f_crit) + "," + std::to_string(n) + "," + std::to_string(unstable) + "," +
      format_real(top_growth) + "," + format_real(top_freq) + "\n";
  char line[512];
  std::snprintf(
      line, sizeof line,
      "rate-and-state steady sliding at V_pl = %g m/s, k = %g Pa/m:\n"
      "  k_crit = sigma (b - a)/D_c = %g Pa/m (quasi-static, Ruina 1983)\n"
      "  with radiation damping eta = %g Pa s/m: %g Pa/m\n"
      "  %s: k_crit = %g Pa/m, frequency there %g Hz\n"
      "  %d of %d modes unstable; largest growth rate %g 1/s at %g Hz\n",
      m.v_pl, m.k, quasi_static, m.eta, with_damping,
      m.dynamics == RsfDynamics::Inertial ? "with inertia (Rice & Ruina 1983)" : "quasi-dynamic",
      k_crit, f_crit, unstable, n, top_growth, top_freq);
  r.text = line;
  return r;
}

namespace {

// The run's own named state in a checkpoint: the integrator's and the detector's numbers.
constexpr const char* kStateName = "rsf";
constexpr const char* kBlocksState = "rsf.blocks_csv";

// rsf_blocks.csv (output.blocks): every output.every seconds, for output.block_first and the
// output.block_count blocks after it, the slip rate, state, frictional stress sigma f and slip,
// read on the Hermite cubic of the step that holds the sample time (the samples never shorten
// a step, so a run writes the same catalogue with and without them).
class BlockSamples {
 public:
  static constexpr const char* kHeader = "t,block,slip_rate,theta,shear_stress,slip";

  BlockSamples(std::string path, double every, int first, int count)
      : path_(std::move(path)), every_(every), first_(first), count_(count) {}
  BlockSamples(const BlockSamples&) = delete;
  BlockSamples& operator=(const BlockSamples&) = delete;
  ~BlockSamples() {
    if (file_) std::fclose(file_);  // an unfinished run's file: its checkpoint says how much counts
  }

  // A fresh file, or the resumed one checked and cut back to its checkpoint's rows.
  void open(const Checkpoint* resumed) {
    if (resumed) {
      std::uint64_t bytes = 0;
      if (!find_state(*resumed, kBlocksState, bytes, rows_, next_))
        throw Error("--resume: the checkpoint holds no rsf_blocks.csv state");
      check_csv_prefix(path_, kHeader, rows_, bytes);
      std::filesystem::resize_file(path_, bytes);
      file_ = std::fopen(path_.c_str(), "ab");
    } else {
      file_ = std::fopen(path_.c_str(), "wb");
      if (file_) std::fprintf(file_, "%s\n", kHeader);
    }
    if (!file_) throw Error("cannot write '" + path_ + "'");
  }

  void after_step(const RsfCycle& c) {
    const int n = c.n();
    const double t0 = c.t_prev(), t1 = c.t();
    const auto& y0 = c.y_prev();
    const auto& d0 = c.dy_prev();
    const auto& y1 = c.y();
    const auto& d1 = c.dy();
    const RsfModel& m = c.model();
    for (double t = static_cast<double>(next_) * every_; t <= t1;
         t = static_cast<double>(++next_) * every_) {
      const auto at = [&](int i) { return hermite_value(t0, y0[i], d0[i], t1, y1[i], d1[i], t); };
      for (int j = first_; j < first_ + count_; ++j) {
        const double ln_v = at(n + j), ln_theta = at(2 * n + j);
        const double tau = m.sigma * m.law[j].friction(m.form, ln_v, ln_theta).f;
        std::fprintf(file_, "%s,%d,%s,%s,%s,%s\n", format_real(t).c_str(), j,
                     format_real(std::exp(ln_v)).c_str(), format_real(std::exp(ln_theta)).c_str(),
                     format_real(tau).c_str(), format_real(at(j)).c_str());
        ++rows_;
      }
    }
  }

  void checkpoint(Checkpoint& c) {
    if (std::fflush(file_) != 0) throw Error("cannot write '" + path_ + "'");
    const auto bytes = static_cast<std::uint64_t>(std::ftell(file_));
    put_state(c, kBlocksState, bytes, rows_, next_);
  }
  void close() {
    if (file_ && std::fclose(file_) != 0) throw Error("cannot write '" + path_ + "'");
    file_ = nullptr;
  }

 private:
  std::string path_;
  double every_;
  int first_, count_;
  std::int64_t rows_ = 0;  // rows written after the header
  std::int64_t next_ = 0;  // index k of the next sample time k * every
  std::FILE* file_ = nullptr;
};

// slow_slip.csv (rsf.slow_slip_threshold): one row per slow-slip or afterslip episode, cut
// back to its checkpoint's rows on a resume as the catalogue is.
class SlowSlipFile {
 public:
  static constexpr const char* kState = "rsf.slow_slip_csv";

  explicit SlowSlipFile(std::string path) : path_(std::move(path)) {}
  SlowSlipFile(const SlowSlipFile&) = delete;
  SlowSlipFile& operator=(const SlowSlipFile&) = delete;
  ~SlowSlipFile() {
    if (file_) std::fclose(file_);
  }

  void open(const Checkpoint* resumed) {
    const std::string header = header_of(slow_slip_schema());
    if (resumed) {
      std::uint64_t bytes = 0;
      if (!find_state(*resumed, kState, bytes, rows_))
        throw Error("--resume: the checkpoint holds no slow_slip.csv state");
      check_csv_prefix(path_, header, rows_, bytes);
      std::filesystem::resize_file(path_, bytes);
      file_ = std::fopen(path_.c_str(), "ab");
    } else {
      file_ = std::fopen(path_.c_str(), "wb");
      if (file_) std::fprintf(file_, "%s\n", header.c_str());
    }
    if (!file_) throw Error("cannot write '" + path_ + "'");
  }

  void write(const RsfSlowEpisode& s) {
    const EventRecord& e = s.record;
    std::fprintf(file_, "%lld,%s,%s,%s,%d,%s,%s,%s,%d,%d,%d,%d,%d,%d\n",
                 static_cast<long long>(e.event), s.afterslip ? "afterslip" : "slow",
                 format_real(e.hypocentre_time).c_str(), format_real(e.duration).c_str(), e.blocks,
                 format_real(e.moment).c_str(), format_real(e.max_speed).c_str(),
                 format_real(e.peak_time).c_str(), e.trigger, e.first_block, e.last_block,
                 e.trigger_row, e.first_row, e.last_row);
    ++rows_;
  }

  void checkpoint(Checkpoint& c) {
    if (std::fflush(file_) != 0) throw Error("cannot write '" + path_ + "'");
    put_state(c, kState, static_cast<std::uint64_t>(std::ftell(file_)), rows_);
  }
  void close() {
    if (file_ && std::fclose(file_) != 0) throw Error("cannot write '" + path_ + "'");
    file_ = nullptr;
  }

 private:
  std::string path_;
  std::int64_t rows_ = 0;
  std::FILE* file_ = nullptr;
};

// Reads the rate-and-state record of a checkpoint with `restore` (given the record's reader);
// a missing or malformed record is refused in one line.
template <class Restore>
void restore_rsf_state(const Checkpoint& resumed, Restore restore) {
  const std::string* bytes = resumed.find(kStateName);
  if (!bytes)
    throw Error("--resume: the checkpoint holds no rate-and-state state (it is another run's)");
  StateReader r(*bytes, kStateName);
  try {
    restore(r);
  } catch (const std::exception& e) {
    throw Error(std::string("--resume: the checkpoint's rate-and-state state is malformed: ") +
                e.what());
  }
  if (!r.done()) throw Error("--resume: the checkpoint's rate-and-state state is malformed");
}

// The observers of both rate-and-state runs, in this order: catalogue, histogram, the run's
// figures (attached by `figures`), summary, checkpoint timer, progress, the caller's.
template <class Figures, class Save>
void attach_run_observers(Observers& obs, const RunRequest& req, const Settings& settings,
                          const OutputFolder& out, std::int64_t resumed_events, Figures figures,
                          Save save) {
  const RunSettings& r = settings.run;
  if (const char* catalog = catalog_file_name(settings.output.catalog))
    obs.attach<CatalogWriter>(settings.output.catalog, out.path(catalog), req.scene, resumed_events,
                              settings.output.catalog_deflate, catalog_layout(settings));
  const auto& hist =
      obs.attach<HistogramWriter>(settings.stats.bin_width, out.path("histogram.csv"));
  figures(obs);
  obs.attach<ContinuousSummary>(req.scene, settings, out, hist.histogram(), obs);
  if (r.checkpoint_events > 0 || r.checkpoint_seconds > 0)
    obs.attach<CheckpointTimer>(save, r.checkpoint_events, r.checkpoint_seconds);
  if (!req.quiet) obs.attach<ProgressLine>();
  for (RunObserver* o : req.observers) obs.attach_ref(*o);
}

class RsfRun {
 public:
  RsfRun(const RunRequest& req, const Settings& settings, const OutputFolder& out,
         const Checkpoint* resumed)
      : req_(req),
        settings_(settings),
        out_(out),
        files_(out.dir()),
        cycle_(settings.rsf.chain, settings.rsf.tolerance, {settings.rsf.v_init},
               settings.rsf.theta_start()),
        detector_(settings.rsf.v_threshold),
        duration_(settings.run.duration) {
    if (settings.rsf.v_slow > 0) slow_.emplace(settings.rsf.v_slow, settings.rsf.v_threshold);
    if (resumed) {
      restore_rsf_state(*resumed, [&](StateReader& r) {
        cycle_.restore(r.f64s());
        detector_.restore(r.f64s());
        if (slow_) slow_->restore(r.f64s());
      });
      prog_ = resumed->progress;
      ++prog_.resumes;
    }
    wall_.set_before(prog_.wall_total);
    if (settings.output.blocks) {
      samples_.emplace(out.path("rsf_blocks.csv"), settings.output.every,
                       settings.output.block_first, settings.output.block_count);
      samples_->open(resumed);
    }
    if (slow_) {
      slow_file_.emplace(out.path("slow_slip.csv"));
      slow_file_->open(resumed);
    }
    attach_observers(resumed != nullptr);
    if (resumed) obs_.resume(*resumed);
  }

  int run() {
    StopSignals signals;
    obs_.start();
    obs_.phase({"time", cycle_.t(), duration_});
    while (cycle_.t() < duration_ && !signals.received()) {
      // The final state is the one before the step clipped at run.duration: a longer run takes
      // that step unclipped, so an extension (--resume, a larger run.duration) continues from
      // here, its rows after this cut back, as one run of the longer scene would.
      if (cycle_.t() + cycle_.next_step() >= duration_) save(true);
      cycle_.step(duration_);
      if (!std::isfinite(cycle_.ln_v(0)))
        throw Error("rsf: non-finite slip rate at t = " + format_real(cycle_.t()) +
                    " (lower integrator.tolerance)");
      // The slow episodes see the step before the seismic detector, which may end an event
      // in it and so start an afterslip episode at the event's end.
      if (slow_)
        if (auto s = slow_->observe(cycle_)) slow_file_->write(*s);
      if (auto e = detector_.observe(cycle_)) {
        obs_.event(*e);
        if (slow_) slow_->event_ended(cycle_, e->hypocentre_time + e->duration);
      }
      if (samples_) samples_->after_step(cycle_);
      obs_.advance({cycle_.t(), detector_.events()});
    }
    obs_.phase_end({cycle_.t(), detector_.events()});
    if (samples_ && cycle_.t() >= duration_) samples_->close();
    if (slow_file_ && cycle_.t() >= duration_) slow_file_->close();
    if (const int sig = signals.received(); sig != 0 && cycle_.t() < duration_) {
      save();
      obs_.end(run_end(sig));
      print_stop_notice(
          sig, "at t = " + format_real(cycle_.t()) + " of " + format_real(duration_) + " s",
          files_.current(), out_.path("scene.ini"), out_.dir());
      return 128 + sig;
    }
    obs_.end(run_end(0));
    files_.remove_interim();
    return 0;
  }

 private:
  void attach_observers(bool resumed) {
    attach_run_observers(
        obs_, req_, settings_, out_, resumed ? prog_.events_done : -1,
        [&](Observers& o) { o.attach<RsfFigures>(cycle_, detector_); }, [this] { save(); });
  }

  // A checkpoint between two steps: the integrator's state is exact (every double's bits),
  // so a resumed run takes the same steps and writes the same bytes. `final`: the finished
  // run's final state (checkpoint.final.bin), kept for an extension.
  void save(bool final = false) {
    prog_.wall_total = prog_.wall_events = wall_.total();
    prog_.events_done = detector_.events();
    prog_.transient_done = 0;
    Checkpoint c =
        Checkpoint::of_run(req_.scene.hash(), req_.scene.to_ini(), settings_.run.seed, prog_);
    c.engine.counters.steps = cycle_.accepted();
    c.engine.counters.events = detector_.events();
    StateWriter w;
    w.f64s(cycle_.snapshot());
    w.f64s(detector_.snapshot());
    if (slow_) w.f64s(slow_->snapshot());
    c.put(kStateName, std::move(w.bytes()));
    if (samples_) samples_->checkpoint(c);
    if (slow_file_) slow_file_->checkpoint(c);
    obs_.checkpoint(c);
    files_.save(c, final);
  }

  RunEnd run_end(int signal) const {
    RunEnd end;
    end.signal = signal;
    end.events = detector_.events();
    end.steps = cycle_.accepted();
    end.blocks = cycle_.n();
    end.total_load = settings_.rsf.chain.v_pl * cycle_.t();
    end.duration = cycle_.t();
    end.wall_seconds = end.wall_seconds_total = wall_.total();
    end.resumes = prog_.resumes;
    return end;
  }

  const RunRequest& req_;
  const Settings& settings_;
  const OutputFolder& out_;
  const CheckpointFiles files_;
  RsfCycle cycle_;
  RsfEventDetector detector_;
  const double duration_;
  RunProgress prog_;
  std::optional<BlockSamples> samples_;
  std::optional<RsfSlowSlipDetector> slow_;
  std::optional<SlowSlipFile> slow_file_;
  Observers obs_;
  RunWall wall_;
};

// drive.mode = events (engine/rsf_loader.hpp): closed forms between events, each event by the
// cycle integrator. Events before run.transient_events are run and not recorded; a checkpoint
// is taken between events only, where the engine's state is every block's closed form.
class RsfEventFigures : public RunObserver {
 public:
  explicit RsfEventFigures(const RsfEventEngine& e, double v_handover)
      : e_(e), v_handover_(v_handover) {}
  void add_to_summary(Json& summary) const override {
    const RsfModel& m = e_.model();
    Json r = Json::object();
    r.set("engine", "event-driven");
    r.set("scheme", "dopri5");
    r.set("handover_speed", v_handover_);
    r.set("creep_quantum", e_.loader().creep_quantum());
    r.set("event_integration", !e_.active_blocks() ? "whole" : e_.groups() ? "groups" : "active");
    if (e_.active_blocks()) {
      r.set("active_block_steps", e_.active_block_steps());
      r.set("alone_speed", e_.alone_speed());
      r.set("alone_tolerance", e_.alone_tolerance());
      r.set("alone_steps", static_cast<std::int64_t>(e_.loader().alone_steps()));
    }
    r.set("integrations", e_.integrations());
    r.set("syncs", e_.syncs());
    r.set("steps", e_.steps());
    r.set("time", e_.t());
    r.set("k", m.k);
    r.set("k_crit_quasi_static", rsf::critical_stiffness(m.law[0].params(), m.sigma));
    r.set("eta", m.eta);
    r.set("rows", m.rows);
    summary.set("rsf", std::move(r));
  }

 private:
  const RsfEventEngine& e_;
  double v_handover_;
};

class RsfEventRun {
 public:
  RsfEventRun(const RunRequest& req, const Settings& settings, const OutputFolder& out,
              const Checkpoint* resumed)
      : req_(req),
        settings_(settings),
        out_(out),
        files_(out.dir()),
        engine_(settings.rsf.chain, settings.rsf.tolerance, settings.rsf.v_threshold,
                settings.rsf.v_handover, settings.rsf.creep_quantum, {settings.rsf.v_init},
                settings.rsf.theta_start()),
        transient_(settings.run.transient_events),
        events_(settings.run.events) {
    engine_.set_active_blocks(settings.rsf.active_blocks);
    engine_.set_groups(settings.rsf.active_groups);
    if (engine_.active_blocks() && settings.rsf.v_alone > 0)
      engine_.set_alone_speed(settings.rsf.v_alone, settings.rsf.alone_tolerance);
    if (resumed) {
      restore_rsf_state(*resumed, [&](StateReader& r) { engine_.restore(r.f64s()); });
      prog_ = resumed->progress;
      ++prog_.resumes;
    }
    wall_.set_before(prog_.wall_total);
    attach_run_observers(
        obs_, req_, settings_, out_, resumed ? prog_.events_done : -1,
        [&](Observers& o) { o.attach<RsfEventFigures>(engine_, settings_.rsf.v_handover); },
        [this] { save(); });
    if (resumed) obs_.resume(*resumed);
  }

  int run() {
    StopSignals signals;
    obs_.start();
    const auto stop = [&] { return signals.received() && !engine_.pending(); };
    const auto advance = [&](std::int64_t done) {
      if (!engine_.pending()) obs_.advance({static_cast<double>(done), engine_.events()});
    };
    bool quiet = false;  // no block reaches V_h any more
    if (prog_.transient_done < transient_) {
      obs_.phase({"transient events", static_cast<double>(prog_.transient_done),
                  static_cast<double>(transient_)});
      while (prog_.transient_done < transient_ && !stop()) {
        if (!engine_.next(HUGE_VAL)) {
          quiet = true;
          break;
        }
        ++prog_.transient_done;
        advance(prog_.transient_done);
      }
      obs_.phase_end({static_cast<double>(prog_.transient_done), engine_.events()});
    }
    if (prog_.transient_done == transient_ && !stop() && !quiet) {
      obs_.phase({"events", static_cast<double>(prog_.events_done), static_cast<double>(events_)});
      while (prog_.events_done < events_ && !stop()) {
        auto e = engine_.next(HUGE_VAL);
        if (!e) {
          quiet = true;
          break;
        }
        e->event -= transient_;
        ++prog_.events_done;
        obs_.event(*e);
        advance(prog_.events_done);
      }
      obs_.phase_end({static_cast<double>(prog_.events_done), engine_.events()});
    }
    if (quiet)
      std::fprintf(stderr,
                   "bkquake: no block reaches rsf.handover_speed any more (every block creeps "
                   "below it); the run ends after %lld events\n",
                   static_cast<long long>(prog_.events_done));
    if (const int sig = signals.received(); sig != 0 && prog_.events_done < events_ && !quiet) {
      save();
      obs_.end(run_end(sig));
      print_stop_notice(sig,
                        "after " + std::to_string(prog_.events_done) + " of " +
                            std::to_string(events_) + " events",
                        files_.current(), out_.path("scene.ini"), out_.dir());
      return 128 + sig;
    }
    // The final state, the records of the last integration not yet returned included: a later
    // --resume with a larger run.events continues from it as an interrupted run would.
    save(true);
    obs_.end(run_end(0));
    files_.remove_interim();
    return 0;
  }

 private:
  void save(bool final = false) {
    prog_.wall_total = prog_.wall_events = wall_.total();
    Checkpoint c =
        Checkpoint::of_run(req_.scene.hash(), req_.scene.to_ini(), settings_.run.seed, prog_);
    c.engine.counters.steps = engine_.steps();
    c.engine.counters.events = engine_.events();
    StateWriter w;
    w.f64s(engine_.snapshot());
    c.put(kStateName, std::move(w.bytes()));
    obs_.checkpoint(c);
    files_.save(c, final);
  }

  RunEnd run_end(int signal) const {
    RunEnd end;
    end.signal = signal;
    end.events = prog_.events_done;
    end.transient_events = prog_.transient_done;
    end.steps = engine_.steps();
    end.blocks = engine_.model().n();
    end.total_load = settings_.rsf.chain.v_pl * engine_.t();
    end.duration = engine_.t();
    end.wall_seconds = end.wall_seconds_total = wall_.total();
    end.resumes = prog_.resumes;
    return end;
  }

  const RunRequest& req_;
  const Settings& settings_;
  const OutputFolder& out_;
  const CheckpointFiles files_;
  RsfEventEngine engine_;
  const std::int64_t transient_, events_;
  RunProgress prog_;
  Observers obs_;
  RunWall wall_;
};

}  // namespace

int run_rsf(const RunRequest& req, const Settings& settings, const OutputFolder& out,
            std::optional<RsfExtension> extension) {
  const CheckpointFiles checkpoints(out.dir());
  if (!req.resume) {
    if (checkpoints.exist() && !req.force)
      throw Error("output folder '" + out.dir() + "' holds an interrupted run (" +
                  checkpoints.current() +
                  "); use --resume to continue it or --force to start over");
    if (req.force) checkpoints.remove();
    write_file_atomic(out.path("scene.ini"), req.scene.to_ini(provenance_lines(req.scene)));
    if (settings.rsf.event_driven) return RsfEventRun(req, settings, out, nullptr).run();
    return RsfRun(req, settings, out, nullptr).run();
  }
  // Everything is checked before anything is changed: a refused resume leaves the folder as it
  // was.
  std::string from;
  Checkpoint saved;
  if (extension) {
    saved = extension->saved;
    from = extension->from;
  } else {
    saved = checkpoints.read(&from);
    check_checkpoint_matches(saved, req.scene, from);
  }
  validate_checkpoint(saved, 0, settings.stats.bin_width, from);
  const CatalogFormat format = settings.output.catalog;
  const std::string catalog =
      format == CatalogFormat::None ? "" : out.path(catalog_file_name(format));
  if (format == CatalogFormat::Csv)
    check_csv_prefix(catalog, catalog_header(catalog_layout(settings)), saved.progress.events_done,
                     saved.progress.catalog_bytes, saved_catalog_checksum(saved));
  else if (format == CatalogFormat::Hdf5)
    check_catalog_h5(catalog, saved.progress.events_done, saved_catalog_checksum(saved),
                     catalog_layout(settings));
  if (extension) from = extension->adopt(saved);
  const auto truncate = [&] {
    if (format != CatalogFormat::Csv) return;
    std::error_code ec;
    std::filesystem::resize_file(catalog, saved.progress.catalog_bytes, ec);
    if (ec) throw Error("cannot truncate '" + catalog + "' to its checkpoint: " + ec.message());
  };
  const auto resuming = [&] {
    std::printf("bkquake: resuming '%s' from %s (%lld events so far)\n", out.dir().c_str(),
                from.c_str(), static_cast<long long>(saved.progress.events_done));
    std::fflush(stdout);
  };
  if (settings.rsf.event_driven) {
    RsfEventRun run(req, settings, out, &saved);
    truncate();
    resuming();
    return run.run();
  }
  RsfRun run(req, settings, out, &saved);
  truncate();
  resuming();
  return run.run();
}

}  // namespace bkq
