// What a time-stepping scheme supports, declared once by the scheme (its class's kTraits)
// and read from there by everyone who needs to know: the event engine through
// Stepper::traits(), the scene's rules and the settings through scheme_traits(keyword).
// Nobody tests a scheme's type or compares its name to find out what it can do.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace bkq {

class ChainForces;
struct ClusterRelaxation;
struct StencilRelaxation;

// How a stepper resolves stick and slip transitions (integrate/stepper.hpp says what each
// rule does).
enum class StickRule { Crossing, Projection, Located };

struct SchemeTraits {
  StickRule stick_rule = StickRule::Crossing;
  // integrator.transitions = located may wrap it (integrate/located.hpp): transitions
  // located on its dense output instead of at the end of its step. Crossing schemes only.
  bool locatable = false;
  // It is such a wrapper: transitions located on a fixed-step scheme. It reports the work
  // of each step piece by piece (InStepTransitions::work) and covers the neighbours of the
  // blocks it releases inside a step itself.
  bool located_on_fixed_steps = false;
  // Its step works on every force kernel: lattices, couplings beyond the nearest
  // neighbours and dashpots (the others read j +- 1 only).
  bool general_kernels = false;
  // Its step written for a fixed-size cluster of a few blocks between two that hold
  // (integrate/cluster.hpp; with the pad moving, ClusterRelaxation's pad fields set), null
  // where it has none; it returns false when it has no form for that cluster (the event
  // engine then takes the general step).
  bool (*cluster_kernel)(const ChainForces&, ClusterRelaxation&) = nullptr;
  // Its step fuses its stages over ranges whose end blocks hold (Stepper::step_held).
  bool fused_kernels = false;
  // It controls its own step size to integrator.tolerance (the accuracy reference).
  bool error_control = false;
  // Its step over a run-time neighbour structure (lattices, range and power stencils:
  // integrate/stencil_kernel.hpp), null where it has none.
  bool (*stencil_kernel)(const ChainForces&, StencilRelaxation&) = nullptr;

  friend bool operator==(const SchemeTraits&, const SchemeTraits&) = default;
};

// The traits of a Crossing scheme with integrator.transitions = located.
constexpr SchemeTraits located_traits(SchemeTraits scheme) {
  SchemeTraits t = scheme;
  t.stick_rule = StickRule::Located;
  t.locatable = false;
  t.located_on_fixed_steps = true;
  t.general_kernels = false;  // its dense output reads j +- 1
  t.fused_kernels = false;
  t.stencil_kernel = nullptr;
  t.cluster_kernel = nullptr;  // not compiled for it (docs/developer/build-time.md)
  return t;
}

// The traits of the scheme named `keyword` (integrator.scheme; the registry's, shipped or
// registered), nullptr when there is none of that name.
const SchemeTraits* scheme_traits(std::string_view keyword);

// The keywords of the schemes the program ships, in registry order: what the reference docs
// list as integrator.scheme's choices (stepper_keywords() adds those registered since).
std::vector<std::string> shipped_scheme_keywords();

}  // namespace bkq
