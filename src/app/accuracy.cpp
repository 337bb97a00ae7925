// The work–precision study; see accuracy.hpp.
#include "app/accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/event_engine.hpp"
#include "engine/initial_state.hpp"
#include "integrate/located.hpp"
#include "integrate/stepper.hpp"
#include "io/accuracy_schema.hpp"
#include "io/json.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/histogram.hpp"

namespace bkq {

namespace {

// An event that needs more steps than this is reported as failed rather than waited for.
constexpr std::int64_t kMaxStepsPerEvent = 20'000'000;
// Macro step of the per-event reference (see sample_states).
constexpr double kReferenceMacroStep = 1e-3;

struct Reference {
  double moment = 0, duration = 0;
  int blocks = 0;
};

struct LongRun {
  MagnitudeHistogram hist;
  double seconds_per_event = 0, steps_per_event = 0;
};

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double relative_error(double value, double reference) {
  return reference != 0 ? std::abs(value - reference) / std::abs(reference) : std::abs(value);
}

class Study {
 public:
  Study(const Settings& settings, const AccuracyOptions& opt)
      : settings_(settings),
        opt_(opt),
        reference_(accuracy_reference_scheme()),
        p_(settings.model),
        forces_(p_),
        dt_(settings.integrator.dt),
        seed_(settings.run.seed),
        transient_(settings.run.transient_events),
        bin_width_(settings.stats.bin_width) {
    EventEngine::check_model(p_);
  }

  // Pre-event states sampled from a run of the scene's own stepper, and the reference
  // relaxation of the event that follows each.
  void sample_states() {
    const auto stepper = stepper_of(settings_.integrator, p_.n);
    check_time_step(*stepper, p_, dt_);
    EventEngine engine(forces_, *stepper, dt_, start(seed_));
    for (std::int64_t i = 0; i < transient_; ++i) engine.next_event();
    for (int k = 0; k < opt_.samples; ++k) {
      for (int i = 0; i < opt_.sample_spacing; ++i) engine.next_event();
      states_.push_back(engine.snapshot());
    }
    // The engine checks stuck blocks outside the integrated ranges once per macro step;
    // a short macro step keeps that lag out of the reference.
    const auto reference = make_stepper(reference_, p_.n, opt_.reference_tolerance);
    // The reference's own error floor: its difference from a reference at 10x its tolerance
    // (whose error is the larger, so this bounds the floor from above).
    const auto looser =
        make_stepper(reference_, p_.n, std::min(10.0 * opt_.reference_tolerance, 1e-2));
    std::vector<double> fm, fd, fm1, fd1;
    for (const EngineSnapshot& s : states_) {
      EventEngine e(forces_, *reference, std::min(dt_, kReferenceMacroStep), s);
      const EventRecord r = e.next_event();
      references_.push_back({r.moment, r.duration, r.blocks});
      EventEngine l(forces_, *looser, std::min(dt_, kReferenceMacroStep), s);
      const EventRecord q = l.next_event();
      fm.push_back(relative_error(q.moment, r.moment));
      fd.push_back(relative_error(q.duration, r.duration));
      if (r.blocks == 1) {
        fm1.push_back(fm.back());
        fd1.push_back(fd.back());
      }
    }
    floor_ = {median(fm), median(fm1), median(fd), median(fd1)};
  }
  const ReferenceFloor& floor() const { return floor_; }

  // The reference long run and the noise floor (the reference from another seed).
  std::vector<AccuracyPoint> reference_rows(AccuracyStudy& study) {
    const auto reference = make_stepper(reference_, p_.n, opt_.long_reference_tolerance);
    reference_run_ = long_run(*reference, dt_, seed_);
    const GrFit fit = fit_histogram(reference_run_.hist, std::nullopt, std::nullopt);
    study.mu_min = fit.mu_min;
    study.mu_max = fit.mu_max;
    window_min_ = fit.mu_min;  // every other run's b is fitted on this window
    window_max_ = fit.mu_max;
    b_reference_ = fit.b_mle;

    AccuracyPoint ref;
    ref.scheme = "reference";
    ref.transitions = "located";
    ref.dt = dt_;
    ref.tolerance = opt_.long_reference_tolerance;
    ref.note = "long-run reference";
    ref.b = b_reference_;
    ref.seconds_per_event = reference_run_.seconds_per_event;
    ref.steps_per_event = reference_run_.steps_per_event;

    const auto other = make_stepper(reference_, p_.n, opt_.long_reference_tolerance);
    LongRun floor_run = long_run(*other, dt_, seed_ + opt_.other_seed_offset);
    AccuracyPoint floor = ref;
    floor.scheme = "noise-floor";
    floor.note = "reference from seed + " + std::to_string(opt_.other_seed_offset);
    fill_statistics(floor, floor_run);
    return {ref, floor};
  }

