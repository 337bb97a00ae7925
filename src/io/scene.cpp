// The parameter table of bkquake and the Scene that reads, checks and writes it.
// Every key is declared exactly once below (type, default, range, units, doc); reading
// (INI files through io/ini.hpp, the one INI parser, and --set overrides), validation,
// --dump-defaults and the effective scene.ini of each run are all driven by that table,
// so a new parameter is one new row. Values are stored as normalised text (shortest
// round-trip reals, true/false booleans) so equal scenes hash equally.
#include "io/scene.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "core/fnv1a.hpp"
#include "core/format.hpp"
#include "core/terminal_text.hpp"
#include "engine/ofc.hpp"
#include "integrate/stepper.hpp"
#include "io/ini.hpp"
#include "io/json.hpp"
#include "model/friction_laws.hpp"

namespace bkq {

namespace {

constexpr double kMaxInt64 = 9223372036854775807.0;  // 2^63 - 1 (rounds to 2^63 as a double)
// Sane bounds, so that no finite but absurd value reaches the physics: a mass, stiffness,
// force or velocity scale of the thesis parameterisation; a simulated time (run length,
// schedule period, output interval), beyond which 64-bit step counts and t + dt in double
// precision stop working at any usable dt; the magnitude mu = ln(moment) of any event of any
// chain bkquake can hold (|mu| <= 50: moments from 1e-22 to 5e21).
constexpr double kHuge = 1e12;
constexpr double kLongTime = 1e15;
constexpr double kMuLimit = 50;
constexpr double kMaxSteps = 1e15;  // time steps of a continuous run

// friction.law's keywords: the rate-only laws of model/law_list.hpp and rsf, the law with
// state on its own path (model/laws/rsf.hpp).
std::vector<std::string> rsf_and_law_names() {
  std::vector<std::string> names = law_names();
  names.emplace_back("rsf");
  return names;
}

// The fields every row has.
ParamSpec spec(const char* key, ParamType type, const char* def, const char* units,
               const char* doc) {
  return {
      .key = key, .type = type, .default_value = def, .choices = {}, .units = units, .doc = doc};
}

// Range brackets: '[' or ']' is inclusive, '(' or ')' exclusive; an infinite bound is
// always written open, so `inf` itself is never an accepted value.
ParamSpec real(const char* key, const char* def, char lo_br, double lo, double hi, char hi_br,
               const char* units, const char* doc) {
  ParamSpec p = spec(key, ParamType::Real, def, units, doc);
  p.min = lo;
  p.max = hi;
  p.has_min = std::isfinite(lo);
  p.has_max = std::isfinite(hi);
  p.min_open = lo_br == '(' || !p.has_min;
  p.max_open = hi_br == ')' || !p.has_max;
  return p;
}

ParamSpec integer(const char* key, const char* def, double lo, double hi, const char* units,
                  const char* doc) {
  ParamSpec p = spec(key, ParamType::Integer, def, units, doc);
  p.min = lo;
  p.max = hi;
  p.has_min = p.has_max = true;
  return p;
}

ParamSpec choice(const char* key, const char* def, std::vector<std::string> choices,
                 const char* doc) {
  ParamSpec p = spec(key, ParamType::Choice, def, "", doc);
  p.choices = std::move(choices);
  return p;
}

ParamSpec boolean(const char* key, const char* def, const char* doc) {
  return spec(key, ParamType::Boolean, def, "", doc);
}

ParamSpec path(const char* key, const char* doc) {
  return spec(key, ParamType::Path, "", "", doc);
}

ParamSpec auto_real(const char* key, double limit, const char* units, const char* doc) {
  ParamSpec p = real(key, "auto", '[', -limit, limit, ']', units, doc);
  p.allow_auto = true;
  return p;
}

// The same on (0, limit] (a state variable, a time).
ParamSpec positive_or_auto(const char* key, double limit, const char* units, const char* doc) {
  ParamSpec p = real(key, "auto", '(', 0, limit, ']', units, doc);
  p.allow_auto = true;
  return p;
}

// The same on [0, limit] (a stiffness).
ParamSpec auto_stiffness(const char* key, double limit, const char* doc) {
  ParamSpec p = real(key, "auto", '[', 0, limit, ']', "", doc);
  p.allow_auto = true;
  return p;
}

// A Real key whose default `none` turns its output off.
ParamSpec none_real(const char* key, double limit, const char* units, const char* doc) {
  ParamSpec p = real(key, "none", '[', -limit, limit, ']', units, doc);
  p.allow_auto = true;
  p.keyword = "none";
  return p;
}

std::vector<ParamSpec> make_table() {
  return {
      // --- model: which chain, in which units (Ferre 2018 eq. 3.1; Carlson & Langer 1989 eq. 2.2)
      // ---
      choice("model.kind", "bk", {"bk", "bkp", "1dof", "ofc"},
             "bk: plain Burridge-Knopoff chain, pad fixed; bkp: BK-Pad, the pad moves; "
             "1dof: one block with spring and damper (thesis eq. 2.11); ofc: the "
             "Olami-Feder-Christensen automaton on model.blocks x model.rows sites (1992)"),
      choice("model.parameterisation", "carlson-langer", {"carlson-langer", "thesis", "si"},
             "carlson-langer: dimensionless units of eq. 2.2 (m_u = k_p = F0 = 1); "
             "thesis: Table 3.1 scalings; si: SI units per unit fault area (friction.law = rsf)"),
      integer("model.blocks", "100", 1, 1e7, "", "number of blocks N"),
      choice("model.boundary", "free", {"free", "periodic"},
             "chain ends: free (missing neighbour, no spring) or periodic (a ring); for ofc the "
             "lattice's edges along strike: free is OFC's open edge (stress pushed over it is "
             "lost)"),
      integer("model.rows", "1", 1, 1e7, "",
              "rows across strike: the lattice is model.blocks x model.rows (bk, bkp, ofc; "
              "1 is the chain; 1dof runs one block)"),
      choice("model.boundary_y", "free", {"free", "periodic"},
             "lattice edges across strike (model.rows > 1, or ofc): free has no spring past "
             "the edge (for ofc the open edge: stress pushed over it is lost), periodic wraps "
             "row model.rows - 1 to row 0"),
      choice("model.coupling", "nearest", {"nearest", "range", "power"},
             "block-to-block springs: nearest (k_c to each neighbour), range (k_c/R to every "
             "block within R = model.range on each side; Xia, Gould, Klein & Rundle 2005) or "
             "power (k_c r^-p / sum_{s<=R} s^-p at distance r <= R, p = "
             "model.coupling_exponent); every choice sums to k_c per side"),
      integer("model.range", "1", 1, 1e6, "",
              "R: blocks coupled on each side (model.coupling = range or power); R = 1 is the "
              "nearest-neighbour chain; a free chain needs R < N, a periodic one 2R < N"),
      real("model.coupling_exponent", "3", '[', 0, 100, ']', "",
           "p of the power kernel's springs r^-p (model.coupling = power; 3 is the elastic "
           "kernel's 1/r^3)"),
      real("model.viscosity", "0", '[', 0, kHuge, ']', "force time/length",
           "viscous coupling eta (Myers & Langer 1993): dashpots beside the coupling's springs, "
           "eta (w'_{j-1} - 2 w'_j + w'_{j+1}) for nearest neighbours, shaped as the stencil "
           "with sum eta for range and power; event and continuous runs (rk2, rk4, verlet)"),
      real("model.l", "10", '[', 0, 1e4, ']', "",
           "stiffness ratio l, neighbour spring k_c = l^2 (carlson-langer only); on a lattice "
           "the spring along strike"),
      auto_stiffness("model.l_y", 1e4,
                     "lattice (model.rows > 1): stiffness ratio across strike, k_c_y = l_y^2 "
                     "(carlson-langer only); auto: equal to model.l"),
      real("model.pad_mass", "100", '(', 0, kHuge, ']', "mass", "pad mass m_x (thesis only)"),
      real("model.caliper_stiffness", "100", '[', 0, kHuge, ']', "force/length",
           "caliper-pad spring k_p0 (thesis only)"),
      real("model.damping_ratio", "0.0833333333333333", '[', 0, 1e3, ']', "",
           "damping ratio zeta: pad damper for bkp, block damper for 1dof"),
      real("model.s_m", "1", '(', 0, 1e6, ']', "", "mass scaling s_m: m_u = s_m m_x / N"),
      real("model.s_p", "1", '(', 0, 1e6, ']', "",
           "pulling-spring scaling s_p: k_p = s_p k_p0 / N"),
      real("model.s_c", "0.01", '[', 0, 1e6, ']', "",
           "coupling scaling s_c: k_c = s_c k_p0 N (thesis only); on a lattice k_c = s_c k_p0 "
           "model.blocks along strike"),
      auto_stiffness("model.s_c_y", 1e6,
                     "lattice (model.rows > 1): coupling scaling across strike, k_c_y = s_c_y k_p0 "
                     "model.rows (thesis only); auto: equal to model.s_c"),
      real("model.rayleigh_alpha", "0", '[', 0, kHuge, ']', "1/time",
           "Rayleigh damping alpha_M M + beta_K K of blocks and pad (K with k_c, k_p and the pad "
           "row; continuous runs and bkquake stability, event runs refuse it): alpha_M"),
      real("model.rayleigh_beta", "0", '[', 0, kHuge, ']', "time",
           "Rayleigh damping alpha_M M + beta_K K: beta_K"),
      // si parameterisation (rate-and-state friction): per unit fault area.
      real("model.stiffness", "2e9", '(', 0, kHuge, ']', "Pa/m",
           "loading spring k per unit area between block and plate (si; QDYN's spring-block: "
           "G/L)"),
      real("model.coupling_stiffness", "0", '[', 0, kHuge, ']', "Pa/m",
           "nearest-neighbour spring k_c per unit area between blocks (si)"),
      choice("model.dynamics", "quasi-dynamic", {"quasi-dynamic", "inertial"},
             "quasi-dynamic: elastic stress minus radiation damping eta V balances friction "
             "(Rice 1993); inertial: model.mass_per_area accelerates the block (si)"),
      real("model.shear_modulus", "2e10", '(', 0, kHuge, ']', "Pa",
           "shear modulus G of the radiation damping eta = G/(2 c_s) (si)"),
      real("model.shear_wave_speed", "3000", '[', 0, kHuge, ']', "m/s",
           "shear-wave speed c_s of the radiation damping eta = G/(2 c_s); 0: no radiation "
           "damping (si)"),
      real("model.mass_per_area", "1e6", '(', 0, kHuge, ']', "kg/m^2",
           "block mass per unit fault area m (model.dynamics = inertial)"),

      // --- ofc: the automaton (Olami, Feder & Christensen 1992) ---
      real("ofc.alpha", "0.2", '(', 0, 0.25, ']', "",
           "share alpha of a toppling site's stress given to each of its z = 4 neighbours "
           "(Olami, Feder & Christensen 1992); 0.25 conserves stress away from free edges"),
      choice("ofc.order", "generations", {"generations", "sequential"},
             "toppling order: generations (parallel update: every unstable site of a generation "
             "releases what it held at the generation's start) or sequential (one site at a "
             "time, first in first out)"),
      real("ofc.relaxation_time", "0", '[', 0, 1e15, ']', "drive",
           "viscoelastic relaxation (after Hainzl, Zoller & Kurths 1999): pending stress flows "
           "into a site as exp(-drive / relaxation_time); 0: off"),
      real("ofc.relaxation_alpha", "0", '[', 0, 0.25, ']', "",
           "share of a toppling site's stress each neighbour receives as pending stress "
           "(relaxation); ofc.alpha + ofc.relaxation_alpha <= 0.25"),

      // --- friction: the law phi(y) (Ferre 2018 eq. 3.5; Carlson et al. 1991 eq. 2.9) ---
      choice(
          "friction.law", "clst91", rsf_and_law_names(),
          "thesis (eq. 3.5, backslip allowed), clst91 (Carlson et al. 1991 eq. 2.9, no "
          "backslip), cl89 (Carlson-Langer 1989 eq. 2.3; continuous runs only, event runs refuse "
          "it), none (frictionless, continuous verification runs only), table (tabulated, "
          "friction.table; thesis Fig. 4.8), rsf (Dieterich-Ruina rate-and-state friction, "
          "[rsf]; model.parameterisation = si, drive.mode = continuous)"),
      real("friction.F0", "1", '(', 0, kHuge, ']', "force/mass",
           "static threshold per unit block mass F0 (thesis only)"),
      real("friction.sigma", "0.01", '[', 0, 1, ')', "",
           "drop sigma from static to kinetic friction"),
      real("friction.alpha", "2.5", '[', 0, 1e6, ']', "",
           "velocity weakening alpha, v_c = 1/(2 alpha) (carlson-langer only)"),
      real("friction.vc", "1", '(', 0, kHuge, ']', "length/time",
           "characteristic velocity v_c (thesis only)"),
      path("friction.table",
           "CSV file of the table law (friction.law = table): columns speed, friction "
           "(docs/reference/scenes.md); relative to the scene file's folder"),

      // --- rsf: rate-and-state friction (Dieterich 1979; Ruina 1983), friction.law = rsf ---
      real("rsf.a", "0.01", '(', 0, 10, ']', "", "direct-effect parameter a"),
      real("rsf.b", "0.025", '[', 0, 10, ']', "",
           "rate-and-state b (evolution effect; not the Gutenberg-Richter b)"),
      real("rsf.dc", "1e-05", '(', 0, 1e6, ']', "m", "critical slip distance D_c"),
      real("rsf.mu0", "0.6", '[', 0, 10, ']', "", "reference friction mu* at rsf.v0"),
      real("rsf.v0", "1e-06", '(', 0, 1e6, ']', "m/s", "reference slip rate V*"),
      choice("rsf.state_law", "aging", {"aging", "slip"},
             "state evolution: aging (d theta/dt = 1 - V theta/D_c) or slip (d theta/dt = "
             "-(V theta/D_c) ln(V theta/D_c))"),
      choice("rsf.form", "log", {"log", "regularised"},
             "log: mu* + a ln(V/V*) + b ln(V* theta/D_c); regularised: a asinh(V/(2V*) "
             "exp((mu* + b ln(V* theta/D_c))/a)) (Rice & Ben-Zion 1996; Lapusta et al. 2000)"),
      real("rsf.normal_stress", "5e6", '(', 0, kHuge, ']', "Pa",
           "effective normal stress sigma (friction.sigma stays Carlson-Langer's drop)"),
      real("rsf.v_threshold", "0.001", '(', 0, 1e6, ']', "m/s",
           "seismic slip rate V_th: an event is an interval in which some block slips faster; "
           "must exceed drive.speed (the plate rate)"),
      real("rsf.v_init", "2e-05", '(', 0, 1e6, ']', "m/s", "slip rate of every block at t = 0"),
      positive_or_auto("rsf.theta_init", 1e15, "s",
                       "state theta of every block at t = 0; auto: steady state at the plate "
                       "rate, rsf.dc/drive.speed"),
      path("rsf.blocks",
           "CSV file of per-block a, b and D_c (header block,a,b,dc, one row per block 0..N-1 in "
           "order; docs/explanation/rate-and-state.md); relative to the scene file's folder; "
           "none: every block has rsf.a, rsf.b, rsf.dc"),
      // rate-and-state keys: slow slip written apart, and per-block values from a pattern.
      real("rsf.slow_slip_threshold", "0", '[', 0, 1e6, ']', "m/s",
           "V_slow: slow-slip and afterslip episodes (some block faster than V_slow, none reaching "
           "rsf.v_threshold) are written to slow_slip.csv; between drive.speed and "
           "rsf.v_threshold; 0: off"),
      choice("rsf.pattern", "uniform", {"uniform", "asperities"},
             "per-block values: uniform (rsf.a, rsf.b everywhere), or asperities: blocks with x "
             "mod rsf.pattern_period < rsf.pattern_width (and the same across strike on a lattice) "
             "keep rsf.a and rsf.b, the others are barriers with a and b swapped"),
      integer("rsf.pattern_period", "10", 2, 1e7, "", "blocks from one asperity to the next"),
      integer("rsf.pattern_width", "5", 1, 1e7, "",
              "blocks of each asperity; below rsf.pattern_period"),

      // --- drive: how the substrate moves ---
      choice("drive.mode", "events", {"events", "continuous"},
             "events: quasistatic loading, one relaxation per slip event (nu -> 0); "
             "continuous: integrate at finite substrate speed"),
      real("drive.speed", "0.01", '[', 0, 1e6, ']', "length/time",
           "substrate speed v (continuous mode; the start value of a steps schedule)"),
      choice("drive.schedule", "constant", {"constant", "steps", "ramp"},
             "substrate speed over time (continuous mode)"),
      real("drive.step_increment", "0.005", '[', -1e6, 1e6, ']', "length/time",
           "speed change at each step (schedule steps)"),
      real("drive.step_interval", "2000", '(', 0, kLongTime, ']', "time",
           "time between speed steps (schedule steps)"),
      real("drive.ramp_from", "0", '[', 0, 1e6, ']', "length/time",
           "speed at the start of the ramp (schedule ramp)"),
      real("drive.ramp_to", "1", '[', 0, 1e6, ']', "length/time",
           "speed at the end of the ramp (schedule ramp)"),
      real("drive.ramp_duration", "40000", '(', 0, kLongTime, ']', "time",
           "time over which the speed ramps (schedule ramp)"),

      // --- run: length, seed, start, checkpoints ---
      integer("run.events", "100000", 0, 1e12, "", "events to record (events mode)"),
      integer("run.transient_events", "1000", 0, 1e12, "",
              "events discarded before recording starts (events mode)"),
      real("run.duration", "1000", '(', 0, kLongTime, ']', "time",
           "simulated time (continuous mode)"),
      integer("run.seed", "20261121", 0, kMaxInt64, "", "random seed (initial disorder)"),
      real("run.initial_disorder", "0.01", '[', 0, 10, ']', "D0",
           "initial displacements uniform in +-value*D0, D0 = F0 m_u / k_p"),
      choice("run.start", "disorder", {"disorder", "equilibrium"},
             "disorder: random displacements (run.initial_disorder), all stuck; equilibrium: "
             "steady sliding at the start speed plus run.start_mode (continuous mode)"),
      choice("run.start_mode", "none", {"none", "chain", "pad", "1dof"},
             "family of the mode added to the equilibrium start (bkquake stability lists them)"),
      integer("run.start_mode_index", "0", 0, 1e7, "", "index of that mode"),
      real("run.start_amplitude", "1e-4", '(', 0, 1, ']', "",
           "largest speed of the perturbation as a fraction of the start speed"),
      integer("run.max_steps_per_event", "200000000", 1, 1e15, "",
              "give up on an event after this many relaxation steps (a runaway: dt or the scene is "
              "wrong)"),
      integer(
          "run.checkpoint_events", "0", 0, 1e12, "",
          "write a checkpoint every this many events (continuous runs: slip episodes; 0 = off)"),
      real("run.checkpoint_seconds", "600", '[', 0, 1e9, ']', "wall s",
           "write a checkpoint at least this often in wall-clock seconds, the first after 30 s "
           "(0 = off)"),
      choice("run.accuracy", "warn", {"warn", "error"},
             "what a run does when an accuracy indicator (energy residual, omega_max*dt, event "
             "steps) is above its threshold: warn on stderr, or fail with exit 2 keeping the "
             "outputs (unattended runs)"),

      // --- integrator: the stepper of the dynamic phase ---
      choice("integrator.scheme", "rk4", stepper_keywords(),
             "rk2 (explicit midpoint), rk4, verlet, theta (theta-method, set-valued friction), "
             "adaptive (event-located adaptive reference)"),
      real("integrator.dt", "0.01", '(', 0, 1e6, ']', "time", "time step"),
      choice("integrator.transitions", "step", {"step", "located"},
             "where stick and slip happen: step (at the end of the step that crosses them, first "
             "order) or located (inside the step, on its dense output: the scheme's order) "
             "(schemes rk2, rk4, verlet)"),
      real("integrator.tolerance", "1e-08", '[', 1e-14, 1e-2, ']', "",
           "local error tolerance (scheme adaptive; friction.law = rsf: of ln V, ln theta and "
           "slip/(D_c + |slip|) per Dormand-Prince 5(4) step)"),
      real("integrator.theta", "0.5", '[', 0.5, 1, ']', "",
           "implicit weight theta of the theta-method: 1/2 trapezoidal (conserves), 1 backward "
           "Euler (damps) (scheme theta)"),

      // --- output ---
      real("output.every", "1", '(', 0, kLongTime, ']', "time",
           "time between timeseries rows (continuous mode)"),
      boolean("output.blocks", "false", "also write block trajectories (continuous mode)"),
      integer("output.block_first", "0", 0, 1e7, "",
              "first block written to blocks.csv (output.blocks; 0-based)"),
      integer("output.block_count", "0", 0, 1e7, "",
              "how many adjacent blocks blocks.csv holds from output.block_first (0: to the end)"),
      boolean("output.status", "false",
              "append the node status (blocks stuck, sliding forward, sliding backward) to "
              "timeseries.csv (continuous mode)"),
      boolean("output.energy", "false",
              "write energy_samples.csv and energy.csv: mechanical energy from the sliding "
              "equilibrium, its windowed mean and rate, the braking force (continuous mode)"),
      real("output.energy_window", "10", '(', 0, kLongTime, ']', "time",
           "window dT of the energy means (50 % overlap)"),
      real("output.energy_tol", "0.001", '(', 0, kHuge, ']', "1/time",
           "the energy has settled once |tau_E| stays below this in every later window"),
      choice("output.catalog", "csv", {"csv", "hdf5", "hdf5-deflate", "none"},
             "the event catalogue: csv (catalog.csv), hdf5 (catalog.h5, one table), "
             "hdf5-deflate (the same table compressed: a quarter of the size, slower), none (no "
             "catalogue; the histogram and the fit are still written)"),
      none_real("output.event_slip", kMuLimit, "",
                "write event_slip.csv (event runs): the slip of every block of each event with "
                "mu >= this, one row per block (event,block,slip; a lattice of more than one "
                "row adds row after block, the OFC automaton topplings after slip, its slip "
                "being the stress a site released); none: not written"),
      integer("output.segment_blocks", "4", 1, 1e6, "",
              "blocks M of the segment statistics' errors in segments.csv (thesis eq. 4.3)"),

      // --- stats: magnitude histogram and fits ---
      real("stats.bin_width", "0.2", '(', 0, 10, ']', "", "magnitude bin width of the histogram"),
      auto_real("stats.mu_min", kMuLimit, "",
                "lower end of the Gutenberg-Richter fit window, or auto"),
      auto_real("stats.mu_max", kMuLimit, "",
                "upper end of the Gutenberg-Richter fit window, or auto"),
  };
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string bound_text(const ParamSpec& p, double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (p.type == ParamType::Integer) {
    if (x >= kMaxInt64) return "9223372036854775807";
    return std::to_string(static_cast<std::int64_t>(x));
  }
  return format_real(x);
}

std::string suffix(const std::string& origin) {
  return origin.empty() ? "" : " (" + origin + ")";
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

[[noreturn]] void unknown_key(const std::string& key, const std::string& origin) {
  throw Error("unknown key '" + key + "'" + suffix(origin) + key_suggestion(key));
}

// Parses `text` for `p`; returns the normalised text or throws naming key, value and range.
std::string normalise(const ParamSpec& p, const std::string& raw, const std::string& origin) {
  const std::string text = trim(raw);
  const std::string where = suffix(origin);
  // A NUL byte would end the message that quotes the value (a C string) and hide the rest.
  if (const auto nul = raw.find('\0'); nul != std::string::npos)
    throw Error(p.key + ": the value holds a NUL byte at character " + std::to_string(nul + 1) +
                ", which no value may contain" + where);
  switch (p.type) {
    case ParamType::Choice:
      if (std::find(p.choices.begin(), p.choices.end(), text) == p.choices.end())
        throw Error(p.key + ": expected one of " + allowed_text(p) + ", got '" + text + "'" +
                    where);
      return text;
    case ParamType::Path:
      return text;
    case ParamType::Boolean: {
      const std::string t = lower(text);
      if (t == "true" || t == "yes" || t == "1" || t == "on") return "true";
      if (t == "false" || t == "no" || t == "0" || t == "off") return "false";
      throw Error(p.key + ": expected a boolean (true|false|yes|no|on|off|1|0), got '" + text +
                  "'" + where);
    }
    case ParamType::Integer: {
      const std::string what = "expected an integer in " + allowed_text(p);
      std::int64_t v = 0;
      const char* b = text.data();
      const char* e = text.data() + text.size();
      if (b != e && *b == '+') ++b;
      const auto res = std::from_chars(b, e, v);
      if (text.empty() || res.ec == std::errc::invalid_argument || res.ptr != e)
        throw Error(p.key + ": " + what + ", got '" + text + "'" + where);
      if (res.ec == std::errc::result_out_of_range)
        throw Error(p.key + ": " + what + ", got " + text + " (too large)" + where);
      if (static_cast<double>(v) < p.min || static_cast<double>(v) > p.max)
        throw Error(p.key + ": " + what + ", got " + text + where);
      return std::to_string(v);
    }
    case ParamType::Real: {
      if (p.allow_auto && text == p.keyword) return text;
      const std::string what = "expected a value in " + allowed_text(p);
      double v = 0;
      const char* b = text.data();
      const char* e = text.data() + text.size();
      if (b != e && *b == '+') ++b;
      const auto res = std::from_chars(b, e, v);
      // from_chars reports tiny/huge magnitudes as out of range; those are still numbers
      // and are judged by the range check (huge ones end up as inf, outside every range).
      if (text.empty() || res.ec == std::errc::invalid_argument || res.ptr != e || std::isnan(v))
        throw Error(p.key + ": " + what + ", got '" + text + "'" + where);
      if (res.ec == std::errc::result_out_of_range)
        v = std::strtod(std::string(b, e).c_str(), nullptr);
      const bool below = p.min_open ? !(v > p.min) : !(v >= p.min);
      const bool above = p.max_open ? !(v < p.max) : !(v <= p.max);
      if (below || above || std::isinf(v))
        throw Error(p.key + ": " + what + ", got " + text + where);
      return format_real(v);
    }
  }
  return text;
}

}  // namespace

struct KeyCondition {
  std::string controller;
  std::vector<std::string> values;
};

struct KeyDependency {
  std::vector<std::string> keys;
  std::vector<KeyCondition> any_of;
};

namespace {

// Keys that only mean something under other keys' values (the applies-when part of the
// declarations): a key applies when every row that lists it holds, and a row holds when
// any of its conditions does. A key given where it does not apply is refused when it came
// from --set and ignored with a warning when it came from a scene file (drop_inapplicable);
// to_ini() comments it out, so a run's own scene.ini reads back to the same scene.
const std::vector<KeyDependency>& dependencies() {
  static const std::vector<KeyDependency> deps = {
      {{"model.pad_mass", "model.caliper_stiffness", "model.s_c", "model.s_c_y", "friction.F0",
        "friction.vc"},
       {{"model.parameterisation", {"thesis"}}}},
      {{"model.l", "model.l_y", "friction.alpha"},
       {{"model.parameterisation", {"carlson-langer"}}}},
      {{"model.range"}, {{"model.coupling", {"range", "power"}}}},
      {{"model.coupling_exponent"}, {{"model.coupling", {"power"}}}},
      // The pad (bkp) and the single block (1dof) have dampers; the plain chain has none.
      {{"model.damping_ratio"}, {{"model.kind", {"bkp", "1dof"}}}},
      // Block scalings of Table 3.1; in carlson-langer units they only scale the pad.
      {{"model.s_m", "model.s_p"},
       {{"model.parameterisation", {"thesis"}}, {"model.kind", {"bkp"}}}},
      {{"drive.speed", "drive.schedule", "run.duration", "output.every", "output.blocks",
        "output.block_first", "output.block_count", "output.segment_blocks", "output.status",
        "output.energy", "output.energy_window", "output.energy_tol"},
       {{"drive.mode", {"continuous"}}}},
      {{"run.events", "run.transient_events", "run.max_steps_per_event", "output.event_slip"},
       {{"drive.mode", {"events"}}}},
      {{"drive.step_increment", "drive.step_interval"}, {{"drive.schedule", {"steps"}}}},
      {{"drive.ramp_from", "drive.ramp_to", "drive.ramp_duration"}, {{"drive.schedule", {"ramp"}}}},
      {{"integrator.tolerance"}, {{"integrator.scheme", {"adaptive"}}, {"friction.law", {"rsf"}}}},
      // Rate-and-state friction runs in SI units on its own integrator (engine/rsf_cycle.hpp).
      {{"rsf.a", "rsf.b", "rsf.dc", "rsf.mu0", "rsf.v0", "rsf.state_law", "rsf.form",
        "rsf.normal_stress", "rsf.v_threshold", "rsf.v_init", "rsf.theta_init", "rsf.blocks",
        "rsf.slow_slip_threshold", "rsf.pattern"},
       {{"friction.law", {"rsf"}}}},
      {{"rsf.pattern_period", "rsf.pattern_width"}, {{"rsf.pattern", {"asperities"}}}},
      {{"model.stiffness", "model.coupling_stiffness", "model.dynamics", "model.shear_modulus",
        "model.shear_wave_speed", "model.mass_per_area"},
       {{"model.parameterisation", {"si"}}}},
      {{"model.mass_per_area"}, {{"model.dynamics", {"inertial"}}}},
      // rate-and-state keys: the coupling's shape applies to every law (the chain and the lattice).
      {{"model.coupling"}, {{"friction.law", rsf_and_law_names()}}},
      {{"integrator.scheme", "integrator.dt", "integrator.transitions", "friction.sigma",
        "run.initial_disorder", "run.max_steps_per_event", "run.start", "model.viscosity",
        "model.rayleigh_alpha", "model.rayleigh_beta", "model.damping_ratio", "output.status",
        "output.energy", "output.energy_window", "output.energy_tol", "output.segment_blocks"},
       {{"friction.law", law_names()}}},
      {{"integrator.theta"}, {{"integrator.scheme", {"theta"}}}},
      {{"integrator.transitions"}, {{"integrator.scheme", {"rk2", "rk4", "verlet"}}}},
      {{"output.energy_window", "output.energy_tol"}, {{"output.energy", {"true"}}}},
      {{"run.start_mode", "run.start_mode_index", "run.start_amplitude"},
       {{"run.start", {"equilibrium"}}}},
      {{"friction.table"}, {{"friction.law", {"table"}}}},
      // The automaton has a threshold and a share alpha, no masses, friction or time steps.
      {{"ofc.alpha", "ofc.order", "ofc.relaxation_time", "ofc.relaxation_alpha"},
       {{"model.kind", {"ofc"}}}},
      {{"model.parameterisation",
        "model.coupling",
        "model.range",
        "model.coupling_exponent",
        "model.viscosity",
        "model.l",
        "model.l_y",
        "model.pad_mass",
        "model.caliper_stiffness",
        "model.s_c",
        "model.s_c_y",
        "model.s_m",
        "model.s_p",
        "model.damping_ratio",
        "model.rayleigh_alpha",
        "model.rayleigh_beta",
        "friction.law",
        "friction.F0",
        "friction.sigma",
        "friction.alpha",
        "friction.vc",
        "friction.table",
        "integrator.scheme",
        "integrator.dt",
        "integrator.tolerance",
        "integrator.theta",
        "run.initial_disorder",
        "run.max_steps_per_event",
        "run.accuracy"},
       {{"model.kind", {"bk", "bkp", "1dof"}}}},
  };
  return deps;
}

// The across-strike stiffness keys: they apply only to a lattice (model.rows > 1).
bool lattice_key(const std::string& key) {
  return key == "model.l_y" || key == "model.s_c_y";
}

std::string join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : sep) + p;
  return out;
}

// "drive.schedule = steps", "model.parameterisation = thesis or model.kind = bkp".
std::string needs_text(const KeyDependency& d) {
  std::vector<std::string> parts;
  for (const auto& c : d.any_of) parts.push_back(c.controller + " = " + join(c.values, "|"));
  return join(parts, " or ");
}

}  // namespace

// The first row listing `key` that does not hold in this scene, or nullptr.
const KeyDependency* Scene::failing_dependency(const std::string& key) const {
  for (const auto& d : dependencies()) {
    if (std::find(d.keys.begin(), d.keys.end(), key) == d.keys.end()) continue;
    bool holds = false;
    for (const auto& c : d.any_of)
      holds = holds ||
              std::find(c.values.begin(), c.values.end(), text(c.controller)) != c.values.end();
    if (!holds) return &d;
  }
  return nullptr;
}

// Why `key` does not apply: "needs drive.schedule = steps, but drive.schedule = constant".
std::string Scene::why_not(const std::string& key) const {
  if (key == "model.blocks") return "model.kind = 1dof has one block";
  if (key == "model.rows")
    return choice("model.kind") == "1dof" ? "model.kind = 1dof has one block"
                                          : "one row is the chain (more make a lattice)";
  if (key == "model.boundary_y")
    return "needs model.rows > 1 or model.kind = ofc, but model.rows = " + text("model.rows") +
           " and model.kind = " + choice("model.kind");
  if (lattice_key(key) && failing_dependency(key) == nullptr)
    return "needs model.rows > 1, but model.rows = " + text("model.rows");
  const KeyDependency* d = failing_dependency(key);
  if (!d) return "";
  std::vector<std::string> now;
  for (const auto& c : d->any_of) now.push_back(c.controller + " = " + text(c.controller));
  return "needs " + needs_text(*d) + ", but " + join(now, " and ");
}

const std::vector<ParamSpec>& parameter_table() {
  static const std::vector<ParamSpec> table = make_table();
  return table;
}

const ParamSpec* find_param(const std::string& key) {
  for (const auto& p : parameter_table())
    if (p.key == key) return &p;
  return nullptr;
}

std::string allowed_text(const ParamSpec& p) {
  switch (p.type) {
    case ParamType::Choice: {
      std::string s;
      for (const auto& c : p.choices) s += (s.empty() ? "" : "|") + c;
      return s;
    }
    case ParamType::Boolean:
      return "true|false";
    case ParamType::Path:
      return "a file path";
    case ParamType::Integer:
    case ParamType::Real: {
      std::string s = std::string(p.min_open ? "(" : "[") + bound_text(p, p.min) + ", " +
                      bound_text(p, p.max) + (p.max_open ? ")" : "]");
      if (p.allow_auto) s += " or " + p.keyword;
      return s;
    }
  }
  return "";
}

std::string option_value(const std::string& option, const std::string& key,
                         const std::string& text) {
  const ParamSpec* p = find_param(key);
  if (!p) throw std::logic_error("option_value: no parameter '" + key + "'");
  try {
    return normalise(*p, text, "");
  } catch (const Error&) {
    throw Error(option + ": expected " +
                (p->type == ParamType::Integer ? "an integer" : std::string("a value")) + " in " +
                allowed_text(*p) + " (as " + key + "), got " + quote_text(trim(text)));
  }
}

Scene::Scene() : origin(kBuiltInOrigin) {
  for (const auto& p : parameter_table()) {
    values_[p.key] = normalise(p, p.default_value, "default");
    given_[p.key] = false;
  }
}

Scene Scene::from_file(const std::string& path) {
  Scene scene = from_text(read_text_file(path, "scene file"), path);
  scene.resolve_paths(std::filesystem::absolute(path).parent_path());
  return scene;
}

void Scene::resolve_paths(const std::filesystem::path& folder) {
  for (const auto& p : parameter_table()) {
    std::string& v = values_[p.key];
    if (p.type == ParamType::Path && !v.empty() && std::filesystem::path(v).is_relative())
      v = (folder / v).lexically_normal().string();
  }
}

Scene Scene::from_text(const std::string& text, const std::string& origin_name) {
  Scene scene;
  scene.origin = origin_name;
  const std::string where = "in " + origin_name;
  std::set<std::string> seen;
  for (const auto& [key, value] : parse_ini(text, where)) {
    if (!find_param(key)) unknown_key(key, where);
    if (!seen.insert(key).second) throw Error(key + ": given more than once" + suffix(where));
    scene.set(key, value, where);
  }
  return scene;
}

void Scene::set(const std::string& key, const std::string& value, const std::string& where) {
  const ParamSpec* p = find_param(key);
  if (!p) unknown_key(key, where);
  values_[key] = normalise(*p, value, where);
  given_[key] = true;
  set_by_[key] = where;
}

void Scene::apply_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos)
    throw Error("--set expects section.key=value, got '" + assignment + "'");
  const std::string key = trim(assignment.substr(0, eq));
  if (key.empty()) throw Error("--set expects section.key=value, got '" + assignment + "'");
  set(key, assignment.substr(eq + 1), "--set");
  resolve_paths(std::filesystem::current_path());
}

