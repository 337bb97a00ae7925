// From the validated scene to the typed settings. The physical parameters (Ferre 2018 Table 3.1;
// Carlson & Langer 1989) come from Ferre 2018 Table 3.1 (block quantities scaled from the pad's) or
// Carlson–Langer dimensionless units (eq. 2.2).
#include "io/settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/format.hpp"
#include "integrate/located.hpp"
#include "integrate/scheme_traits.hpp"
#include "integrate/theta.hpp"
#include "io/friction_table.hpp"
#include "io/rsf_blocks.hpp"
#include "io/scene.hpp"
#include "model/coupling.hpp"
#include "model/friction_laws.hpp"

namespace bkq {

namespace {

// rsf.alone_tolerance's auto (where integrator.tolerance is tighter): a block alone near steady
// sliding then errs by ~1e-6 in ln V over a forecast, against the creep quantum's k q / (2 a
// sigma), some 5e-2 in the shipped chains.
constexpr double kAloneTolerance = 1e-6;

// The chain's physics from the model.* and friction.* keys.
ModelParams model_of(const SceneValues& v) {
  const ModelKeys& k = v.model;
  ModelParams p;
  p.kind = k.kind == ModelChoice::Bkp      ? ModelKind::BKP
           : k.kind == ModelChoice::OneDof ? ModelKind::OneDof
                                           : ModelKind::BK;
  p.boundary = k.boundary;
  // A lattice (model.rows > 1) stores its rows one after the other: n counts every block.
  const int nx = p.kind == ModelKind::OneDof ? 1 : k.blocks;
  p.rows = k.kind == ModelChoice::Ofc || p.kind == ModelKind::OneDof ? 1 : k.rows;
  p.n = nx * p.rows;
  p.boundary_y = k.boundary_y;

  // The scene has checked the keyword against the registry's names; rsf is not among them
  // (its own path, RsfSettings), and its chain keeps the default law.
  if (!v.friction.law.rsf) p.law = v.friction.law.law;
  if (p.law == law_id<law::Table>) p.table = read_friction_table(v.friction.table);
  p.sigma = v.friction.sigma;

  const double s_m = k.s_m;
  const double s_p = k.s_p;
  const double zeta = k.damping_ratio;
  double m_x = 0, k_p0 = 0;
  if (k.units == Units::Si) {
    // Rate-and-state (RsfSettings): per unit area; the blocks' springs are read there.
    p.k_c = 0;
  } else if (k.units == Units::Thesis) {
    // Thesis Table 3.1: the blocks share the pad's mass and spring, the chain keeps the
    // axial stiffness of a single element (k_c grows with N).
    m_x = k.pad_mass;
    k_p0 = k.caliper_stiffness;
    p.m_u = s_m * m_x / p.n;
    p.k_p = s_p * k_p0 / p.n;
    // On a lattice each axis keeps the stiffness of its own elements.
    p.k_c = k.s_c * k_p0 * nx;
    if (p.rows > 1) p.k_c_y = k.s_c_y.value_or(k.s_c) * k_p0 * p.rows;
    p.F0 = v.friction.F0;
    p.v_c = v.friction.vc;
  } else {
    // Carlson–Langer units (eq. 2.2): m_u = k_p = F0 = 1, k_c = l^2, v_c = 1/(2 alpha).
    // A pad, if any, is scaled from the blocks with the same factors as Table 3.1.
    p.m_u = 1;
    p.k_p = 1;
    p.F0 = 1;
    const double l = k.l;
    p.k_c = l * l;
    if (p.rows > 1) {
      const double l_y = k.l_y.value_or(l);
      p.k_c_y = l_y * l_y;
    }
    const double alpha = v.friction.alpha;
    p.v_c = alpha > 0 ? 1.0 / (2.0 * alpha) : HUGE_VAL;
    m_x = p.n * p.m_u / s_m;
    k_p0 = p.n * p.k_p / s_p;
  }
  if (p.n == 1) p.k_c = 0;
  p.coupling = k.coupling;
  p.range = k.range;
  p.coupling_exponent = k.coupling_exponent;
  p.viscosity = k.viscosity;
  p.rayleigh_alpha = k.rayleigh_alpha;
  p.rayleigh_beta = k.rayleigh_beta;
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

// The grid and springs of friction.law = rsf: a chain (model.rows = 1), a column
// (model.blocks = 1: the chain along y) or a lattice, coupled by model.coupling's stencil with
// model.coupling_stiffness the springs' total along strike and model.coupling_stiffness_y
// across (auto: the same); a column takes the across-strike springs, as the other laws' do.
void rsf_grid(const SceneValues& v, const ModelParams& chain, RsfModel& m) {
  const int nx = v.model.kind == ModelChoice::OneDof ? 1 : v.model.blocks;
  const int ny = chain.n / nx;
  m.rows = ny;
  m.periodic = v.model.boundary == Boundary::Periodic;
  m.periodic_y = v.model.boundary_y == Boundary::Periodic;
  m.springs.clear();
  const double k_y = ny > 1 ? v.model.coupling_stiffness_y.value_or(m.k_c) : 0.0;
  if (nx == 1 && ny > 1) m.k_c = k_y;
  if (m.k_c == 0 && k_y == 0) return;
  ModelParams p = chain;
  p.coupling = v.model.coupling;
  p.range = v.model.range;
  p.coupling_exponent = v.model.coupling_exponent;
  p.k_c = m.k_c;
  p.n = nx * ny;
  p.rows = ny;
  if (nx > 1 && ny > 1) {
    p.k_c_y = k_y;
    m.springs = lattice_stencil(p);
    return;
  }
  p.rows = 1;
  for (const CouplingSpring& c : coupling_stencil(p))
    m.springs.push_back(nx > 1 ? LatticeSpring{c.offset, 0, c.k} : LatticeSpring{0, c.offset, c.k});
}

// Asperities of rsf.a, rsf.b among barriers with the two swapped, in patches of
// rsf.pattern_width of every rsf.pattern_period blocks along strike (and across on a lattice).
void rsf_pattern(const SceneValues& v, int n, RsfModel& m) {
  const int period = v.rsf.pattern_period, width = v.rsf.pattern_width;
  const int nx = v.model.kind == ModelChoice::OneDof ? 1 : v.model.blocks;
  rsf::Params barrier = v.rsf.law;
  std::swap(barrier.a, barrier.b_rsf);
  for (int j = 0; j < n; ++j) {
    const int x = j % nx, y = j / nx;
    const bool asperity = x % period < width && y % period < width;
    m.law[j] = rsf::Law(asperity ? v.rsf.law : barrier);
  }
}

// A value in a message, to 3 digits.
std::string short_real(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g", x);
  return s;
}

// The rate-and-state chain of `chain`'s size and boundary from the rsf.* and si model keys.
RsfSettings rsf_of(const SceneValues& v, const ModelParams& chain) {
  RsfSettings r;
  r.on = true;
  const rsf::Params& p = v.rsf.law;
  RsfModel& m = r.chain;
  m.law.assign(static_cast<std::size_t>(chain.n), rsf::Law(p));
  if (!v.rsf.blocks.empty()) {
    const std::vector<rsf::Params> blocks = read_rsf_blocks(v.rsf.blocks, chain.n, p);
    for (int j = 0; j < chain.n; ++j) m.law[j] = rsf::Law(blocks[j]);
  }
  if (v.rsf.pattern == RsfPattern::Asperities) rsf_pattern(v, chain.n, m);
  r.v_slow = v.rsf.slow_slip_threshold;
  m.state_law = v.rsf.state_law;
  m.form = v.rsf.form;
  m.dynamics = v.model.dynamics;
  m.sigma = v.rsf.normal_stress;
  m.k = v.model.stiffness;
  m.k_c = chain.n > 1 ? v.model.coupling_stiffness : 0.0;
  rsf_grid(v, chain, m);
  m.v_pl = v.drive.speed;
  const double c_s = v.model.shear_wave_speed;
  m.eta = c_s > 0 ? v.model.shear_modulus / (2 * c_s) : 0.0;  // Rice 1993
  m.mass = v.model.mass_per_area;
  r.tolerance = v.integrator.tolerance;
  r.v_threshold = v.rsf.v_threshold;
  r.v_init = v.rsf.v_init;
  r.theta_init = v.rsf.theta_init.value_or(0.0);
  if (v.drive.mode == DriveMode::Events) {
    // The closed forms between events leave radiation damping out: V_h keeps eta V_h a small
    // share of a sigma (at most 0.1 when given, 0.01 when auto).
    r.event_driven = true;
    r.active_blocks = v.rsf.event_integration != RsfEventIntegration::Whole;
    r.active_groups = v.rsf.event_integration == RsfEventIntegration::Groups;
    double a_min = HUGE_VAL, dc_min = HUGE_VAL;
    for (const rsf::Law& law : m.law) {
      a_min = std::min(a_min, law.params().a);
      dc_min = std::min(dc_min, law.params().dc);
    }
    // Auto: each quantum moves a neighbour's slip rate by at most 10 % (k_c q <= 0.1 a sigma),
    // and a tenth of the least D_c on a grid without springs (where it passes nothing on).
    double k_max = 0;
    for (const LatticeSpring& sp : m.stencil()) k_max = std::max(k_max, std::fabs(sp.k));
    r.creep_quantum =
        v.rsf.creep_quantum.value_or(k_max > 0 ? 0.1 * a_min * m.sigma / k_max : dc_min / 10);
    const double damped = m.eta > 0 ? a_min * m.sigma / m.eta : HUGE_VAL;
    r.v_handover = v.rsf.handover_speed.value_or(std::min(r.v_threshold / 10, 0.01 * damped));
    if (v.rsf.handover_speed && m.eta * r.v_handover > 0.1 * a_min * m.sigma)
      throw Error("rsf.handover_speed = " + format_real(r.v_handover) +
                  ": radiation damping eta V_h exceeds a tenth of a sigma there, which the "
                  "closed form between events leaves out; allowed: up to " +
                  short_real(0.1 * damped) + " m/s (or auto)");
    // Blocks alone: their law leaves radiation damping out as the closed forms do (eta V_a at
    // most 0.01 a sigma when auto, 0.1 when given).
    if (r.active_blocks) {
      r.v_alone =
          v.rsf.alone_speed.value_or(std::min({100 * m.v_pl, r.v_threshold / 10, 0.01 * damped}));
      if (!v.rsf.alone_speed && !(r.v_alone > m.v_pl)) r.v_alone = 0;
      r.alone_tolerance = v.rsf.alone_tolerance.value_or(std::max(r.tolerance, kAloneTolerance));
      if (v.rsf.alone_speed && m.eta * r.v_alone > 0.1 * a_min * m.sigma)
        throw Error("rsf.alone_speed = " + format_real(r.v_alone) +
                    ": radiation damping eta V_a exceeds a tenth of a sigma there, which a block "
                    "integrated alone leaves out; allowed: up to " +
                    short_real(0.1 * damped) + " m/s, auto or 0");
    }
    if (!(r.v_handover > m.v_pl))
      throw Error("rsf.handover_speed = auto: with radiation damping eta = " + format_real(m.eta) +
                  " Pa s/m the hand-over speed that keeps eta V_h << a sigma (" +
                  short_real(r.v_handover) +
                  " m/s) is not above the plate rate drive.speed; allowed: a larger "
                  "model.shear_wave_speed, or drive.mode = continuous");
  }
  return r;
}

// The located transitions' event functions and the steps of the schemes whose traits
// declare no general kernels (the theta-method's implicit solve, the adaptive scheme's) are
// written for nearest-neighbour springs without dashpots.
void check_general_kernels(const Scene& scene, const Settings& s) {
  const bool general = s.model.long_range() || s.model.viscous() || s.model.lattice();
  if (!general) return;
  const std::string& scheme = s.integrator.scheme;
  const SchemeTraits* traits = scheme_traits(scheme);
  const bool runs = traits != nullptr && traits->general_kernels;
  if (runs && !s.integrator.located_transitions) return;
  std::vector<std::string> able;  // "rk2, rk4 or verlet": the registry's, by their traits
  for (const std::string& k : stepper_keywords())
    if (scheme_traits(k)->general_kernels) able.push_back(k);
  std::string allowed;
  for (std::size_t i = 0; i < able.size(); ++i)
    allowed += (i == 0 ? "" : i + 1 == able.size() ? " or " : ", ") + able[i];
  throw Error((runs ? "integrator.transitions = located" : "integrator.scheme = " + scheme) +
              " with " +
              (s.model.lattice()      ? "model.rows = " + scene.text(key::model_rows)
               : s.model.long_range() ? "model.coupling = " + scene.text(key::model_coupling) +
                                            " and model.range = " + scene.text(key::model_range)
                                      : "model.viscosity = " + scene.text(key::model_viscosity)) +
              ": written for chains of nearest-neighbour springs without dashpots; allowed "
              "here: integrator.scheme = " +
              allowed + " with integrator.transitions = step");
}

}  // namespace

ModelParams model_from_scene(const Scene& scene) {
  return model_of(scene_values(scene));
}

RsfSettings rsf_from_scene(const Scene& scene, const ModelParams& chain) {
  return rsf_of(scene_values(scene), chain);
}

Settings settings_from_scene(const Scene& scene) {
  const SceneValues v = scene_values(scene);
  Settings s;
  s.model = model_of(v);
  if (v.model.kind != ModelChoice::OneDof) {
    s.lattice.nx = v.model.blocks;
    s.lattice.ny = v.model.rows;
  }
  if (v.model.kind == ModelChoice::Ofc) {
    s.ofc.on = true;
    s.ofc.lattice = v.ofc;
    OfcParams& o = s.ofc.lattice;
    o.nx = v.model.blocks;
    o.ny = v.model.rows;
    o.periodic_x = v.model.boundary == Boundary::Periodic;
    o.periodic_y = v.model.boundary_y == Boundary::Periodic;
  }

  if (v.friction.law.rsf) {
    s.rsf = rsf_of(v, s.model);
    s.model.kind = ModelKind::BK;  // one block (1dof) is a chain of one
  }

  s.drive = v.drive;
  s.run = v.run;
  s.integrator = v.integrator;
  s.integrator.located_transitions =
      v.integrator.located_transitions && scene.applies(key::integrator_transitions);
  check_general_kernels(scene, s);

  s.output = v.output;
  {
    // The range of blocks.csv, clipped to the chain: count 0 means up to the last block.
    const int n = s.model.n;
    if (s.output.blocks && s.output.block_first >= n)
      throw Error("output.block_first = " + std::to_string(s.output.block_first) +
                  " is beyond the chain: the blocks are 0 .. " + std::to_string(n - 1));
    const int left = n - s.output.block_first;
    const int count = v.output.block_count;
    s.output.block_count = count == 0 ? left : std::min(count, left);
  }
  s.stats = v.stats;
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
