// The scene turned into typed settings, once, in io: the layers above read fields, never
// string keys. Every key is declared (type, default, range, units, doc) in scene.cpp's
// parameter table; these structs are that table's values after validation.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/ofc.hpp"
#include "engine/rsf_cycle.hpp"
#include "integrate/stepper.hpp"
#include "io/scene_values.hpp"
#include "model/parameters.hpp"
#include "model/substrate.hpp"

namespace bkq {

class Scene;

// model.kind = ofc: the automaton's lattice and share (the chain's ModelParams unused).
struct OfcSettings {
  bool on = false;
  OfcParams lattice;
};

// The scene's lattice as given (model.blocks along strike, model.rows across), for the outputs:
// a lattice of one column runs as the chain along y (model/parameters.hpp: line_as_chain), and
// its catalogue still reads (x, y) = (0, the chain's block).
struct LatticeShape {
  int nx = 1, ny = 1;
};

// friction.law = rsf (model.parameterisation = si): the rate-and-state chain, its start and
// integration (engine/rsf_cycle.hpp), and the seismic threshold that makes events. `model`
// then holds only the chain's size and boundary.
struct RsfSettings {
  bool on = false;
  RsfModel chain;
  double tolerance = 1e-8;     // integrator.tolerance
  double v_threshold = 1e-3;   // rsf.v_threshold [m/s]
  double v_init = 2e-5;        // rsf.v_init [m/s]
  double theta_init = 0;       // rsf.theta_init [s]; 0: auto, each block's D_c/V_pl
  double v_slow = 0;           // rsf.slow_slip_threshold [m/s]; 0: no slow_slip.csv
  bool event_driven = false;   // drive.mode = events (engine/rsf_loader.hpp)
  double v_handover = 0;       // rsf.handover_speed [m/s], auto resolved
  double creep_quantum = 0;    // rsf.creep_quantum [m], auto resolved
  bool active_blocks = false;  // rsf.event_integration = active or groups
  bool active_groups = false;  // rsf.event_integration = groups
  double v_alone = 0;          // rsf.alone_speed [m/s], auto resolved; 0: off
  double alone_tolerance = 0;  // rsf.alone_tolerance, auto resolved
  // The start state of every block: theta_init, or each block's steady state at V_pl.
  std::vector<double> theta_start() const {
    std::vector<double> theta;
    for (const rsf::Law& law : chain.law)
      theta.push_back(theta_init > 0 ? theta_init : law.params().dc / chain.v_pl);
    return theta;
  }
};

struct Settings {
  ModelParams model;
  RsfSettings rsf;
  LatticeShape lattice;
  OfcSettings ofc;
  DriveSettings drive;
  RunSettings run;
  IntegratorSettings integrator;
  OutputSettings output;
  StatsSettings stats;
};

// Reads every key of a validated scene into its typed field.
Settings settings_from_scene(const Scene& scene);

ModelParams model_from_scene(const Scene& scene);
// friction.law = rsf: the rate-and-state chain of `chain`'s size and boundary.
RsfSettings rsf_from_scene(const Scene& scene, const ModelParams& chain);

// The objects the settings describe, built in one place: the substrate motion
// (continuous mode) and the stepper for a chain of `blocks`.
Substrate substrate_of(const DriveSettings& drive);
std::unique_ptr<Stepper> stepper_of(const IntegratorSettings& integrator, int blocks);

}  // namespace bkq