bool Scene::applies(const std::string& key) const {
  if (key == "model.blocks") return choice("model.kind") != "1dof" || integer(key) == 1;
  // A chain is one row: given as 1 it is accepted (and left out of a chain's scene.ini), more
  // make a lattice of bk or bkp; 1dof refuses more in validate(). The edges across strike
  // mean something on a lattice, and for the automaton always.
  if (key == "model.rows" || key == "model.boundary_y")
    return choice("model.kind") == "ofc" ||
           (choice("model.kind") != "1dof" && integer("model.rows") > 1);
  if (lattice_key(key) && integer("model.rows") == 1) return false;
  return failing_dependency(key) == nullptr;
}

std::vector<std::string> Scene::drop_inapplicable() {
  std::vector<std::string> warnings;
  // In table order, so a controller is settled before the keys that depend on it.
  for (const auto& p : parameter_table()) {
    if (!is_set(p.key) || applies(p.key) || p.key == "model.blocks" || p.key == "model.rows")
      continue;
    const std::string& from = set_by_.at(p.key);
    if (from == "--set")
      throw Error("--set " + p.key + "=" + text(p.key) + " does not apply to this scene: it " +
                  why_not(p.key) + "; remove it or change what it depends on");
    warnings.push_back(p.key + " = " + text(p.key) + " (" + from + ") does not apply to this " +
                       "scene: it " + why_not(p.key) + "; ignored");
    values_[p.key] = normalise(p, p.default_value, "default");
    given_[p.key] = false;
  }
  return warnings;
}

