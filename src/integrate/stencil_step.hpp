// The declaration of a scheme's step over a run-time neighbour structure (the stencil
// kernel, integrate/stencil_kernel.hpp), which an explicit scheme declares in its traits.
// Compiled once per scheme in integrate/stencil_kernel.cpp, so that the schemes' own files
// do not compile it.
#pragma once

namespace bkq {

class ChainForces;
struct StencilRelaxation;

// Runs the stencil relaxation with Method's step; false where it has no kernel for the
// scene's law and terms (the general path then takes the steps).
template <class Method>
bool run_stencil(const ChainForces& forces, StencilRelaxation& r);

}  // namespace bkq