  AccuracyPoint measure(const std::string& scheme, double dt, double tolerance,
                        const std::string& transitions) {
    AccuracyPoint pt;
    pt.scheme = scheme;
    pt.dt = dt;
    pt.tolerance = scheme_traits(scheme)->error_control ? tolerance : 0.0;
    auto stepper = make_stepper(scheme, p_.n, tolerance > 0 ? tolerance : 1e-8);
    if (stepper->stick_rule() == StickRule::Crossing) {
      pt.transitions = transitions;
      if (transitions == "located") stepper = with_located_transitions(std::move(stepper), p_.n);
    } else {
      pt.transitions = stepper->stick_rule() == StickRule::Located ? "located" : "projection";
    }
    const double limit = stability_limit(*stepper, p_);
    if (dt > limit) {
      pt.status = "unstable";
      char note[80];
      std::snprintf(note, sizeof note, "dt above the stability limit %.4g", limit);
      pt.note = note;
      return pt;
    }
    try {
      std::vector<double> dm, dd, dm1, dd1;
      for (std::size_t k = 0; k < states_.size(); ++k) {
        EventEngine e(forces_, *stepper, dt, states_[k]);
        e.max_steps_per_event = kMaxStepsPerEvent;
        const EventRecord r = e.next_event();
        dm.push_back(relative_error(r.moment, references_[k].moment));
        dd.push_back(relative_error(r.duration, references_[k].duration));
        if (references_[k].blocks == 1) {
          dm1.push_back(dm.back());
          dd1.push_back(dd.back());
        }
      }
      pt.sampled = static_cast<int>(dm.size());
      pt.moment_error_median = median(dm);
      pt.duration_error_median = median(dd);
      pt.sampled_single = static_cast<int>(dm1.size());
      pt.moment_error_median_single = median(dm1);
      pt.duration_error_median_single = median(dd1);
      pt.moment_error_max = dm.empty() ? 0 : *std::max_element(dm.begin(), dm.end());
      pt.duration_error_max = dd.empty() ? 0 : *std::max_element(dd.begin(), dd.end());
      LongRun run = long_run(*stepper, dt, seed_);
      fill_statistics(pt, run);
    } catch (const Error& err) {
      pt.status = "failed";
      pt.note = err.what();
    }
    return pt;
  }

 private:
  ChainState start(std::uint64_t seed) const {
    return initial_state(forces_, seed, settings_.run.initial_disorder, true);
  }

  LongRun long_run(Stepper& stepper, double dt, std::uint64_t seed) {
    EventEngine engine(forces_, stepper, dt, start(seed));
    engine.max_steps_per_event = kMaxStepsPerEvent;
    for (std::int64_t i = 0; i < transient_; ++i) engine.next_event();
    LongRun run{MagnitudeHistogram(bin_width_), 0, 0};
    const double load0 = engine.load();
    const std::int64_t steps0 = engine.counters().steps;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::int64_t i = 0; i < opt_.long_events; ++i) {
      const EventRecord e = engine.next_event();
      if (e.moment > 0) run.hist.add(e.magnitude);
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.hist.set_loading(engine.load() - load0, p_.n);
    const double events = static_cast<double>(std::max<std::int64_t>(opt_.long_events, 1));
    run.seconds_per_event = wall / events;
    run.steps_per_event = static_cast<double>(engine.counters().steps - steps0) / events;
    return run;
  }