std::string Scene::where() const {
  bool overridden = false;
  for (const auto& [key, from] : set_by_) overridden = overridden || from == "--set";
  // The built-in default's origin describes the scene it starts as (event-driven); once
  // --set has changed it, that description may no longer hold (drive.mode = continuous).
  if (origin == kBuiltInOrigin)
    return overridden ? " (built-in default scene with --set overrides)"
                      : " (built-in default scene)";
  return suffix("scene " + origin + (overridden ? " with --set overrides" : ""));
}

namespace {
void check_stencil_cost(const Scene& s, const std::string& where);

// validate()'s checks of a rate-and-state scene (friction.law = rsf, model.parameterisation = si):
// the two go together, continuous drive, a chain or one block, V_th above the plate rate.
void check_rsf(const Scene& s, const std::string& where) {
  const std::string& law = s.choice("friction.law");
  if (law != "rsf")
    throw Error("model.parameterisation = si is for friction.law = rsf, but friction.law = " + law +
                "; allowed: friction.law = rsf, or model.parameterisation = carlson-langer " +
                "or thesis" + where);
  if (s.choice("model.parameterisation") != "si")
    throw Error("friction.law = rsf runs in SI units, but model.parameterisation = " +
                s.choice("model.parameterisation") + "; allowed: model.parameterisation = si" +
                where);
  if (s.choice("drive.mode") != "continuous")
    throw Error("drive.mode = " + s.choice("drive.mode") +
                " with friction.law = rsf: bkquake has no event-driven rate-and-state engine yet; "
                "allowed: drive.mode = continuous (whole cycles, rsf.v_threshold defines events)" +
                where);
  const std::string& kind = s.choice("model.kind");
  if (kind != "bk" && kind != "1dof")
    throw Error("model.kind = " + kind +
                " with friction.law = rsf: allowed model.kind = bk or 1dof" + where);
  if (s.choice("drive.schedule") != "constant")
    throw Error("drive.schedule = " + s.choice("drive.schedule") +
                " with friction.law = rsf: the plate moves at a constant rate; allowed: "
                "drive.schedule = constant" +
                where);
  const double v_pl = s.real("drive.speed");
  if (!(v_pl > 0))
    throw Error("drive.speed = " + s.text("drive.speed") +
                " with friction.law = rsf: the plate rate must be positive (m/s)" + where);
  if (!(s.real("rsf.v_threshold") > v_pl))
    throw Error("rsf.v_threshold = " + s.text("rsf.v_threshold") +
                ": the seismic slip rate must exceed the plate rate drive.speed = " +
                s.text("drive.speed") + "; allowed: (" + s.text("drive.speed") + ", 1e6]" + where);
  // rate-and-state keys: slow slip between the plate rate and V_th; a pattern or a file.
  const double v_slow = s.real("rsf.slow_slip_threshold");
  if (v_slow != 0 && !(v_slow > v_pl && v_slow < s.real("rsf.v_threshold")))
    throw Error("rsf.slow_slip_threshold = " + s.text("rsf.slow_slip_threshold") +
                ": slow slip lies between the plate rate and the seismic rate; allowed: 0 (off) "
                "or (" +
                s.text("drive.speed") + ", " + s.text("rsf.v_threshold") + ")" + where);
  if (s.choice("rsf.pattern") != "uniform" && !s.text("rsf.blocks").empty())
    throw Error("rsf.pattern = " + s.choice("rsf.pattern") +
                " with rsf.blocks: per-block values come from one of them; allowed: rsf.pattern = "
                "uniform with a file, or no rsf.blocks" +
                where);
  if (s.choice("rsf.pattern") == "asperities" && !(s.real("rsf.b") > 0))
    throw Error("rsf.b = " + s.text("rsf.b") +
                " with rsf.pattern = asperities: the barriers' direct effect is rsf.b; allowed: "
                "rsf.b > 0" +
                where);
  if (s.choice("rsf.pattern") == "asperities" &&
      s.integer("rsf.pattern_width") >= s.integer("rsf.pattern_period"))
    throw Error("rsf.pattern_width = " + s.text("rsf.pattern_width") +
                ": an asperity must be narrower than the pattern's period rsf.pattern_period = " +
                s.text("rsf.pattern_period") + "; allowed: 1 to " +
                std::to_string(s.integer("rsf.pattern_period") - 1) + where);
}
}  // namespace

