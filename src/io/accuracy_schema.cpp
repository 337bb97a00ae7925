// The accuracy.csv schema (see accuracy_schema.hpp). Measured columns are left blank where
// nothing was measured: a point not run, or per-event errors of the reference rows.
#include "io/accuracy_schema.hpp"

namespace bkq {

const Schema& accuracy_schema() {
  static const Schema schema = {
      {"scheme", "", "integrator.scheme, or reference / noise-floor for the first two rows", kText},
      {"dt", "time", "time step (the adaptive scheme: its macro step)"},
      {"tolerance", "",
       "local error tolerance of the adaptive scheme and the reference rows, 0 for the others"},
      {"status", "", "ok, unstable (dt above the scheme's limit, not run) or failed", kText},
      {"sampled_events", "", "pre-event states the per-event errors are taken over", kInteger},
      {"moment_error_median", "", "median over the sampled events of |M - M_ref| / M_ref"},
      {"moment_error_max", "", "largest |M - M_ref| / M_ref over the sampled events"},
      {"duration_error_median", "", "median over the sampled events of |T - T_ref| / T_ref"},
      {"duration_error_max", "", "largest |T - T_ref| / T_ref over the sampled events"},
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

}  // namespace bkq
