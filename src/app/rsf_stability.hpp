// `bkquake stability` of a rate-and-state scene whose blocks have their own laws (rsf.blocks,
// rsf.pattern): the modal analysis of rsf_run.hpp's rsf_stability assumes one law, so these
// scenes get the dense linearisation of stats/rsf_stability.hpp instead.
#pragma once

#include "app/rsf_run.hpp"

namespace bkq {

// stability.csv's rows (one per eigenvalue, complex pairs once, "dense i" in decreasing
// growth), rsf_stability.csv (the same columns as one law's; the k_crit columns are nan, since
// a critical stiffness belongs to one block's law) and the lines printed: the largest growth
// rate and its frequency, and the blocks' range of sigma (b - a)/D_c. A bkq::Error above
// kRsfDenseLimit blocks.
RsfStabilityReport rsf_dense_stability(const Settings& settings);

}  // namespace bkq