void Scene::validate() const {
  const std::string where = this->where();
  for (const auto& p : parameter_table()) {
    if (!is_set(p.key) || applies(p.key)) continue;
    if (p.key == "model.rows") {
      if (integer(p.key) == 1) continue;
      throw Error("model.rows = " + text(p.key) +
                  " with model.kind = 1dof: one block has one row; allowed: model.rows = 1, or "
                  "model.kind = bk, bkp or ofc" +
                  where);
    }
    if (p.key == "model.boundary_y" || (lattice_key(p.key) && failing_dependency(p.key) == nullptr))
      throw Error(p.key + " = " + text(p.key) +
                  " applies only to a lattice (model.rows > 1), but model.rows = " +
                  text("model.rows") + where);
    if (p.key == "model.blocks")
      throw Error("model.blocks = " + text(p.key) +
                  " contradicts model.kind = 1dof (a single block); remove model.blocks or set "
                  "it to 1" +
                  where);
    const KeyDependency* d = failing_dependency(p.key);
    std::vector<std::string> now;
    for (const auto& c : d->any_of) now.push_back(c.controller + " = " + text(c.controller));
    throw Error(p.key + " = " + text(p.key) + " applies only with " + needs_text(*d) + ", but " +
                join(now, " and ") + where);
  }
  if (choice("friction.law") == "table" && text("friction.table").empty())
    throw Error("friction.table: friction.law = table needs the table's file, got none" + where);
  if (choice("model.boundary") == "periodic" && integer("model.blocks") < 3)
    throw Error("model.boundary = periodic needs model.blocks >= 3, got model.blocks = " +
                text("model.blocks") + where);
  if (choice("model.kind") == "ofc") check_ofc(where);
  if (choice("model.kind") != "ofc" && integer("model.rows") > 1) check_lattice(where);
  if (applies("model.range") && integer("model.rows") == 1)
    check_range("model.blocks", "model.boundary", where);
  if (applies("model.range")) check_stencil_cost(*this, where);
  if (choice("run.start") == "equilibrium" && choice("drive.mode") != "continuous")
    throw Error("run.start = equilibrium needs drive.mode = continuous, but drive.mode = " +
                choice("drive.mode") + where);
  const auto lo = real_or_auto("stats.mu_min");
  const auto hi = real_or_auto("stats.mu_max");
  if (lo && hi && *lo >= *hi)
    throw Error("stats.mu_min = " + text("stats.mu_min") +
                " must be below stats.mu_max = " + text("stats.mu_max") + where);
  if (choice("friction.law") == "rsf" || choice("model.parameterisation") == "si")
    check_rsf(*this, where);
  if (choice("drive.mode") == "continuous") check_continuous_run(where);
}

