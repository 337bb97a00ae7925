// The verlet stepper's code, compiled here (see verlet.hpp).
#include "integrate/verlet.hpp"

namespace bkq {
template class ExplicitScheme<VerletMethod>;
}  // namespace bkq
