// The energy diagnostics of continuous runs (output.energy; Sinou, Chiello & Charroyer 2019
// §4.3.2-4.3.3), written by app/observers/energy: energy_samples.csv (the mechanical
// energy and the braking force at every sample) and energy.csv (their means over windows
// of output.energy_window with 50 % overlap, and the rate of relative change of the mean
// energy). Columns declared once here.
#pragma once

#include "io/schema.hpp"

namespace bkq {

const Schema& energy_samples_schema();
const Schema& energy_schema();

}  // namespace bkq