namespace {

// The springs of a wide stencil one evaluation of every block's force sums: the engine's
// construction (its tree of times to failure), a resume's, and each step of an event that
// spans the chain cost that many terms. A chain's block has 2R partners; a lattice's site
// those of the disc 0 < dx^2 + dy^2 <= R^2 (model/coupling.hpp), at most N - 1 along an axis.
// Above this bound (seconds per evaluation; the largest nearest-neighbour lattice costs
// 10^7 sites x 4 springs) a run would sit for minutes to hours before its first event:
// refused in one line naming the cost. Every shipped scene and study is below it by orders
// of magnitude.
constexpr double kMaxStencilTerms = 1e8;

void check_stencil_cost(const Scene& s, const std::string& where) {
  const std::int64_t r = s.integer("model.range"), nx = s.integer("model.blocks"),
                     ny = s.integer("model.rows");
  double partners = 0;
  std::string per;
  if (ny == 1) {
    partners = 2.0 * static_cast<double>(std::min(r, nx - 1));
    per = "2 model.range springs per block";
  } else {
    const std::int64_t ax = std::min(r, nx - 1), ay = std::min(r, ny - 1);
    for (std::int64_t dx = -ax; dx <= ax; ++dx) {
      const auto reach = static_cast<std::int64_t>(
          std::floor(std::sqrt(static_cast<double>(r * r - dx * dx)) + 1e-9));
      partners += static_cast<double>(2 * std::min(reach, ay) + 1);
    }
    partners -= 1;  // the site itself
    per = "the sites within model.range of each site";
  }
  const double terms = partners * static_cast<double>(nx) * static_cast<double>(ny);
  if (terms <= kMaxStencilTerms) return;
  const auto short_number = [](double x, int digits) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    return std::string(buf);
  };
  const std::string blocks = ny == 1 ? "model.blocks = " + s.text("model.blocks")
                                     : "model.blocks x model.rows = " + s.text("model.blocks") +
                                           " x " + s.text("model.rows");
  throw Error("model.range = " + s.text("model.range") + " with " + blocks + ": every force " +
              "evaluation sums " + short_number(terms, 3) + " springs (" + per +
              "), which would take minutes to hours before the first event; allowed: at most " +
              short_number(kMaxStencilTerms, 3) +
              " (blocks x springs per block): a smaller model.range or fewer blocks" + where);
}

}  // namespace

