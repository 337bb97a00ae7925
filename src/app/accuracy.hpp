// The work–precision study behind `bkquake accuracy` (docs/explanation/accuracy.md):
// how much precision each second buys, for the user's own scene, driven event by event.
//
// Every point is one scheme at one dt (the adaptive scheme: one tolerance, at the scene's
// dt as its macro step), measured three ways:
//  (a) Per-event error. K pre-event states are sampled from one run of the scene's own
//      stepper (after the transient, every `sample_spacing` events). From each state the
//      scheme and the reference (the event-located adaptive scheme at
//      `reference_tolerance`) relax the same event; the errors are |M - M_ref| / M_ref of
//      the moment and |T - T_ref| / T_ref of the duration, median and maximum over the K.
//      (The reference runs with a 1e-3 macro step: the engine checks stuck blocks outside
//      the integrated ranges once per macro step.)
//  (b) Statistics. A long run (`long_events` after the transient, the scene's seed for
//      every point) gives the magnitude distribution: its Kolmogorov–Smirnov distance
//      to the reference run's (on the histogram's bins, see ks_binned), and the shift of b (binned
//      MLE on the window the automatic fit picks for the reference run). The noise floor is the
//      same two numbers between the reference run and a reference run from another seed: below it a
//      scheme's statistics are as good as the reference's.
//  (c) Cost: wall seconds per event of the long run (and steps per event).
// The fixed-step schemes run with each transition mode asked for (integrator.transitions:
// step, located). Per scheme and mode the study fits the observed order: the least-squares
// slope of log median per-event error against log dt over the ladder's stable points,
// leaving out points within 10x of the reference's own error floor (the median difference
// between the reference and a reference at 10x its tolerance), for the moment and the
// duration, over all sampled events and over those in which one block slips.
// A dt above a scheme's stability limit stays in the table as "unstable" (not run); a run
// that fails (non-finite state, an event that does not end) as "failed".
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "stats/histogram.hpp"

namespace bkq {

struct AccuracyOptions {
  // The registry's schemes, shipped and registered, in its order (stepper_keywords()).
  std::vector<std::string> schemes = stepper_keywords();
  std::vector<double> dts{0.05, 0.02, 0.01, 0.005, 0.002, 0.001};
  std::vector<double> tolerances{1e-3, 1e-5, 1e-7, 1e-9};   // schemes with error_control
  std::vector<std::string> transitions{"step", "located"};  // Crossing schemes (located:
                                                            // the locatable ones)
  int samples = 40;                        // K pre-event states for the per-event errors
  int sample_spacing = 25;                 // events between two sampled states
  std::int64_t long_events = 50000;        // events per long run, after the scene's transient
  double reference_tolerance = 1e-12;      // per-event reference
  double long_reference_tolerance = 1e-9;  // reference long runs (cost grows fast below)
  std::uint64_t other_seed_offset = 1;     // the noise-floor run uses seed + this
};

// The sizes a study accepts: finite, so a typo cannot start a run of years. Each sample is
// relaxed once per scheme and dt and by the reference; samples x spacing events are run to
// sample the states (at most 10^9).
inline constexpr int kMaxAccuracySamples = 10000;
inline constexpr int kMaxAccuracySpacing = 100000;
inline constexpr std::int64_t kMinLongEvents = 100;
inline constexpr std::int64_t kMaxLongEvents = 1000000000000;

// Checks samples, sample_spacing and long_events against those ranges; bkq::Error naming the
// option (--samples, --spacing, --long-events), the value and the range otherwise.
void check_accuracy_options(const AccuracyOptions& options);

struct AccuracyPoint {
  std::string scheme;
  std::string transitions = "step";  // step | located | projection (theta)
  double dt = 0;
  double tolerance = 0;       // adaptive only (0 otherwise)
  std::string status = "ok";  // ok | unstable | failed
  std::string note;           // why, when not ok
  int sampled = 0;
  double moment_error_median = 0, moment_error_max = 0;
  double duration_error_median = 0, duration_error_max = 0;
  int sampled_single = 0;  // sampled events in which one block slips (the reference's count)
  double moment_error_median_single = 0, duration_error_median_single = 0;
  double ks_distance = 0, b = 0, b_shift = 0;
  double seconds_per_event = 0, steps_per_event = 0;
};

// The observed order of one scheme and transition mode (accuracy_orders.csv).
struct AccuracyOrder {
  std::string scheme, transitions;
  std::string quantity;  // moment | duration
  std::string events;    // all | single
  double order = 0;      // NaN with fewer than two points
  int points = 0;
  double dt_min = 0, dt_max = 0;
  double floor = 0;  // the reference's own error floor
};

struct AccuracyStudy {
  std::vector<AccuracyPoint> points;  // the first two rows: the reference and the noise floor
  std::vector<AccuracyOrder> orders;
  double mu_min = 0, mu_max = 0;  // the b-fit window
};

// Runs the study (options checked first); `report` (if set) is told about each point as it
// is finished.
// The study's reference scheme: the first of the registry's (stepper_keywords()) that
// declares error_control ("adaptive" among the shipped ones); bkq::Error when none does.
std::string accuracy_reference_scheme();

AccuracyStudy run_accuracy(const Scene& scene, const AccuracyOptions& options,
                           const std::function<void(const AccuracyPoint&)>& report = {});

// accuracy.csv: the header line, then one row per point.
std::string accuracy_csv(const AccuracyStudy& study);
// accuracy_orders.csv: the header line, then one row per observed order.
std::string accuracy_orders_csv(const AccuracyStudy& study);
// The observed orders of the study's fixed-step points (fills study.orders), given the
// reference's floors: moment and duration, all events and single-block ones.
struct ReferenceFloor {
  double moment_all = 0, moment_single = 0, duration_all = 0, duration_single = 0;
};
void fit_orders(AccuracyStudy& study, const ReferenceFloor& floor);
// The table printed at the end of `bkquake accuracy`.
std::string accuracy_table(const AccuracyStudy& study);

// Kolmogorov–Smirnov distance sup |F_a - F_b| between two magnitude distributions, on
// their bins. On the bins, not the raw magnitudes: many events are single-block slips
// whose moment is one number (a point mass of the distribution), and a scheme's tiny
// error in that number would otherwise move the whole point mass past the reference's.
double ks_binned(const MagnitudeHistogram& a, const MagnitudeHistogram& b);

}  // namespace bkq
