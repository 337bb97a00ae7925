// The verlet stepper's code, compiled here (see verlet.hpp).
#include "integrate/verlet.hpp"

namespace bkq {
template class ExplicitScheme<VerletMethod>;
template bool relax_cluster<VerletMethod>(const ChainForces&, ClusterRelaxation&);
}  // namespace bkq