void Scene::check_range(const std::string& count_key, const std::string& boundary_key,
                        const std::string& where) const {
  // A spring reaching past a free end, or two offsets of a ring reaching the same block,
  // would not be the coupling the key describes.
  const std::int64_t r = integer("model.range"), n = integer(count_key);
  const bool ring = choice(boundary_key) == "periodic";
  if (ring ? 2 * r < n : r < n) return;
  throw Error(
      "model.range = " + text("model.range") + " with " + count_key + " = " + text(count_key) +
      " and " + boundary_key + " = " + choice(boundary_key) + ": allowed " +
      (ring ? "2 model.range < " + count_key + " (a ring)" : "model.range < " + count_key) + where);
}

void Scene::check_lattice(const std::string& where) const {
  // The BK lattice (Carlson 1991): what its engine and its forces are written for.
  const std::int64_t nx = integer("model.blocks"), ny = integer("model.rows");
  if (nx * ny > 10'000'000)
    throw Error("model.blocks x model.rows = " + text("model.blocks") + " x " + text("model.rows") +
                ": allowed at most 1e7 blocks for a bk or bkp lattice" + where);
  const bool py = choice("model.boundary_y") == "periodic";
  if (py && ny < 3)
    throw Error("model.boundary_y = periodic needs model.rows >= 3, got model.rows = " +
                text("model.rows") + where);
  if (real("model.viscosity") != 0)
    throw Error("model.viscosity = " + text("model.viscosity") +
                " with model.rows = " + text("model.rows") +
                ": the viscous coupling is written for chains; allowed on a lattice: "
                "model.viscosity = 0" +
                where);
  if (choice("drive.mode") == "continuous" && choice("run.start") == "equilibrium")
    throw Error("run.start = equilibrium with model.rows = " + text("model.rows") +
                ": steady sliding is solved for chains; allowed on a lattice: run.start = "
                "disorder" +
                where);
  if (!applies("model.range")) return;
  // A lattice's range couples a disc of radius R: per axis as for a chain (a lattice of one
  // column is the chain along y).
  if (nx > 1) check_range("model.blocks", "model.boundary", where);
  if (ny > 1) check_range("model.rows", "model.boundary_y", where);
}

