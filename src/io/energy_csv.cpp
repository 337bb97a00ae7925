// Schemas of the energy diagnostics; see energy_csv.hpp.
#include "io/energy_csv.hpp"

namespace bkq {

const Schema& energy_samples_schema() {
  static const Schema schema = {
      {"t", "time", "simulated time of the sample"},
      {"energy", "energy",
       "E = 1/2 du^T K du + 1/2 u'^T M u' of blocks and pad, du measured from the sliding "
       "equilibrium at the current speed (from the zero position where there is none)"},
      {"braking_force", "force", "effective braking force N_b = k_p0 x + c_p x' (0 for bk)"},
  };
  return schema;
}

const Schema& energy_schema() {
  static const Schema schema = {
      {"t", "time", "centre of the window [t - dT/2, t + dT/2], dT = output.energy_window"},
      {"samples", "", "samples in the window", kInteger},
      {"energy_mean", "energy", "mean energy E over the window"},
      {"energy_rate_mean", "energy/time",
       "mean of E_t = (E(t_i+1) - E(t_i))/(t_i+1 - t_i) over the window"},
      {"tau_energy", "1/time",
       "rate of relative change of the mean energy, energy_rate_mean / "
       "energy_mean (tau_E of Sinou, Chiello & Charroyer 2019)"},
      {"braking_mean", "force", "mean braking force over the window"},
  };
  return schema;
}

}  // namespace bkq
