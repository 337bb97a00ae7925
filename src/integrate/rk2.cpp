// The rk2 stepper's code, compiled here (see rk2.hpp).
#include "integrate/rk2.hpp"

namespace bkq {
template class ExplicitScheme<Rk2Method>;
template bool relax_cluster<Rk2Method>(const ChainForces&, ClusterRelaxation&);
}  // namespace bkq
