// The accuracy.csv schema (see accuracy_schema.hpp). Measured columns are left blank where
// nothing was measured: a point not run, or per-event errors of the reference rows.
#include "io/accuracy_schema.hpp"

namespace bkq {

const Schema& accuracy_schema() {
  static const Schema schema = {
      {"scheme", "", "integrator.scheme, or reference / noise-floor for the first two rows", kText},
      {"transitions", "",
       "where stick and slip happen: step or located (integrator.transitions; adaptive and the "
       "reference rows: located, theta: projection)",
       kText},
      {"dt", "time", "time step (the adaptive scheme: its macro step)"},
      {"tolerance", "",
       "local error tolerance of the adaptive scheme and the reference rows, 0 for the others"},
      {"status", "", "ok, unstable (dt above the scheme's limit, not run) or failed", kText},
      {"sampled_events", "", "pre-event states the per-event errors are taken over", kInteger},
      {"moment_error_median", "", "median over the sampled events of |M - M_ref| / M_ref"},
      {"moment_error_max", "", "largest |M - M_ref| / M_ref over the sampled events"},
      {"duration_error_median", "", "median over the sampled events of |T - T_ref| / T_ref"},
      {"duration_error_max", "", "largest |T - T_ref| / T_ref over the sampled events"},
      {"sampled_single", "",
       "sampled events in which one block slips (in the reference), the medians below are over "
       "them",
       kInteger},
      {"moment_error_median_single", "", "median of |M - M_ref| / M_ref over single-block events"},
      {"duration_error_median_single", "",
       "median of |T - T_ref| / T_ref over single-block events"},
      {"ks_distance", "",
       "Kolmogorov-Smirnov distance of the long run's magnitude distribution from the "
       "reference run's"},
      {"b", "", "binned maximum-likelihood b of the long run on the reference's fit window"},
      {"b_shift", "", "b minus the reference run's b"},
      {"seconds_per_event", "wall s", "wall-clock seconds per event of the long run"},
      {"steps_per_event", "", "relaxation steps per event of the long run"},
      {"note", "", "why a point is not ok, or what a reference row is (double-quoted)", kText},
  };
  return schema;
}

const Schema& accuracy_orders_schema() {
  static const Schema schema = {
      {"scheme", "", "integrator.scheme (the fixed-step schemes)", kText},
      {"transitions", "", "step or located (integrator.transitions), projection for theta", kText},
      {"quantity", "", "moment or duration: whose median per-event relative error is fitted",
       kText},
      {"events", "", "all sampled events, or single (those in which one block slips)", kText},
      {"order", "",
       "least-squares slope of log(median error) against log(dt) over the points used; blank "
       "with fewer than two"},
      {"points", "", "ladder points used: status ok and error above 10 x the floor", kInteger},
      {"dt_min", "time", "smallest dt used"},
      {"dt_max", "time", "largest dt used"},
      {"floor", "",
       "the reference's own error floor: median relative difference between the reference "
       "and a reference at 10 x its tolerance"},
  };
  return schema;
}

}  // namespace bkq
