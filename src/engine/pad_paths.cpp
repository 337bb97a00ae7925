// The event engine's cluster path with the pad moving (integrate/pad_cluster.hpp): the
// cluster's shape and bookkeeping are relax_cluster's; this adds what the pad's form reads
// (the force tree's extremes over the far stuck blocks, the pad damper's weight).
#include "engine/event_engine.hpp"
#include "integrate/pad_cluster.hpp"

namespace bkq {

bool EventEngine::relax_pad_cluster(ClusterRelaxation& r) {
  PadClusterRelaxation pr;
  static_cast<ClusterRelaxation&>(pr) = r;
  pr.far_max = tree_.max();
  pr.far_min = tree_.min();
  pr.half_dt_cp = 0.5 * dt_ * forces_.params().c_p;
  if (!stepper_.relax_pad_cluster(forces_, pr)) return false;
  r = pr;
  return true;
}

}  // namespace bkq
