// The stencil kernel path: on a lattice or a chain whose springs reach beyond j +- 1, the
// covered sites stepped by the scheme's kernel over a run-time neighbour structure
// (integrate/stencil_kernel.hpp) for as long as the covered ranges stay as they are (no
// site breaks loose, no refit that changes them). The same events bit for bit as the
// general step, in less time. The pad held, no dashpots, Crossing schemes that declare the
// kernel (SchemeTraits::stencil_kernel); the general path takes the rest.
#pragma once

#include <cstdint>

#include "engine/relaxation.hpp"
#include "integrate/stencil_kernel.hpp"

namespace bkq {

class StencilPath final : public RelaxationPath {
 public:
  const char* name() const override { return "stencil"; }
  bool advance(Relaxation& rx, PathReport& out) override;
  // Steps taken here (a study count).
  std::int64_t steps() const { return steps_; }

 private:
  StencilRelaxation r_;
  std::int64_t steps_ = 0;
};

}  // namespace bkq
