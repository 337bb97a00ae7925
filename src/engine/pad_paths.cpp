// The event engine's cluster path with the pad moving (integrate/cluster.hpp): the
// cluster's shape and bookkeeping are relax_cluster's; this adds what the pad's form reads
// (the force tree's extremes over the far stuck blocks, the pad damper's weight).
#include "engine/event_engine.hpp"
#include "integrate/cluster.hpp"

namespace bkq {

bool EventEngine::relax_pad_cluster(ClusterRelaxation& r) {
  r.far_max = tree_.max();
  r.far_min = tree_.min();
  r.half_dt_cp = 0.5 * dt_ * forces_.params().c_p;
  return stepper_.relax_pad_cluster(forces_, r);
}

}  // namespace bkq
