// Every scene key's value, typed: one member per key, filled by the row that declares the
// key (io/scene_table.cpp) and written back by it. The sections whose keys are already what
// the runs use (drive, run, integrator, output, stats) are the settings' own structs; model,
// friction and rsf hold the keys as given, from which io/settings.cpp derives the physics.
// Code above io compares these enums, never a choice's text.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "engine/ofc.hpp"
#include "engine/rsf_cycle.hpp"
#include "model/laws/rsf.hpp"
#include "model/parameters.hpp"
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

// model.kind: the plain chain, the pad, one block, the OFC automaton.
enum class ModelChoice { Bk, Bkp, OneDof, Ofc };
// model.parameterisation: Carlson-Langer's dimensionless units, thesis Table 3.1, SI per area.
enum class Units { CarlsonLanger, Thesis, Si };

// model.*, as given.
struct ModelKeys {
  ModelChoice kind = ModelChoice::Bk;
  Units units = Units::CarlsonLanger;
  int blocks = 0, rows = 0;
  Boundary boundary = Boundary::Free, boundary_y = Boundary::Free;
  Coupling coupling = Coupling::Nearest;
  int range = 0;
  double coupling_exponent = 0, viscosity = 0;
  double l = 0;
  std::optional<double> l_y;  // auto: model.l
  double pad_mass = 0, caliper_stiffness = 0, damping_ratio = 0;
  double s_m = 0, s_p = 0, s_c = 0;
  std::optional<double> s_c_y;  // auto: model.s_c
  double rayleigh_alpha = 0, rayleigh_beta = 0;
  // si (rate-and-state): per unit fault area.
  double stiffness = 0, coupling_stiffness = 0;
  std::optional<double> coupling_stiffness_y;  // auto: model.coupling_stiffness
  RsfDynamics dynamics = RsfDynamics::QuasiDynamic;
  double shear_modulus = 0, shear_wave_speed = 0, mass_per_area = 0;
};

// friction.law: a rate-only law of the registry, or rate-and-state (rsf, its own path).
struct LawChoice {
  bool rsf = false;
  FrictionLaw law{};  // when !rsf
  friend bool operator==(const LawChoice&, const LawChoice&) = default;
};

// friction.*, as given.
struct FrictionKeys {
  LawChoice law;
  double F0 = 0, sigma = 0, alpha = 0, vc = 0;
  std::string table;  // friction.table: absolute path, or empty
};

// rsf.*, as given.
// rsf.pattern: per-block values of rsf.a and rsf.b everywhere, or asperities among barriers.
enum class RsfPattern { Uniform, Asperities };

// rsf.event_integration: the whole grid, the active blocks in one integration, or their groups
// that share no spring each with its own step size.
enum class RsfEventIntegration { Whole, Active, Groups };

struct RsfKeys {
  rsf::Params law;  // rsf.a, rsf.b, rsf.dc, rsf.mu0, rsf.v0
  rsf::StateLaw state_law = rsf::StateLaw::Aging;
  rsf::Form form = rsf::Form::Log;
  double normal_stress = 0, v_threshold = 0, v_init = 0;
  std::optional<double> theta_init;  // auto: steady state at the plate rate
  std::string blocks;                // rsf.blocks: absolute path, or empty
  double slow_slip_threshold = 0;    // 0: off
  RsfPattern pattern = RsfPattern::Uniform;
  int pattern_period = 0, pattern_width = 0;
  std::optional<double> handover_speed;  // drive.mode = events; auto: chosen from V_th and eta
  std::optional<double> creep_quantum;   // drive.mode = events; auto: from a sigma and k_c
  RsfEventIntegration event_integration = RsfEventIntegration::Whole;
  std::optional<double> alone_speed;      // active blocks only; auto: from V_pl, V_th, eta; 0: off
  std::optional<double> alone_tolerance;  // blocks alone; auto: 1e-6, or integrator.tolerance
};

struct SceneValues {
  ModelKeys model;
  OfcParams ofc;  // ofc.* (its size and edges are model.* keys, set in io/settings.cpp)
  FrictionKeys friction;
  RsfKeys rsf;
  DriveSettings drive;
  RunSettings run;
  IntegratorSettings integrator;  // located_transitions as given (settings: where it applies)
  OutputSettings output;          // block_count as given (settings: resolved against the chain)
  StatsSettings stats;
};

// Every key of `scene` through its row into its member. Reads no file.
SceneValues scene_values(const Scene& scene);

// Whether integrator.scheme `scheme` can locate stick and slip inside its step
// (integrator.transitions = located), as the scheme's traits declare it
// (integrate/scheme_traits.hpp); false for a keyword the registry does not hold.
bool scheme_supports_located(const std::string& scheme);

}  // namespace bkq
