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
  // Release tests of stuck sites taken and skipped by the kernel's bound (study counts).
  std::int64_t release_tests() const { return r_.tests; }
  std::int64_t skipped_tests() const { return r_.skipped; }
  // Tests only: take each skipped test anyway and count in `check` how it compares.
  void check_skips(StencilRelaxation::SkipCheck* check) { r_.check = check; }

 private:
  StencilRelaxation r_;
  std::int64_t steps_ = 0;
};

}  // namespace bkq