void Scene::check_ofc(const std::string& where) const {
  if (choice("drive.mode") != "events")
    throw Error("drive.mode = " + choice("drive.mode") +
                " with model.kind = ofc: the automaton runs event by event only; allowed: "
                "drive.mode = events" +
                where);
  if (integer("model.blocks") * integer("model.rows") > 100'000'000)
    throw Error("model.blocks x model.rows = " + text("model.blocks") + " x " + text("model.rows") +
                ": allowed at most 1e8 sites for ofc" + where);
  const bool px = choice("model.boundary") == "periodic";  // its length is checked above
  const bool py = choice("model.boundary_y") == "periodic";
  if (py && integer("model.rows") < 3)
    throw Error("model.boundary_y = periodic needs model.rows >= 3, got model.rows = " +
                text("model.rows") + where);
  if (px && py && real("ofc.alpha") == 0.25)
    throw Error(
        "ofc.alpha = 0.25 with model.boundary = periodic and model.boundary_y = periodic: "
        "stress would never leave the lattice and an avalanche would never end; allowed: "
        "ofc.alpha < 0.25, or model.boundary or model.boundary_y = free" +
        where);
  // The relaxation's own limits are the engine's (one place states them).
  OfcParams p;
  p.nx = static_cast<int>(integer("model.blocks"));
  p.ny = static_cast<int>(integer("model.rows"));
  p.alpha = real("ofc.alpha");
  p.periodic_x = px;
  p.periodic_y = py;
  p.relaxation_time = real("ofc.relaxation_time");
  p.relaxation_alpha = real("ofc.relaxation_alpha");
  try {
    OfcEngine::check(p);
  } catch (const Error& e) {
    throw Error(e.what() + where);
  }
}

