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
#include "model/parameters.hpp"
#include "model/substrate.hpp"
#include "stats/stability.hpp"

namespace bkq {

class Scene;

enum class DriveMode { Events, Continuous };
enum class Schedule { Constant, Steps, Ramp };

// drive.*: how the substrate moves. The step_* and ramp_* values apply only to their
// schedule (they hold their defaults otherwise).
struct DriveSettings {
  DriveMode mode = DriveMode::Events;
  Schedule schedule = Schedule::Constant;
  double speed = 0;
  double step_increment = 0, step_interval = 0;
  double ramp_from = 0, ramp_to = 0, ramp_duration = 0;
};

// run.start*: how a continuous run starts: random disorder (all stuck), or steady sliding
// (model/equilibrium.hpp) plus one mode of its linearisation (stats/stability.hpp).
struct StartSettings {
  bool equilibrium = false;
  std::optional<ModeFamily> mode;  // none: the equilibrium alone
  int mode_index = 0;
  double amplitude = 0;  // largest speed of the perturbation / the start speed
};

// run.*: length, seed, start and checkpoints.
struct RunSettings {
  std::int64_t events = 0;            // recorded events (events mode)
  std::int64_t transient_events = 0;  // discarded before recording (events mode)
  double duration = 0;                // simulated time (continuous mode)
  std::uint64_t seed = 0;
  double initial_disorder = 0;
  std::int64_t max_steps_per_event = 0;
  std::int64_t checkpoint_events = 0;  // 0 = off
  double checkpoint_seconds = 0;       // 0 = off
  StartSettings start;
  bool accuracy_error = false;  // run.accuracy = error: an indicator above threshold fails
};

// integrator.*: the stepper of the dynamic phase, by its registry keyword.
struct IntegratorSettings {
  std::string scheme;
  double dt = 0;
  double tolerance = 0;  // adaptive scheme only
  double theta = 0.5;    // theta scheme only
  // integrator.transitions = located: stick and slip located inside the step (rk2, rk4,
  // verlet; integrate/located.hpp); false: at the end of the step (the Crossing rule).
  bool located_transitions = false;
};

// output.*: continuous-mode outputs.
// output.catalog: the event catalogue's format.
enum class CatalogFormat { Csv, Hdf5, None };

struct OutputSettings {
  double every = 0;                      // time between timeseries rows
  bool blocks = false;                   // also write blocks.csv
  int block_first = 0, block_count = 0;  // blocks.csv: these blocks (count resolved, > 0)
  CatalogFormat catalog = CatalogFormat::Csv;
  bool catalog_deflate = false;  // hdf5-deflate: catalog.h5 shuffled and deflated
  int segment_blocks = 4;        // M of the segment statistics' block errors (Ferre 2018 eq. 4.3)
  bool status = false;           // node-status columns in timeseries.csv
  bool energy = false;           // energy_samples.csv and energy.csv
  double energy_window = 0, energy_tol = 0;
  std::optional<double> event_slip;  // event_slip.csv for events with mu >= this
};

// stats.*: histogram and Gutenberg-Richter fit window (nullopt: chosen automatically).
struct StatsSettings {
  double bin_width = 0;
  std::optional<double> mu_min, mu_max;
};

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
  double tolerance = 1e-8;    // integrator.tolerance
  double v_threshold = 1e-3;  // rsf.v_threshold [m/s]
  double v_init = 2e-5;       // rsf.v_init [m/s]
  double theta_init = 0;      // rsf.theta_init [s]; 0: auto, each block's D_c/V_pl
  double v_slow = 0;          // rsf.slow_slip_threshold [m/s]; 0: no slow_slip.csv
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