  void fill_statistics(AccuracyPoint& pt, LongRun& run) {
    pt.ks_distance = ks_binned(run.hist, reference_run_.hist);
    try {
      pt.b = fit_histogram(run.hist, window_min_, window_max_).b_mle;
      pt.b_shift = pt.b - b_reference_;
    } catch (const Error& err) {
      pt.b = pt.b_shift = std::nan("");
      pt.note = std::string("b not fitted: ") + err.what();
    }
    pt.seconds_per_event = run.seconds_per_event;
    pt.steps_per_event = run.steps_per_event;
  }
  const Settings& settings_;
  const AccuracyOptions& opt_;
  std::string reference_;  // the reference scheme's keyword (accuracy_reference_scheme)
  ModelParams p_;
  ChainForces forces_;
  double dt_;
  std::uint64_t seed_;
  std::int64_t transient_;
  double bin_width_;
  std::vector<EngineSnapshot> states_;
  std::vector<Reference> references_;
  LongRun reference_run_{MagnitudeHistogram(), 0, 0};
  double b_reference_ = 0;
  std::optional<double> window_min_, window_max_;
  ReferenceFloor floor_;
};

// Least-squares slope of log(y) against log(x).
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

double ks_binned(const MagnitudeHistogram& a, const MagnitudeHistogram& b) {
  if (a.empty() || b.empty()) return 1.0;
  const double na = static_cast<double>(a.events()), nb = static_cast<double>(b.events());
  double d = 0;
  std::int64_t ca = 0, cb = 0;
  for (std::int64_t k = std::min(a.first_bin(), b.first_bin());
       k <= std::max(a.last_bin(), b.last_bin()); ++k) {
    ca += a.count(k);
    cb += b.count(k);
    d = std::max(d, std::abs(static_cast<double>(ca) / na - static_cast<double>(cb) / nb));
  }
  return d;
}

void check_accuracy_options(const AccuracyOptions& options) {
  const auto check = [](const char* option, std::int64_t value, std::int64_t lo, std::int64_t hi) {
    if (value < lo || value > hi)
      throw Error(std::string("accuracy: --") + option + ": expected an integer in [" +
                  std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                  std::to_string(value));
  };
  check("samples", options.samples, 1, kMaxAccuracySamples);
  check("spacing", options.sample_spacing, 1, kMaxAccuracySpacing);
  check("long-events", options.long_events, kMinLongEvents, kMaxLongEvents);
  for (const std::string& scheme : options.schemes)
    if (scheme_traits(scheme) == nullptr) {
      std::string valid;
      for (const auto& k : stepper_keywords()) valid += (valid.empty() ? "" : "|") + k;
      throw Error("accuracy: --schemes: '" + scheme + "' is not a scheme; expected a list of " +
                  valid);
    }
}

std::string accuracy_reference_scheme() {
  for (const std::string& scheme : stepper_keywords())
    if (scheme_traits(scheme)->error_control) return scheme;
  throw Error(
      "accuracy: no scheme of the registry controls its own error (error_control); the "
      "study's reference needs one");
}

AccuracyStudy run_accuracy(const Scene& scene, const AccuracyOptions& options,
                           const std::function<void(const AccuracyPoint&)>& report) {
  check_accuracy_options(options);
  AccuracyStudy study;
  const Settings settings = settings_from_scene(scene);
  // Its reference (the adaptive scheme among the shipped ones) is written for chains of
  // nearest-neighbour springs.
  if (settings.model.lattice() || settings.model.long_range() || settings.model.viscous())
    throw Error(std::string("accuracy: ") +
                (settings.model.lattice() ? "model.rows = " + std::to_string(settings.model.rows)
                 : settings.model.long_range()
                     ? "model.range = " + std::to_string(settings.model.range)
                     : "model.viscosity = " + format_real(settings.model.viscosity)) +
                ": the study's reference (the adaptive scheme with located transitions) is "
                "written for chains of nearest-neighbour springs without dashpots; allowed: "
                "model.rows = 1, model.coupling = nearest, model.viscosity = 0");
  Study s(settings, options);
  s.sample_states();
  for (AccuracyPoint& row : s.reference_rows(study)) {
    if (report) report(row);
    study.points.push_back(std::move(row));
  }
  for (const std::string& scheme : options.schemes) {
    const SchemeTraits& traits = *scheme_traits(scheme);
    if (traits.error_control) {
      for (double tol : options.tolerances) {
        study.points.push_back(s.measure(scheme, settings.integrator.dt, tol, "located"));
        if (report) report(study.points.back());
      }
      continue;
    }
    // Each transition mode asked for, for the Crossing schemes (located: the locatable
    // ones); the others resolve their own.
    std::vector<std::string> modes;
    if (traits.stick_rule != StickRule::Crossing)
      modes = {"step"};
    else
      for (const std::string& t : options.transitions)
        if (t != "located" || traits.locatable) modes.push_back(t);
    for (const std::string& transitions : modes)
      for (double dt : options.dts) {
        study.points.push_back(s.measure(scheme, dt, 0.0, transitions));
        if (report) report(study.points.back());
      }
  }
  fit_orders(study, s.floor());
  return study;
}

void fit_orders(AccuracyStudy& study, const ReferenceFloor& floor) {
  study.orders.clear();
  // The fixed-step (scheme, transitions) pairs in the order of the points.
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const AccuracyPoint& p : study.points) {
    if (p.tolerance > 0 || p.scheme == "reference" || p.scheme == "noise-floor") continue;
    const std::pair<std::string, std::string> key{p.scheme, p.transitions};
    if (std::find(pairs.begin(), pairs.end(), key) == pairs.end()) pairs.push_back(key);
  }
  struct Quantity {
    const char *quantity, *events;
    double AccuracyPoint::*median;
    double floor;
  };
  const Quantity quantities[] = {
      {"moment", "all", &AccuracyPoint::moment_error_median, floor.moment_all},
      {"moment", "single", &AccuracyPoint::moment_error_median_single, floor.moment_single},
      {"duration", "all", &AccuracyPoint::duration_error_median, floor.duration_all},
      {"duration", "single", &AccuracyPoint::duration_error_median_single, floor.duration_single},
  };
  for (const auto& [scheme, transitions] : pairs)
    for (const Quantity& q : quantities) {
      AccuracyOrder o{scheme, transitions, q.quantity, q.events, std::nan(""), 0, 0, 0, q.floor};
      std::vector<double> dts, errors;
      for (const AccuracyPoint& p : study.points) {
        if (p.scheme != scheme || p.transitions != transitions || p.tolerance > 0 ||
            p.status != "ok" || p.sampled == 0)
          continue;
        const double e = p.*q.median;
        // A floor of NaN (no such events) leaves every point out.
        if (!(e > 10.0 * q.floor) || !std::isfinite(e)) continue;
        dts.push_back(p.dt);
        errors.push_back(e);
      }
      o.points = static_cast<int>(dts.size());
      if (!dts.empty()) {
        o.dt_min = *std::min_element(dts.begin(), dts.end());
        o.dt_max = *std::max_element(dts.begin(), dts.end());
      }
      if (o.points >= 2 && o.dt_min < o.dt_max) o.order = log_log_slope(dts, errors);
      study.orders.push_back(o);
    }
}

namespace {
std::string csv_field(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}
}  // namespace

std::string accuracy_csv(const AccuracyStudy& study) {
  std::string out = header_of(accuracy_schema()) + "\n";
  for (const AccuracyPoint& p : study.points) {
    out += p.scheme + ',' + p.transitions + ',' + format_real(p.dt) + ',' +
           format_real(p.tolerance) + ',' + p.status + ',' + std::to_string(p.sampled);
    // Blank where nothing was measured: not run, or (reference rows) no per-event errors.
    const bool ran = p.status == "ok", per_event = ran && p.sampled > 0;
    for (double v :
         {p.moment_error_median, p.moment_error_max, p.duration_error_median, p.duration_error_max})
      out += ',' + (per_event ? format_real(v) : std::string());
    out += ',' + (per_event ? std::to_string(p.sampled_single) : std::string());
    // No single-block event among the samples: nothing to take a median of.
    const bool single = per_event && p.sampled_single > 0;
    for (double v : {p.moment_error_median_single, p.duration_error_median_single})
      out += ',' + (single ? format_real(v) : std::string());
    for (double v : {p.ks_distance, p.b, p.b_shift, p.seconds_per_event, p.steps_per_event})
      out += ',' + (ran ? format_real(v) : std::string());
    out += ',' + csv_field(p.note) + '\n';
  }
  return out;
}

std::string accuracy_orders_csv(const AccuracyStudy& study) {
  std::string out = header_of(accuracy_orders_schema()) + "\n";
  for (const AccuracyOrder& o : study.orders) {
    const bool fitted = std::isfinite(o.order), used = o.points > 0;
    out += o.scheme + ',' + o.transitions + ',' + o.quantity + ',' + o.events + ',' +
           (fitted ? format_real(o.order) : std::string()) + ',' + std::to_string(o.points) + ',' +
           (used ? format_real(o.dt_min) : std::string()) + ',' +
           (used ? format_real(o.dt_max) : std::string()) + ',' +
           (std::isfinite(o.floor) ? format_real(o.floor) : std::string()) + '\n';
  }
  return out;
}

std::string accuracy_table(const AccuracyStudy& study) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-11s %-10s %8s %8s %11s %11s %9s %8s %11s %9s  %s\n", "scheme",
                "transits", "dt", "tol", "dM/M med", "dT/T med", "KS", "db", "s/event", "steps/ev",
                "status");
  out += line;
  for (const AccuracyPoint& p : study.points) {
    if (p.status != "ok") {
      std::snprintf(line, sizeof line,
                    "%-11s %-10s %8.3g %8s %11s %11s %9s %8s %11s %9s  %s (%s)\n", p.scheme.c_str(),
                    p.transitions.c_str(), p.dt,
                    p.tolerance > 0 ? format_real(p.tolerance).c_str() : "-", "", "", "", "", "",
                    "", p.status.c_str(), p.note.c_str());
    } else {
      char dm[32] = "-", dd[32] = "-";
      if (p.sampled > 0) {
        std::snprintf(dm, sizeof dm, "%.3g", p.moment_error_median);
        std::snprintf(dd, sizeof dd, "%.3g", p.duration_error_median);
      }
      std::snprintf(line, sizeof line,
                    "%-11s %-10s %8.3g %8s %11s %11s %9.4f %+8.4f %11.3g %9.4g  ok\n",
                    p.scheme.c_str(), p.transitions.c_str(), p.dt,
                    p.tolerance > 0 ? format_real(p.tolerance).c_str() : "-", dm, dd, p.ks_distance,
                    p.b_shift, p.seconds_per_event, p.steps_per_event);
    }
    out += line;
  }
  std::snprintf(line, sizeof line,
                "b fitted on mu in [%.2f, %.2f) (the reference run's automatic window)\n",
                study.mu_min, study.mu_max);
  out += line;
  if (study.orders.empty()) return out;
  out +=
      "observed orders (slope of log median error vs log dt; points within 10x of the "
      "reference's floor left out):\n";
  std::snprintf(line, sizeof line, "%-11s %-10s %10s %10s %10s %10s\n", "scheme", "transits",
                "M all", "M single", "T all", "T single");
  out += line;
  for (std::size_t i = 0; i + 3 < study.orders.size(); i += 4) {
    char cells[4][32];
    for (int k = 0; k < 4; ++k) {
      const AccuracyOrder& o = study.orders[i + k];
      if (std::isfinite(o.order))
        std::snprintf(cells[k], sizeof cells[k], "%.2f (%d)", o.order, o.points);
      else
        std::snprintf(cells[k], sizeof cells[k], "- (%d)", o.points);
    }
    std::snprintf(line, sizeof line, "%-11s %-10s %10s %10s %10s %10s\n",
                  study.orders[i].scheme.c_str(), study.orders[i].transitions.c_str(), cells[0],
                  cells[1], cells[2], cells[3]);
    out += line;
  }
  return out;
}

}  // namespace bkq
