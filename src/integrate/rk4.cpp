// The rk4 stepper's code, compiled here (see rk4.hpp).
#include "integrate/rk4.hpp"

namespace bkq {
template class ExplicitScheme<Rk4Method>;
template bool relax_cluster<Rk4Method>(const ChainForces&, ClusterRelaxation&);
}  // namespace bkq