void Scene::check_continuous_run(const std::string& where) const {
  // The step counter is 64-bit and the clock a double: past 1e15 steps neither is safe.
  const double duration = real("run.duration");
  const double steps = duration / real("integrator.dt");
  if (!(steps <= kMaxSteps))
    throw Error("run.duration = " + text("run.duration") +
                " at integrator.dt = " + text("integrator.dt") + " is " + format_real(steps) +
                " time steps, more than a run can count (1e15); shorten run.duration or raise "
                "integrator.dt" +
                where);
  if (choice("drive.schedule") != "steps") return;
  // The speed after the last step within the run, v0 + k inc, must stay in drive.speed's
  // range: a negative speed would drive the substrate backwards, which no friction law here
  // is written for.
  const double v0 = real("drive.speed"), inc = real("drive.step_increment");
  const double interval = real("drive.step_interval");
  const double last = std::floor(duration / interval);
  const double v_end = v0 + last * inc;
  const ParamSpec& speed = *find_param("drive.speed");
  if (v_end >= speed.min && v_end <= speed.max) return;
  // The first step outside the range.
  const double k = inc < 0 ? std::floor(v0 / -inc) + 1 : std::floor((speed.max - v0) / inc) + 1;
  throw Error("drive.step_increment = " + text("drive.step_increment") +
              " takes the substrate speed out of " + allowed_text(speed) + " at step " +
              format_real(k) + " (time " + format_real(k * interval) + ", speed " +
              format_real(v0 + k * inc) + ") within run.duration = " + text("run.duration") +
              (inc < 0 ? ": the substrate would move backwards" : "") +
              "; shorten run.duration or change the schedule" + where);
}

namespace {
const ParamSpec& spec_of(const std::string& key, ParamType type) {
  const ParamSpec* p = find_param(key);
  if (!p) throw std::logic_error("scene: no parameter '" + key + "'");
  if (p->type != type) throw std::logic_error("scene: parameter '" + key + "' read as wrong type");
  return *p;
}
}  // namespace

double Scene::real(const std::string& key) const {
  const ParamSpec& p = spec_of(key, ParamType::Real);
  const std::string& t = values_.at(key);
  if (p.allow_auto && t == p.keyword)
    throw std::logic_error("scene: " + key + " is " + t + "; read it with real_or_auto()");
  return std::strtod(t.c_str(), nullptr);
}

std::optional<double> Scene::real_or_auto(const std::string& key) const {
  const ParamSpec& p = spec_of(key, ParamType::Real);
  const std::string& t = values_.at(key);
  if (p.allow_auto && t == p.keyword) return std::nullopt;
  return std::strtod(t.c_str(), nullptr);
}

std::int64_t Scene::integer(const std::string& key) const {
  spec_of(key, ParamType::Integer);
  return std::stoll(values_.at(key));
}

const std::string& Scene::choice(const std::string& key) const {
  spec_of(key, ParamType::Choice);
  return values_.at(key);
}

bool Scene::flag(const std::string& key) const {
  spec_of(key, ParamType::Boolean);
  return values_.at(key) == "true";
}

bool Scene::is_set(const std::string& key) const {
  const auto it = given_.find(key);
  if (it == given_.end()) throw std::logic_error("scene: no parameter '" + key + "'");
  return it->second;
}

const std::string& Scene::text(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) throw std::logic_error("scene: no parameter '" + key + "'");
  return it->second;
}

std::string Scene::to_ini(const std::vector<std::string>& header) const {
  std::ostringstream out;
  for (const auto& h : header) out << "# " << h << "\n";
  if (!header.empty()) out << "\n";
  // A section none of whose keys applies (the automaton's [ofc] in a chain's scene, the
  // chain's [friction] in the automaton's) is written as comments, header and all, so a
  // scene's non-comment lines are those of the keys it uses.
  std::map<std::string, bool> used;
  for (const auto& p : parameter_table()) used[p.key.substr(0, p.key.find('.'))] |= applies(p.key);
  std::string section;
  for (const auto& p : parameter_table()) {
    const auto dot = p.key.find('.');
    const std::string sec = p.key.substr(0, dot);
    const std::string name = p.key.substr(dot + 1);
    if (sec != section) {
      const char* mark = used[sec] ? "" : "# ";
      if (!section.empty()) out << (used[sec] ? "\n" : "#\n");
      out << mark << "[" << sec << "]\n";
      section = sec;
    }
    out << "# " << p.doc;
    if (!p.units.empty()) out << " [" << p.units << "]";
    out << " (allowed: " << allowed_text(p) << ")\n";
    const std::string& v = values_.at(p.key);
    if (applies(p.key))
      out << name << " = " << v << "\n";
    else
      out << "# " << name << " = " << v << "  (unused: " << why_not(p.key) << ")\n";
  }
  return out.str();
}

namespace {
// Keys added after scenes, checkpoints and summaries were first hashed. At their default
// they mean what a scene without them meant, so the hash leaves them out and runs made
// before the key existed still resume and merge.
bool added_later(const std::string& key) {
  static const std::set<std::string> keys{
      "model.rows", "model.boundary_y", "ofc.alpha", "model.coupling", "model.range",
      "model.coupling_exponent", "model.viscosity", "ofc.order", "ofc.relaxation_time",
      "ofc.relaxation_alpha", "model.l_y", "model.s_c_y",
      // Rate-and-state friction.
      "model.stiffness", "model.coupling_stiffness", "model.dynamics", "model.shear_modulus",
      "model.shear_wave_speed", "model.mass_per_area", "rsf.a", "rsf.b", "rsf.dc", "rsf.mu0",
      "rsf.v0", "rsf.state_law", "rsf.form", "rsf.normal_stress", "rsf.v_threshold", "rsf.v_init",
      "rsf.theta_init",
      // rate-and-state keys added later still.
      "rsf.slow_slip_threshold", "rsf.pattern", "rsf.pattern_period", "rsf.pattern_width"};
  return keys.count(key) != 0;
}
}  // namespace

std::uint64_t Scene::hash() const {
  std::uint64_t h = kFnv1a64Basis;
  for (const auto& p : parameter_table()) {
    // An unset file key leaves the hash of the scenes that do not use it as it was; so do
    // the keys added after scenes, their checkpoints and summaries were first hashed, at
    // their defaults (see added_later).
    if (p.type == ParamType::Path && values_.at(p.key).empty()) continue;
    // Likewise integrator.transitions at step, its meaning before the key existed, so that
    // checkpoints and results of those scenes keep their hash.
    if (p.key == "integrator.transitions" && values_.at(p.key) == "step") continue;
    if (added_later(p.key) && values_.at(p.key) == normalise(p, p.default_value, "default"))
      continue;
    h = fnv1a64(p.key + "=" + values_.at(p.key) + "\n", h);
    // rate-and-state keys: the per-block file's bytes, so that an edited file is another
    // scene (a resume refuses it). An unreadable file hashes as its name alone (the run then
    // refuses it when it reads the file).
    if (p.key == "rsf.blocks") {
      std::ifstream in(values_.at(p.key), std::ios::binary);
      std::ostringstream bytes;
      if (in && (bytes << in.rdbuf())) h = fnv1a64("rsf.blocks bytes=" + bytes.str() + "\n", h);
    }
  }
  return h;
}

std::string dump_defaults() {
  return Scene().to_ini({"bkquake scene with every key at its default value",
                         "the built-in default: the Carlson-Langer reference, event-driven",
                         "keys shown as comments are unused by this scene's choices"});
}

std::string key_suggestion(const std::string& key) {
  const ParamSpec* best = nullptr;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const auto& p : parameter_table()) {
    const std::size_t d = edit_distance(key, p.key);
    if (d < best_d) {
      best_d = d;
      best = &p;
    }
  }
  // A far-off "suggestion" only confuses; offer one when it plausibly is a typo.
  if (best && best_d <= std::max<std::size_t>(3, key.size() / 3))
    return "; did you mean '" + best->key + "'?";
  return "; see 'bkquake run --dump-defaults' for all keys";
}

}  // namespace bkq
