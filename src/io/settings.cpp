// From the validated scene to the typed settings. The physical parameters (Ferre 2018 Table 3.1;
// Carlson & Langer 1989) come from Ferre 2018 Table 3.1 (block quantities scaled from the pad's) or
// Carlson–Langer dimensionless units (eq. 2.2).
#include "io/settings.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "integrate/located.hpp"
#include "integrate/theta.hpp"
#include "io/friction_table.hpp"
#include "io/rsf_blocks.hpp"
#include "io/scene.hpp"
#include "model/coupling.hpp"
#include "model/friction_laws.hpp"

namespace bkq {

ModelParams model_from_scene(const Scene& scene) {
  ModelParams p;
  const std::string& kind = scene.choice("model.kind");
  p.kind = kind == "bkp" ? ModelKind::BKP : kind == "1dof" ? ModelKind::OneDof : ModelKind::BK;
  p.boundary = scene.choice("model.boundary") == "periodic" ? Boundary::Periodic : Boundary::Free;
  // A lattice (model.rows > 1) stores its rows one after the other: n counts every block.
  const int nx = p.kind == ModelKind::OneDof ? 1 : static_cast<int>(scene.integer("model.blocks"));
  p.rows = kind == "ofc" || p.kind == ModelKind::OneDof
               ? 1
               : static_cast<int>(scene.integer("model.rows"));
  p.n = nx * p.rows;
  p.boundary_y =
      scene.choice("model.boundary_y") == "periodic" ? Boundary::Periodic : Boundary::Free;

  // The scene has checked the keyword against the registry's names; rsf is not among them
  // (its own path, RsfSettings), and its chain keeps the default law.
  if (scene.choice("friction.law") != "rsf")
    p.law = law_named(scene.choice("friction.law")).value();
  if (p.law == law_id<law::Table>) p.table = read_friction_table(scene.text("friction.table"));
  p.sigma = scene.real("friction.sigma");

  const double s_m = scene.real("model.s_m");
  const double s_p = scene.real("model.s_p");
  const double zeta = scene.real("model.damping_ratio");
  double m_x = 0, k_p0 = 0;
  if (scene.choice("model.parameterisation") == "si") {
    // Rate-and-state (RsfSettings): per unit area; the blocks' springs are read there.
    p.k_c = 0;
  } else if (scene.choice("model.parameterisation") == "thesis") {
    // Thesis Table 3.1: the blocks share the pad's mass and spring, the chain keeps the
    // axial stiffness of a single element (k_c grows with N).
    m_x = scene.real("model.pad_mass");
    k_p0 = scene.real("model.caliper_stiffness");
    p.m_u = s_m * m_x / p.n;
    p.k_p = s_p * k_p0 / p.n;
    // On a lattice each axis keeps the stiffness of its own elements.
    p.k_c = scene.real("model.s_c") * k_p0 * nx;
    if (p.rows > 1)
      p.k_c_y = scene.real_or_auto("model.s_c_y").value_or(scene.real("model.s_c")) * k_p0 * p.rows;
    p.F0 = scene.real("friction.F0");
    p.v_c = scene.real("friction.vc");
  } else {
    // Carlson–Langer units (eq. 2.2): m_u = k_p = F0 = 1, k_c = l^2, v_c = 1/(2 alpha).
    // A pad, if any, is scaled from the blocks with the same factors as Table 3.1.
    p.m_u = 1;
    p.k_p = 1;
    p.F0 = 1;
    const double l = scene.real("model.l");
    p.k_c = l * l;
    if (p.rows > 1) {
      const double l_y = scene.real_or_auto("model.l_y").value_or(l);
      p.k_c_y = l_y * l_y;
    }
    const double alpha = scene.real("friction.alpha");
    p.v_c = alpha > 0 ? 1.0 / (2.0 * alpha) : HUGE_VAL;
    m_x = p.n * p.m_u / s_m;
    k_p0 = p.n * p.k_p / s_p;
  }
  if (p.n == 1) p.k_c = 0;
  const std::string& coupling = scene.choice("model.coupling");
  p.coupling = coupling == "range"   ? Coupling::Range
               : coupling == "power" ? Coupling::Power
                                     : Coupling::Nearest;
  p.range = static_cast<int>(scene.integer("model.range"));
  p.coupling_exponent = scene.real("model.coupling_exponent");
  p.viscosity = scene.real("model.viscosity");
  p.rayleigh_alpha = scene.real("model.rayleigh_alpha");
  p.rayleigh_beta = scene.real("model.rayleigh_beta");
  if (p.kind == ModelKind::BKP) {
    p.m_x = m_x;
    p.k_p0 = k_p0;
    p.c_p = critical_damping(zeta, k_p0 + p.n * p.k_p, m_x);
  } else if (p.kind == ModelKind::OneDof) {
    // Thesis eq. 2.11: one mass on a spring with a damper, m x'' = -c x' - k x - F(x' + v).
    p.c_u = critical_damping(zeta, p.k_p, p.m_u);
  }
  return line_as_chain(p);
}

namespace {

// rate-and-state keys: the grid and springs of friction.law = rsf. A chain (model.rows = 1), a
// column (model.blocks = 1: the chain along y) or a lattice, coupled by model.coupling's stencil
// with model.coupling_stiffness the springs' total along each axis (isotropic).
void rsf_grid(const Scene& scene, const ModelParams& chain, RsfModel& m) {
  const int nx =
      scene.choice("model.kind") == "1dof" ? 1 : static_cast<int>(scene.integer("model.blocks"));
  const int ny = chain.n / nx;
  m.rows = ny;
  m.periodic = scene.choice("model.boundary") == "periodic";
  m.periodic_y = scene.choice("model.boundary_y") == "periodic";
  m.springs.clear();
  if (m.k_c == 0) return;
  ModelParams p = chain;
  p.coupling = scene.choice("model.coupling") == "range"   ? Coupling::Range
               : scene.choice("model.coupling") == "power" ? Coupling::Power
                                                           : Coupling::Nearest;
  p.range = static_cast<int>(scene.integer("model.range"));
  p.coupling_exponent = scene.real("model.coupling_exponent");
  p.k_c = m.k_c;
  p.n = nx * ny;
  p.rows = ny;
  if (nx > 1 && ny > 1) {
    p.k_c_y = m.k_c;
    m.springs = lattice_stencil(p);
    return;
  }
  p.rows = 1;
  for (const CouplingSpring& c : coupling_stencil(p))
    m.springs.push_back(nx > 1 ? LatticeSpring{c.offset, 0, c.k} : LatticeSpring{0, c.offset, c.k});
}

}  // namespace

RsfSettings rsf_from_scene(const Scene& scene, const ModelParams& chain) {
  RsfSettings r;
  r.on = true;
  rsf::Params p;
  p.a = scene.real("rsf.a");
  p.b_rsf = scene.real("rsf.b");
  p.dc = scene.real("rsf.dc");
  p.mu0 = scene.real("rsf.mu0");
  p.v0 = scene.real("rsf.v0");
  RsfModel& m = r.chain;
  m.law.assign(static_cast<std::size_t>(chain.n), rsf::Law(p));
  if (const std::string& file = scene.text("rsf.blocks"); !file.empty()) {
    const std::vector<rsf::Params> blocks = read_rsf_blocks(file, chain.n, p);
    for (int j = 0; j < chain.n; ++j) m.law[j] = rsf::Law(blocks[j]);
  }
  // rate-and-state keys: asperities of rsf.a, rsf.b among barriers with the two swapped, in
  // patches of pattern_width of every pattern_period blocks along strike (and across on a
  // lattice).
  if (scene.choice("rsf.pattern") == "asperities") {
    const int period = static_cast<int>(scene.integer("rsf.pattern_period"));
    const int width = static_cast<int>(scene.integer("rsf.pattern_width"));
    const int nx =
        scene.choice("model.kind") == "1dof" ? 1 : static_cast<int>(scene.integer("model.blocks"));
    rsf::Params barrier = p;
    std::swap(barrier.a, barrier.b_rsf);
    for (int j = 0; j < chain.n; ++j) {
      const int x = j % nx, y = j / nx;
      const bool asperity = x % period < width && y % period < width;
      m.law[j] = rsf::Law(asperity ? p : barrier);
    }
  }
  r.v_slow = scene.real("rsf.slow_slip_threshold");
  m.state_law =
      scene.choice("rsf.state_law") == "slip" ? rsf::StateLaw::Slip : rsf::StateLaw::Aging;
  m.form = scene.choice("rsf.form") == "regularised" ? rsf::Form::Regularised : rsf::Form::Log;
  m.dynamics = scene.choice("model.dynamics") == "inertial" ? RsfDynamics::Inertial
                                                            : RsfDynamics::QuasiDynamic;
  m.sigma = scene.real("rsf.normal_stress");
  m.k = scene.real("model.stiffness");
  m.k_c = chain.n > 1 ? scene.real("model.coupling_stiffness") : 0.0;
  rsf_grid(scene, chain, m);
  m.v_pl = scene.real("drive.speed");
  const double c_s = scene.real("model.shear_wave_speed");
  m.eta = c_s > 0 ? scene.real("model.shear_modulus") / (2 * c_s) : 0.0;  // Rice 1993
  m.mass = scene.real("model.mass_per_area");
  r.tolerance = scene.real("integrator.tolerance");
  r.v_threshold = scene.real("rsf.v_threshold");
  r.v_init = scene.real("rsf.v_init");
  r.theta_init = scene.real_or_auto("rsf.theta_init").value_or(0.0);
  return r;
}

Settings settings_from_scene(const Scene& scene) {
  Settings s;
  s.model = model_from_scene(scene);
  if (scene.choice("model.kind") != "1dof") {
    s.lattice.nx = static_cast<int>(scene.integer("model.blocks"));
    s.lattice.ny = static_cast<int>(scene.integer("model.rows"));
  }
  if (scene.choice("model.kind") == "ofc") {
    s.ofc.on = true;
    OfcParams& o = s.ofc.lattice;
    o.nx = static_cast<int>(scene.integer("model.blocks"));
    o.ny = static_cast<int>(scene.integer("model.rows"));
    o.alpha = scene.real("ofc.alpha");
    o.periodic_x = scene.choice("model.boundary") == "periodic";
    o.periodic_y = scene.choice("model.boundary_y") == "periodic";
    o.sequential = scene.choice("ofc.order") == "sequential";
    o.relaxation_time = scene.real("ofc.relaxation_time");
    o.relaxation_alpha = scene.real("ofc.relaxation_alpha");
  }

  if (scene.choice("friction.law") == "rsf") {
    s.rsf = rsf_from_scene(scene, s.model);
    s.model.kind = ModelKind::BK;  // one block (1dof) is a chain of one
  }

  DriveSettings& d = s.drive;
  d.mode = scene.choice("drive.mode") == "continuous" ? DriveMode::Continuous : DriveMode::Events;
  const std::string& schedule = scene.choice("drive.schedule");
  d.schedule = schedule == "steps"  ? Schedule::Steps
               : schedule == "ramp" ? Schedule::Ramp
                                    : Schedule::Constant;
  d.speed = scene.real("drive.speed");
  d.step_increment = scene.real("drive.step_increment");
  d.step_interval = scene.real("drive.step_interval");
  d.ramp_from = scene.real("drive.ramp_from");
  d.ramp_to = scene.real("drive.ramp_to");
  d.ramp_duration = scene.real("drive.ramp_duration");

  RunSettings& r = s.run;
  r.events = scene.integer("run.events");
  r.transient_events = scene.integer("run.transient_events");
  r.duration = scene.real("run.duration");
  r.seed = static_cast<std::uint64_t>(scene.integer("run.seed"));
  r.initial_disorder = scene.real("run.initial_disorder");
  r.max_steps_per_event = scene.integer("run.max_steps_per_event");
  r.checkpoint_events = scene.integer("run.checkpoint_events");
  r.checkpoint_seconds = scene.real("run.checkpoint_seconds");
  r.start.equilibrium = scene.choice("run.start") == "equilibrium";
  const std::string& mode = scene.choice("run.start_mode");
  if (mode != "none")
    r.start.mode = mode == "pad"    ? ModeFamily::Pad
                   : mode == "1dof" ? ModeFamily::OneDof
                                    : ModeFamily::Chain;
  r.start.mode_index = static_cast<int>(scene.integer("run.start_mode_index"));
  r.start.amplitude = scene.real("run.start_amplitude");
  r.accuracy_error = scene.choice("run.accuracy") == "error";

  s.integrator.scheme = scene.choice("integrator.scheme");
  s.integrator.dt = scene.real("integrator.dt");
  s.integrator.tolerance = scene.real("integrator.tolerance");
  s.integrator.theta = scene.real("integrator.theta");
  s.integrator.located_transitions = scene.applies("integrator.transitions") &&
                                     scene.choice("integrator.transitions") == "located";
  // The theta-method's implicit solve, the adaptive scheme's and the located transitions'
  // event functions are written for nearest-neighbour springs without dashpots.
  const std::string& scheme = s.integrator.scheme;
  const bool crossing = scheme == "rk2" || scheme == "rk4" || scheme == "verlet";
  const bool general = s.model.long_range() || s.model.viscous() || s.model.lattice();
  if (general && (!crossing || s.integrator.located_transitions))
    throw Error((crossing ? "integrator.transitions = located" : "integrator.scheme = " + scheme) +
                " with " +
                (s.model.lattice()      ? "model.rows = " + scene.text("model.rows")
                 : s.model.long_range() ? "model.coupling = " + scene.choice("model.coupling") +
                                              " and model.range = " + scene.text("model.range")
                                        : "model.viscosity = " + scene.text("model.viscosity")) +
                ": written for chains of nearest-neighbour springs without dashpots; allowed "
                "here: integrator.scheme = rk2, rk4 or verlet with integrator.transitions = step");

  s.output.every = scene.real("output.every");
  s.output.blocks = scene.flag("output.blocks");
  {
    // The range of blocks.csv, clipped to the chain: count 0 means up to the last block.
    const int n = s.model.n;
    s.output.block_first = static_cast<int>(scene.integer("output.block_first"));
    const auto count = static_cast<int>(scene.integer("output.block_count"));
    if (scene.flag("output.blocks") && s.output.block_first >= n)
      throw Error("output.block_first = " + std::to_string(s.output.block_first) +
                  " is beyond the chain: the blocks are 0 .. " + std::to_string(n - 1));
    const int left = n - s.output.block_first;
    s.output.block_count = count == 0 ? left : std::min(count, left);
  }
  s.output.status = scene.flag("output.status");
  s.output.energy = scene.flag("output.energy");
  s.output.energy_window = scene.real("output.energy_window");
  s.output.energy_tol = scene.real("output.energy_tol");
  const std::string& catalog = scene.choice("output.catalog");
  s.output.catalog = catalog == "hdf5" || catalog == "hdf5-deflate" ? CatalogFormat::Hdf5
                     : catalog == "none"                            ? CatalogFormat::None
                                                                    : CatalogFormat::Csv;
  s.output.catalog_deflate = catalog == "hdf5-deflate";
  s.output.segment_blocks = static_cast<int>(scene.integer("output.segment_blocks"));

  s.stats.bin_width = scene.real("stats.bin_width");
  s.stats.mu_min = scene.real_or_auto("stats.mu_min");
  s.output.event_slip = scene.real_or_none("output.event_slip");
  s.stats.mu_max = scene.real_or_auto("stats.mu_max");
  return s;
}

Substrate substrate_of(const DriveSettings& drive) {
  switch (drive.schedule) {
    case Schedule::Steps:
      return Substrate::steps(drive.speed, drive.step_increment, drive.step_interval);
    case Schedule::Ramp:
      return Substrate::ramp(drive.ramp_from, drive.ramp_to, drive.ramp_duration);
    case Schedule::Constant:
      break;
  }
  return Substrate::constant(drive.speed);
}

std::unique_ptr<Stepper> stepper_of(const IntegratorSettings& integrator, int blocks) {
  std::unique_ptr<Stepper> s = make_stepper(integrator.scheme, blocks, integrator.tolerance);
  if (auto* theta = dynamic_cast<Theta*>(s.get())) theta->set_theta(integrator.theta);
  if (integrator.located_transitions) s = with_located_transitions(std::move(s), blocks);
  return s;
}

}  // namespace bkq
