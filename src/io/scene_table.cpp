// The parameter table of bkquake: every scene key declared once, as one row that gives its
// type, default, allowed range, units and doc, the member of SceneValues it fills
// (io/scene_values.hpp), when it applies (the model kinds, units, schemes, drive modes and
// lattice shapes it needs), and whether it was added after scenes were first hashed. Reading,
// validation, --dump-defaults, the effective scene.ini, the reference table in
// docs/reference/scenes.md and the typed settings are all driven by these rows. The
// cross-key rules that remain (contradictory combinations) sit beside the rows they join.
//
// A new key: a constant in io/scene_keys.hpp, a member in io/scene_values.hpp, and a row in
// its section below (e.g. `real(key::rsf_x, at(&SceneValues::rsf, &RsfKeys::x), "1", '(',
// 0, 1e6, ']', "m", "doc").when(rsf_law()).later()`).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>

#include "core/error.hpp"
#include "core/format.hpp"
#include "engine/ofc.hpp"
#include "integrate/scheme_traits.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/scene_values.hpp"
#include "model/friction_laws.hpp"

namespace bkq {

namespace {

constexpr double kSeedMax = 9223372036854775807.0;  // 2^63 - 1 (rounds to 2^63 as a double)
// Sane bounds, so that no finite but absurd value reaches the physics: a mass, stiffness,
// force or velocity scale of the thesis parameterisation; a simulated time (run length,
// schedule period, output interval), beyond which 64-bit step counts and t + dt in double
// precision stop working at any usable dt; the magnitude mu = ln(moment) of any event of any
// chain bkquake can hold (|mu| <= 50: moments from 1e-22 to 5e21).
constexpr double kHuge = 1e12;
constexpr double kLongTime = 1e15;
constexpr double kMuLimit = 50;
constexpr double kMaxSteps = 1e15;  // time steps of a continuous run

// ---------------------------------------------------------------------------------------
// Binding a row to its member.

// A member of SceneValues, reached through pointers to members: at(&SceneValues::drive,
// &DriveSettings::speed) is values.drive.speed.
template <class... Ms>
struct Field {
  std::tuple<Ms...> path;
  template <class V>
  decltype(auto) ref(V& v) const {
    return std::apply([&v](auto... m) -> decltype(auto) { return (v.*....*m); }, path);
  }
  auto get(const SceneValues& v) const { return ref(v); }
  template <class T>
  void set(SceneValues& v, T x) const {
    ref(v) = std::move(x);
  }
};

template <class... Ms>
Field<Ms...> at(Ms... members) {
  return Field<Ms...>{std::tuple<Ms...>(members...)};
}

// output.catalog fills two members: the format and whether HDF5 is deflated.
struct CatalogAccess {
  std::pair<CatalogFormat, bool> get(const SceneValues& v) const {
    return {v.output.catalog, v.output.catalog_deflate};
  }
  void set(SceneValues& v, std::pair<CatalogFormat, bool> x) const {
    v.output.catalog = x.first;
    v.output.catalog_deflate = x.second;
  }
};

template <class A>
using value_t =
    std::decay_t<decltype(std::declval<const A&>().get(std::declval<const SceneValues&>()))>;

// A row under construction: the fields every row has, then what it needs (`when`), whether
// it is newer than the first hashed scenes (`later`) and kept for validate() (`kept`).
class Row {
 public:
  Row(Key key, ParamType type, const char* def, const char* units, const char* doc) {
    p_.key = key.name;
    p_.type = type;
    p_.default_value = def;
    p_.units = units;
    p_.doc = doc;
  }
  template <class... R>
  Row when(R... rules) && {
    (p_.applies_when.push_back(std::move(rules)), ...);
    return std::move(*this);
  }
  Row later() && {
    p_.added_later = true;
    return std::move(*this);
  }
  Row kept() && {
    p_.kept_when_inapplicable = true;
    return std::move(*this);
  }
  operator ParamSpec() && { return std::move(p_); }  // NOLINT(google-explicit-constructor)
  ParamSpec& spec() { return p_; }

 private:
  ParamSpec p_;
};

// Range brackets: '[' or ']' is inclusive, '(' or ')' exclusive; an infinite bound is
// always written open, so `inf` itself is never an accepted value. The member is a double,
// or a std::optional<double> when the word `keyword` (auto, none) is accepted too.
template <class A>
Row ranged(Key key, A a, const char* def, char lo_br, double lo, double hi, char hi_br,
           const char* units, const char* doc, const char* keyword) {
  Row row(key, ParamType::Real, def, units, doc);
  ParamSpec& p = row.spec();
  p.min = lo;
  p.max = hi;
  p.has_min = std::isfinite(lo);
  p.has_max = std::isfinite(hi);
  p.min_open = lo_br == '(' || !p.has_min;
  p.max_open = hi_br == ')' || !p.has_max;
  if constexpr (std::is_same_v<value_t<A>, std::optional<double>>) {
    p.allow_auto = true;
    p.keyword = keyword;
    p.fill = [a, kw = p.keyword](SceneValues& v, const std::string& t) {
      a.set(v, t == kw ? std::nullopt : std::optional<double>(std::strtod(t.c_str(), nullptr)));
    };
    p.text_of = [a, kw = p.keyword](const SceneValues& v) {
      const std::optional<double> x = a.get(v);
      return x ? format_real(*x) : kw;
    };
  } else {
    p.fill = [a](SceneValues& v, const std::string& t) {
      a.set(v, std::strtod(t.c_str(), nullptr));
    };
    p.text_of = [a](const SceneValues& v) { return format_real(a.get(v)); };
  }
  return row;
}

template <class A>
Row real(Key key, A a, const char* def, char lo_br, double lo, double hi, char hi_br,
         const char* units, const char* doc) {
  return ranged(key, a, def, lo_br, lo, hi, hi_br, units, doc, "auto");
}

template <class A>
Row integer(Key key, A a, const char* def, double lo, double hi, const char* units,
            const char* doc) {
  Row row(key, ParamType::Integer, def, units, doc);
  ParamSpec& p = row.spec();
  p.min = lo;
  p.max = hi;
  p.has_min = p.has_max = true;
  p.fill = [a](SceneValues& v, const std::string& t) {
    a.set(v, static_cast<value_t<A>>(std::stoll(t)));
  };
  p.text_of = [a](const SceneValues& v) {
    return std::to_string(static_cast<std::int64_t>(a.get(v)));
  };
  return row;
}

// The member holds one value per keyword; `options` pairs them, in the order the allowed
// values are listed.
template <class A>
Row choice(Key key, const char* def, A a, std::vector<std::pair<std::string, value_t<A>>> options,
           const char* doc) {
  Row row(key, ParamType::Choice, def, "", doc);
  ParamSpec& p = row.spec();
  for (const auto& o : options) p.choices.push_back(o.first);
  p.fill = [a, options, name = p.key](SceneValues& v, const std::string& t) {
    for (const auto& o : options)
      if (o.first == t) return a.set(v, o.second);
    throw std::logic_error("scene: " + name + " has no choice '" + t + "'");
  };
  p.text_of = [a, options, name = p.key](const SceneValues& v) {
    const value_t<A> x = a.get(v);
    for (const auto& o : options)
      if (o.second == x) return o.first;
    throw std::logic_error("scene: " + name + " holds a value no choice names");
  };
  return row;
}

template <class A>
Row boolean(Key key, A a, const char* def, const char* doc) {
  Row row(key, ParamType::Boolean, def, "", doc);
  ParamSpec& p = row.spec();
  p.fill = [a](SceneValues& v, const std::string& t) { a.set(v, t == "true"); };
  p.text_of = [a](const SceneValues& v) { return std::string(a.get(v) ? "true" : "false"); };
  return row;
}

template <class A>
Row path(Key key, A a, const char* doc) {
  Row row(key, ParamType::Path, "", "", doc);
  ParamSpec& p = row.spec();
  p.fill = [a](SceneValues& v, const std::string& t) { a.set(v, t); };
  p.text_of = [a](const SceneValues& v) { return a.get(v); };
  return row;
}

// A Real key whose default `auto` is chosen for you, on [-limit, limit].
template <class A>
Row auto_real(Key key, A a, double limit, const char* units, const char* doc) {
  return real(key, a, "auto", '[', -limit, limit, ']', units, doc);
}

// The same on (0, limit] (a state variable, a time).
template <class A>
Row positive_or_auto(Key key, A a, double limit, const char* units, const char* doc) {
  return real(key, a, "auto", '(', 0, limit, ']', units, doc);
}

// The same on [0, limit] (a stiffness).
template <class A>
Row auto_stiffness(Key key, A a, double limit, const char* doc) {
  return real(key, a, "auto", '[', 0, limit, ']', "", doc);
}

// A Real key whose default `none` turns its output off.
template <class A>
Row none_real(Key key, A a, double limit, const char* units, const char* doc) {
  return ranged(key, a, "none", '[', -limit, limit, ']', units, doc, "none");
}

// The keywords of the choice keys whose values are not a fixed list.
std::vector<std::pair<std::string, Boundary>> boundaries() {
  return {{"free", Boundary::Free}, {"periodic", Boundary::Periodic}};
}

// friction.law: the rate-only laws of model/law_list.hpp and rsf, the law with state on its
// own path (model/laws/rsf.hpp).
std::vector<std::pair<std::string, LawChoice>> law_options() {
  std::vector<std::pair<std::string, LawChoice>> o;
  for (const std::string& name : law_names()) o.push_back({name, {false, *law_named(name)}});
  o.push_back({"rsf", {true, {}}});
  return o;
}

// integrator.scheme: the registry's keywords (integrate/registry.cpp), read whenever a scene
// is read or validated, so that a scheme registered at run time is a choice as the shipped
// ones are; the reference docs list the shipped ones.
Row scheme_choice(const char* def, const char* doc) {
  const auto a = at(&SceneValues::integrator, &IntegratorSettings::scheme);
  Row row(key::integrator_scheme, ParamType::Choice, def, "", doc);
  ParamSpec& p = row.spec();
  p.choices = shipped_scheme_keywords();
  p.choices_now = [] { return stepper_keywords(); };
  p.fill = [a](SceneValues& v, const std::string& t) { a.set(v, t); };
  p.text_of = [a](const SceneValues& v) { return a.get(v); };
  return row;
}

// The schemes of `keywords` whose traits let integrator.transitions = located wrap them.
std::vector<std::string> locatable(const std::vector<std::string>& keywords) {
  std::vector<std::string> out;
  for (const std::string& k : keywords)
    if (scheme_supports_located(k)) out.push_back(k);
  return out;
}

// "rk2, rk4, verlet": the shipped locatable schemes, for integrator.transitions' doc.
std::string shipped_locatable_text() {
  std::string t;
  for (const std::string& k : locatable(shipped_scheme_keywords()))
    t += (t.empty() ? "" : ", ") + k;
  return t;
}

// The named keys of `s` through their rows (a rule reads the keys it joins as enums).
template <class... K>
SceneValues read(const Scene& s, K... keys) {
  SceneValues v;
  (find_param(keys)->fill(v, s.text(keys)), ...);
  return v;
}

// ---------------------------------------------------------------------------------------
// When a key applies. A rule holds when its controller holds one of the listed values (the
// values are checked against the controller's row when the table is built).

Requirement needs(Key controller, std::vector<std::string> values) {
  Requirement r;
  r.any_of.push_back({controller.name, std::move(values), {}});
  return r;
}

Requirement either(Requirement a, const Requirement& b) {
  a.any_of.insert(a.any_of.end(), b.any_of.begin(), b.any_of.end());
  return a;
}

Requirement thesis_units() {
  return needs(key::model_parameterisation, {"thesis"});
}
Requirement carlson_langer_units() {
  return needs(key::model_parameterisation, {"carlson-langer"});
}
Requirement si_units() {
  return needs(key::model_parameterisation, {"si"});
}
Requirement chain_kinds() {
  return needs(key::model_kind, {"bk", "bkp", "1dof"});
}
// The pad (bkp) and the single block (1dof) have dampers; the plain chain has none.
Requirement with_dampers() {
  return needs(key::model_kind, {"bkp", "1dof"});
}
// Block scalings of Table 3.1; in carlson-langer units they only scale the pad.
Requirement scaled_blocks() {
  return either(thesis_units(), needs(key::model_kind, {"bkp"}));
}
// The automaton has a threshold and a share alpha, no masses, friction or time steps.
Requirement automaton() {
  return needs(key::model_kind, {"ofc"});
}
Requirement range_kernel() {
  return needs(key::model_coupling, {"range", "power"});
}
Requirement power_kernel() {
  return needs(key::model_coupling, {"power"});
}
Requirement inertial() {
  return needs(key::model_dynamics, {"inertial"});
}
Requirement rate_law() {
  return needs(key::friction_law, law_names());
}
Requirement table_law() {
  return needs(key::friction_law, {"table"});
}
// Rate-and-state friction runs in SI units on its own integrator (engine/rsf_cycle.hpp).
Requirement rsf_law() {
  return needs(key::friction_law, {"rsf"});
}
Requirement continuous() {
  return needs(key::drive_mode, {"continuous"});
}
Requirement event_driven() {
  return needs(key::drive_mode, {"events"});
}
Requirement steps_schedule() {
  return needs(key::drive_schedule, {"steps"});
}
Requirement ramp_schedule() {
  return needs(key::drive_schedule, {"ramp"});
}
Requirement equilibrium_start() {
  return needs(key::run_start, {"equilibrium"});
}
Requirement theta_scheme() {
  return needs(key::integrator_scheme, {"theta"});
}
Requirement adaptive_or_rsf() {
  return either(needs(key::integrator_scheme, {"adaptive"}), rsf_law());
}
// Read from the registry's traits each time it is checked (a scheme registered at run time
// that declares itself locatable takes located transitions).
Requirement located_scheme() {
  Requirement r = needs(key::integrator_scheme, {});
  r.any_of.front().values_now = [] { return locatable(stepper_keywords()); };
  return r;
}
Requirement energy_on() {
  return needs(key::output_energy, {"true"});
}

// The lattice's rules: not a controller's values but a count.
bool lattice_or_ofc(const Scene& s) {
  const SceneValues v = read(s, key::model_kind, key::model_rows);
  return v.model.kind == ModelChoice::Ofc ||
         (v.model.kind != ModelChoice::OneDof && v.model.rows > 1);
}

std::string lattice_refusal(const Scene& s, const std::string& key) {
  return key + " = " + s.text(key) + " applies only to a lattice (model.rows > 1), but " +
         "model.rows = " + s.text(key::model_rows);
}

// model.blocks: 1dof runs one block (given as 1 it is accepted).
Requirement one_block() {
  Requirement r;
  r.holds = [](const Scene& s) {
    const SceneValues v = read(s, key::model_kind, key::model_blocks);
    return v.model.kind != ModelChoice::OneDof || v.model.blocks == 1;
  };
  r.why_not = [](const Scene&) { return std::string("model.kind = 1dof has one block"); };
  r.refusal = [](const Scene& s, const std::string&) {
    return "model.blocks = " + s.text(key::model_blocks) +
           " contradicts model.kind = 1dof (a single block); remove model.blocks or set it to 1";
  };
  return r;
}

// model.rows: a chain is one row; given as 1 it is accepted (and left out of a chain's
// scene.ini), more make a lattice of bk or bkp; 1dof refuses more. The automaton always
// has rows.
Requirement rows_of_kind() {
  Requirement r;
  r.holds = lattice_or_ofc;
  r.why_not = [](const Scene& s) {
    return std::string(read(s, key::model_kind).model.kind == ModelChoice::OneDof
                           ? "model.kind = 1dof has one block"
                           : "one row is the chain (more make a lattice)");
  };
  r.refusal = [](const Scene& s, const std::string&) {
    if (read(s, key::model_rows).model.rows == 1) return std::string();
    return "model.rows = " + s.text(key::model_rows) +
           " with model.kind = 1dof: one block has one row; allowed: model.rows = 1, or "
           "model.kind = bk, bkp or ofc";
  };
  return r;
}

// The edges across strike mean something on a lattice, and for the automaton always.
Requirement lattice_or_automaton() {
  Requirement r;
  r.holds = lattice_or_ofc;
  r.why_not = [](const Scene& s) {
    return "needs model.rows > 1 or model.kind = ofc, but model.rows = " + s.text(key::model_rows) +
           " and model.kind = " + s.text(key::model_kind);
  };
  r.refusal = lattice_refusal;
  return r;
}

// The across-strike stiffness keys: a lattice only (model.rows > 1).
Requirement lattice_only() {
  Requirement r;
  r.holds = [](const Scene& s) { return read(s, key::model_rows).model.rows > 1; };
  r.why_not = [](const Scene& s) {
    return "needs model.rows > 1, but model.rows = " + s.text(key::model_rows);
  };
  r.refusal = lattice_refusal;
  return r;
}

// ---------------------------------------------------------------------------------------
// model: which chain, in which units (Ferre 2018 eq. 3.1; Carlson & Langer 1989 eq. 2.2)

// Its kind, units, size, edges and coupling.
std::vector<ParamSpec> model_rows() {
  return {
      choice(key::model_kind, "bk", at(&SceneValues::model, &ModelKeys::kind),
             {{"bk", ModelChoice::Bk},
              {"bkp", ModelChoice::Bkp},
              {"1dof", ModelChoice::OneDof},
              {"ofc", ModelChoice::Ofc}},
             "bk: plain Burridge-Knopoff chain, pad fixed; bkp: BK-Pad, the pad moves; "
             "1dof: one block with spring and damper (thesis eq. 2.11); ofc: the "
             "Olami-Feder-Christensen automaton on model.blocks x model.rows sites (1992)"),
      choice(
          key::model_parameterisation, "carlson-langer", at(&SceneValues::model, &ModelKeys::units),
          {{"carlson-langer", Units::CarlsonLanger}, {"thesis", Units::Thesis}, {"si", Units::Si}},
          "carlson-langer: dimensionless units of eq. 2.2 (m_u = k_p = F0 = 1); "
          "thesis: Table 3.1 scalings; si: SI units per unit fault area (friction.law = rsf)")
          .when(chain_kinds()),
      integer(key::model_blocks, at(&SceneValues::model, &ModelKeys::blocks), "100", 1, 1e7, "",
              "number of blocks N")
          .when(one_block())
          .kept(),
      choice(key::model_boundary, "free", at(&SceneValues::model, &ModelKeys::boundary),
             boundaries(),
             "chain ends: free (missing neighbour, no spring) or periodic (a ring); for ofc the "
             "lattice's edges along strike: free is OFC's open edge (stress pushed over it is "
             "lost)"),
      integer(key::model_rows, at(&SceneValues::model, &ModelKeys::rows), "1", 1, 1e7, "",
              "rows across strike: the lattice is model.blocks x model.rows (bk, bkp, ofc; "
              "1 is the chain; 1dof runs one block)")
          .when(rows_of_kind())
          .later()
          .kept(),
      choice(key::model_boundary_y, "free", at(&SceneValues::model, &ModelKeys::boundary_y),
             boundaries(),
             "lattice edges across strike (model.rows > 1, or ofc): free has no spring past "
             "the edge (for ofc the open edge: stress pushed over it is lost), periodic wraps "
             "row model.rows - 1 to row 0")
          .when(lattice_or_automaton())
          .later(),
      choice(
          key::model_coupling, "nearest", at(&SceneValues::model, &ModelKeys::coupling),
          {{"nearest", Coupling::Nearest}, {"range", Coupling::Range}, {"power", Coupling::Power}},
          "block-to-block springs: nearest (k_c to each neighbour), range (k_c/R to every "
          "block within R = model.range on each side; Xia, Gould, Klein & Rundle 2005) or "
          "power (k_c r^-p / sum_{s<=R} s^-p at distance r <= R, p = "
          "model.coupling_exponent); every choice sums to k_c per side")
          .when(chain_kinds())  // every law, rate-and-state included
          .later(),
      integer(key::model_range, at(&SceneValues::model, &ModelKeys::range), "1", 1, 1e6, "",
              "R: blocks coupled on each side (model.coupling = range or power); R = 1 is the "
              "nearest-neighbour chain; a free chain needs R < N, a periodic one 2R < N")
          .when(range_kernel(), chain_kinds())
          .later(),
      real(key::model_coupling_exponent, at(&SceneValues::model, &ModelKeys::coupling_exponent),
           "3", '[', 0, 100, ']', "",
           "p of the power kernel's springs r^-p (model.coupling = power; 3 is the elastic "
           "kernel's 1/r^3)")
          .when(power_kernel(), chain_kinds())
          .later(),
      real(key::model_viscosity, at(&SceneValues::model, &ModelKeys::viscosity), "0", '[', 0, kHuge,
           ']', "force time/length",
           "viscous coupling eta (Myers & Langer 1993): dashpots beside the coupling's springs, "
           "eta (w'_{j-1} - 2 w'_j + w'_{j+1}) for nearest neighbours, shaped as the stencil "
           "with sum eta for range and power; event and continuous runs (rk2, rk4, verlet)")
          .when(rate_law(), chain_kinds())
          .later(),
  };
}

// The chain's springs, masses and dampers in either unit system.
std::vector<ParamSpec> stiffness_rows() {
  return {
      real(key::model_l, at(&SceneValues::model, &ModelKeys::l), "10", '[', 0, 1e4, ']', "",
           "stiffness ratio l, neighbour spring k_c = l^2 (carlson-langer only); on a lattice "
           "the spring along strike")
          .when(carlson_langer_units(), chain_kinds()),
      auto_stiffness(key::model_l_y, at(&SceneValues::model, &ModelKeys::l_y), 1e4,
                     "lattice (model.rows > 1): stiffness ratio across strike, k_c_y = l_y^2 "
                     "(carlson-langer only); auto: equal to model.l")
          .when(carlson_langer_units(), chain_kinds(), lattice_only())
          .later(),
      real(key::model_pad_mass, at(&SceneValues::model, &ModelKeys::pad_mass), "100", '(', 0, kHuge,
           ']', "mass", "pad mass m_x (thesis only)")
          .when(thesis_units(), chain_kinds()),
      real(key::model_caliper_stiffness, at(&SceneValues::model, &ModelKeys::caliper_stiffness),
           "100", '[', 0, kHuge, ']', "force/length", "caliper-pad spring k_p0 (thesis only)")
          .when(thesis_units(), chain_kinds()),
      real(key::model_damping_ratio, at(&SceneValues::model, &ModelKeys::damping_ratio),
           "0.0833333333333333", '[', 0, 1e3, ']', "",
           "damping ratio zeta: pad damper for bkp, block damper for 1dof")
          .when(with_dampers(), rate_law(), chain_kinds()),
      real(key::model_s_m, at(&SceneValues::model, &ModelKeys::s_m), "1", '(', 0, 1e6, ']', "",
           "mass scaling s_m: m_u = s_m m_x / N")
          .when(scaled_blocks(), chain_kinds()),
      real(key::model_s_p, at(&SceneValues::model, &ModelKeys::s_p), "1", '(', 0, 1e6, ']', "",
           "pulling-spring scaling s_p: k_p = s_p k_p0 / N")
          .when(scaled_blocks(), chain_kinds()),
      real(key::model_s_c, at(&SceneValues::model, &ModelKeys::s_c), "0.01", '[', 0, 1e6, ']', "",
           "coupling scaling s_c: k_c = s_c k_p0 N (thesis only); on a lattice k_c = s_c k_p0 "
           "model.blocks along strike")
          .when(thesis_units(), chain_kinds()),
      auto_stiffness(key::model_s_c_y, at(&SceneValues::model, &ModelKeys::s_c_y), 1e6,
                     "lattice (model.rows > 1): coupling scaling across strike, k_c_y = s_c_y k_p0 "
                     "model.rows (thesis only); auto: equal to model.s_c")
          .when(thesis_units(), chain_kinds(), lattice_only())
          .later(),
      real(key::model_rayleigh_alpha, at(&SceneValues::model, &ModelKeys::rayleigh_alpha), "0", '[',
           0, kHuge, ']', "1/time",
           "Rayleigh damping alpha_M M + beta_K K of blocks and pad (K with k_c, k_p and the pad "
           "row; continuous runs and bkquake stability, event runs refuse it): alpha_M")
          .when(rate_law(), chain_kinds()),
      real(key::model_rayleigh_beta, at(&SceneValues::model, &ModelKeys::rayleigh_beta), "0", '[',
           0, kHuge, ']', "time", "Rayleigh damping alpha_M M + beta_K K: beta_K")
          .when(rate_law(), chain_kinds()),
  };
}

// A spring reaching past a free end, or two offsets of a ring reaching the same block,
// would not be the coupling the key describes. `across`: the lattice's rows, else along strike.
void check_range(const Scene& s, bool across, const std::string& where) {
  const SceneValues v = scene_values(s);
  const std::int64_t r = v.model.range, n = across ? v.model.rows : v.model.blocks;
  const bool ring = (across ? v.model.boundary_y : v.model.boundary) == Boundary::Periodic;
  if (ring ? 2 * r < n : r < n) return;
  const std::string count = across ? "model.rows" : "model.blocks";
  const Key boundary = across ? key::model_boundary_y : key::model_boundary;
  throw Error("model.range = " + s.text(key::model_range) + " with " + count + " = " +
              s.text(count) + " and " + std::string(boundary) + " = " + s.text(boundary) +
              ": allowed " +
              (ring ? "2 model.range < " + count + " (a ring)" : "model.range < " + count) + where);
}

void periodic_chain_length(const Scene& s, const std::string& where) {
  const SceneValues v = read(s, key::model_boundary, key::model_blocks);
  if (v.model.boundary == Boundary::Periodic && v.model.blocks < 3)
    throw Error("model.boundary = periodic needs model.blocks >= 3, got model.blocks = " +
                s.text(key::model_blocks) + where);
}

// The BK lattice (Carlson 1991): what its engine and its forces are written for.
void chain_lattice(const Scene& s, const std::string& where) {
  const SceneValues v = scene_values(s);
  if (v.model.kind == ModelChoice::Ofc || v.model.rows <= 1) return;
  const std::int64_t nx = v.model.blocks, ny = v.model.rows;
  if (nx * ny > 10'000'000)
    throw Error("model.blocks x model.rows = " + s.text(key::model_blocks) + " x " +
                s.text(key::model_rows) + ": allowed at most 1e7 blocks for a bk or bkp lattice" +
                where);
  if (v.model.boundary_y == Boundary::Periodic && ny < 3)
    throw Error("model.boundary_y = periodic needs model.rows >= 3, got model.rows = " +
                s.text(key::model_rows) + where);
  if (v.model.viscosity != 0)
    throw Error("model.viscosity = " + s.text(key::model_viscosity) +
                " with model.rows = " + s.text(key::model_rows) +
                ": the viscous coupling is written for chains; allowed on a lattice: "
                "model.viscosity = 0" +
                where);
  if (v.drive.mode == DriveMode::Continuous && v.run.start.equilibrium)
    throw Error("run.start = equilibrium with model.rows = " + s.text(key::model_rows) +
                ": steady sliding is solved for chains; allowed on a lattice: run.start = "
                "disorder" +
                where);
  if (!s.applies(key::model_range)) return;
  // A lattice's range couples a disc of radius R: per axis as for a chain (a lattice of one
  // column is the chain along y).
  if (nx > 1) check_range(s, false, where);
  if (ny > 1) check_range(s, true, where);
}

void chain_range(const Scene& s, const std::string& where) {
  if (s.applies(key::model_range) && read(s, key::model_rows).model.rows == 1)
    check_range(s, false, where);
}

// The springs of a wide stencil one evaluation of every block's force sums: the engine's
// construction (its tree of times to failure), a resume's, and each step of an event that
// spans the chain cost that many terms. A chain's block has 2R partners; a lattice's site
// those of the disc 0 < dx^2 + dy^2 <= R^2 (model/coupling.hpp), at most N - 1 along an axis.
// Above this bound (seconds per evaluation; the largest nearest-neighbour lattice costs
// 10^7 sites x 4 springs) a run would sit for minutes to hours before its first event:
// refused in one line naming the cost. Every shipped scene and study is below it by orders
// of magnitude.
constexpr double kMaxStencilTerms = 1e8;

void stencil_cost(const Scene& s, const std::string& where) {
  if (!s.applies(key::model_range)) return;
  const SceneValues v = read(s, key::model_range, key::model_blocks, key::model_rows);
  const std::int64_t r = v.model.range, nx = v.model.blocks, ny = v.model.rows;
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
  const std::string blocks = ny == 1 ? "model.blocks = " + s.text(key::model_blocks)
                                     : "model.blocks x model.rows = " + s.text(key::model_blocks) +
                                           " x " + s.text(key::model_rows);
  throw Error("model.range = " + s.text(key::model_range) + " with " + blocks + ": every force " +
              "evaluation sums " + short_number(terms, 3) + " springs (" + per +
              "), which would take minutes to hours before the first event; allowed: " +
              "at most " + short_number(kMaxStencilTerms, 3) +
              " (blocks x springs per block): a smaller model.range or fewer blocks" + where);
}

// si parameterisation (rate-and-state friction): per unit fault area.
std::vector<ParamSpec> si_model_rows() {
  return {
      real(key::model_stiffness, at(&SceneValues::model, &ModelKeys::stiffness), "2e9", '(', 0,
           kHuge, ']', "Pa/m",
           "loading spring k per unit area between block and plate (si; QDYN's spring-block: "
           "G/L)")
          .when(si_units())
          .later(),
      real(key::model_coupling_stiffness, at(&SceneValues::model, &ModelKeys::coupling_stiffness),
           "0", '[', 0, kHuge, ']', "Pa/m",
           "nearest-neighbour spring k_c per unit area between blocks (si); on a lattice the "
           "spring along strike")
          .when(si_units())
          .later(),
      real(key::model_coupling_stiffness_y,
           at(&SceneValues::model, &ModelKeys::coupling_stiffness_y), "auto", '[', 0, kHuge, ']',
           "Pa/m",
           "lattice (model.rows > 1): spring k_c_y per unit area across strike (si; a column, "
           "model.blocks = 1, is coupled by it alone); auto: equal to model.coupling_stiffness")
          .when(si_units(), lattice_only())
          .later(),
      choice(key::model_dynamics, "quasi-dynamic", at(&SceneValues::model, &ModelKeys::dynamics),
             {{"quasi-dynamic", RsfDynamics::QuasiDynamic}, {"inertial", RsfDynamics::Inertial}},
             "quasi-dynamic: elastic stress minus radiation damping eta V balances friction "
             "(Rice 1993); inertial: model.mass_per_area accelerates the block (si)")
          .when(si_units())
          .later(),
      real(key::model_shear_modulus, at(&SceneValues::model, &ModelKeys::shear_modulus), "2e10",
           '(', 0, kHuge, ']', "Pa",
           "shear modulus G of the radiation damping eta = G/(2 c_s) (si)")
          .when(si_units())
          .later(),
      real(key::model_shear_wave_speed, at(&SceneValues::model, &ModelKeys::shear_wave_speed),
           "3000", '[', 0, kHuge, ']', "m/s",
           "shear-wave speed c_s of the radiation damping eta = G/(2 c_s); 0: no radiation "
           "damping (si)")
          .when(si_units())
          .later(),
      real(key::model_mass_per_area, at(&SceneValues::model, &ModelKeys::mass_per_area), "1e6", '(',
           0, kHuge, ']', "kg/m^2", "block mass per unit fault area m (model.dynamics = inertial)")
          .when(si_units(), inertial())
          .later(),
  };
}

// ---------------------------------------------------------------------------------------
// ofc: the automaton (Olami, Feder & Christensen 1992)

std::vector<ParamSpec> ofc_rows() {
  return {
      real(key::ofc_alpha, at(&SceneValues::ofc, &OfcParams::alpha), "0.2", '(', 0, 0.25, ']', "",
           "share alpha of a toppling site's stress given to each of its z = 4 neighbours "
           "(Olami, Feder & Christensen 1992); 0.25 conserves stress away from free edges")
          .when(automaton())
          .later(),
      choice(key::ofc_order, "generations", at(&SceneValues::ofc, &OfcParams::sequential),
             {{"generations", false}, {"sequential", true}},
             "toppling order: generations (parallel update: every unstable site of a generation "
             "releases what it held at the generation's start) or sequential (one site at a "
             "time, first in first out)")
          .when(automaton())
          .later(),
      real(key::ofc_relaxation_time, at(&SceneValues::ofc, &OfcParams::relaxation_time), "0", '[',
           0, 1e15, ']', "drive",
           "viscoelastic relaxation (after Hainzl, Zoller & Kurths 1999): pending stress flows "
           "into a site as exp(-drive / relaxation_time); 0: off")
          .when(automaton())
          .later(),
      real(key::ofc_relaxation_alpha, at(&SceneValues::ofc, &OfcParams::relaxation_alpha), "0", '[',
           0, 0.25, ']', "",
           "share of a toppling site's stress each neighbour receives as pending stress "
           "(relaxation); ofc.alpha + ofc.relaxation_alpha <= 0.25")
          .when(automaton())
          .later(),
  };
}

// Events only, its catalogue format, its lattice; the relaxation's own limits are the
// engine's (one place states them).
void automaton_lattice(const Scene& s, const std::string& where) {
  const SceneValues v = scene_values(s);
  if (v.model.kind != ModelChoice::Ofc) return;
  if (v.drive.mode != DriveMode::Events)
    throw Error("drive.mode = " + s.text(key::drive_mode) +
                " with model.kind = ofc: the automaton runs event by event only; allowed: "
                "drive.mode = events" +
                where);
  if (std::int64_t{v.model.blocks} * v.model.rows > 100'000'000)
    throw Error("model.blocks x model.rows = " + s.text(key::model_blocks) + " x " +
                s.text(key::model_rows) + ": allowed at most 1e8 sites for ofc" + where);
  const bool px = v.model.boundary == Boundary::Periodic;  // its length is checked above
  const bool py = v.model.boundary_y == Boundary::Periodic;
  if (py && v.model.rows < 3)
    throw Error("model.boundary_y = periodic needs model.rows >= 3, got model.rows = " +
                s.text(key::model_rows) + where);
  if (px && py && v.ofc.alpha == 0.25)
    throw Error(
        "ofc.alpha = 0.25 with model.boundary = periodic and model.boundary_y = periodic: "
        "stress would never leave the lattice and an avalanche would never end; allowed: "
        "ofc.alpha < 0.25, or model.boundary or model.boundary_y = free" +
        where);
  OfcParams p = v.ofc;
  p.nx = v.model.blocks;
  p.ny = v.model.rows;
  p.periodic_x = px;
  p.periodic_y = py;
  try {
    OfcEngine::check(p);
  } catch (const Error& e) {
    throw Error(e.what() + where);
  }
}

// ---------------------------------------------------------------------------------------
// friction: the law phi(y) (Ferre 2018 eq. 3.5; Carlson et al. 1991 eq. 2.9)

std::vector<ParamSpec> friction_rows() {
  return {
      choice(
          key::friction_law, "clst91", at(&SceneValues::friction, &FrictionKeys::law),
          law_options(),
          "thesis (eq. 3.5, backslip allowed), clst91 (Carlson et al. 1991 eq. 2.9, no "
          "backslip), cl89 (Carlson-Langer 1989 eq. 2.3; continuous runs only, event runs refuse "
          "it), none (frictionless, continuous verification runs only), table (tabulated, "
          "friction.table; thesis Fig. 4.8), rsf (Dieterich-Ruina rate-and-state friction, "
          "[rsf]; model.parameterisation = si, drive.mode = continuous)")
          .when(chain_kinds()),
      real(key::friction_F0, at(&SceneValues::friction, &FrictionKeys::F0), "1", '(', 0, kHuge, ']',
           "force/mass", "static threshold per unit block mass F0 (thesis only)")
          .when(thesis_units(), chain_kinds()),
      real(key::friction_sigma, at(&SceneValues::friction, &FrictionKeys::sigma), "0.01", '[', 0, 1,
           ')', "", "drop sigma from static to kinetic friction")
          .when(rate_law(), chain_kinds()),
      real(key::friction_alpha, at(&SceneValues::friction, &FrictionKeys::alpha), "2.5", '[', 0,
           1e6, ']', "", "velocity weakening alpha, v_c = 1/(2 alpha) (carlson-langer only)")
          .when(carlson_langer_units(), chain_kinds()),
      real(key::friction_vc, at(&SceneValues::friction, &FrictionKeys::vc), "1", '(', 0, kHuge, ']',
           "length/time", "characteristic velocity v_c (thesis only)")
          .when(thesis_units(), chain_kinds()),
      path(key::friction_table, at(&SceneValues::friction, &FrictionKeys::table),
           "CSV file of the table law (friction.law = table): columns speed, friction "
           "(docs/reference/scenes.md); relative to the scene file's folder")
          .when(table_law(), chain_kinds()),
  };
}

void table_file(const Scene& s, const std::string& where) {
  const SceneValues v = read(s, key::friction_law, key::friction_table);
  if (!v.friction.law.rsf && v.friction.law.law == law_id<law::Table> && v.friction.table.empty())
    throw Error("friction.table: friction.law = table needs the table's file, got none" + where);
}

// ---------------------------------------------------------------------------------------
// rsf: rate-and-state friction (Dieterich 1979; Ruina 1983), friction.law = rsf

std::vector<ParamSpec> rsf_rows() {
  return {
      real(key::rsf_a, at(&SceneValues::rsf, &RsfKeys::law, &rsf::Params::a), "0.01", '(', 0, 10,
           ']', "", "direct-effect parameter a")
          .when(rsf_law())
          .later(),
      real(key::rsf_b, at(&SceneValues::rsf, &RsfKeys::law, &rsf::Params::b_rsf), "0.025", '[', 0,
           10, ']', "", "rate-and-state b (evolution effect; not the Gutenberg-Richter b)")
          .when(rsf_law())
          .later(),
      real(key::rsf_dc, at(&SceneValues::rsf, &RsfKeys::law, &rsf::Params::dc), "1e-05", '(', 0,
           1e6, ']', "m", "critical slip distance D_c")
          .when(rsf_law())
          .later(),
      real(key::rsf_mu0, at(&SceneValues::rsf, &RsfKeys::law, &rsf::Params::mu0), "0.6", '[', 0, 10,
           ']', "", "reference friction mu* at rsf.v0")
          .when(rsf_law())
          .later(),
      real(key::rsf_v0, at(&SceneValues::rsf, &RsfKeys::law, &rsf::Params::v0), "1e-06", '(', 0,
           1e6, ']', "m/s", "reference slip rate V*")
          .when(rsf_law())
          .later(),
      choice(key::rsf_state_law, "aging", at(&SceneValues::rsf, &RsfKeys::state_law),
             {{"aging", rsf::StateLaw::Aging}, {"slip", rsf::StateLaw::Slip}},
             "state evolution: aging (d theta/dt = 1 - V theta/D_c) or slip (d theta/dt = "
             "-(V theta/D_c) ln(V theta/D_c))")
          .when(rsf_law())
          .later(),
      choice(key::rsf_form, "log", at(&SceneValues::rsf, &RsfKeys::form),
             {{"log", rsf::Form::Log}, {"regularised", rsf::Form::Regularised}},
             "log: mu* + a ln(V/V*) + b ln(V* theta/D_c); regularised: a asinh(V/(2V*) "
             "exp((mu* + b ln(V* theta/D_c))/a)) (Rice & Ben-Zion 1996; Lapusta et al. 2000)")
          .when(rsf_law())
          .later(),
      real(key::rsf_normal_stress, at(&SceneValues::rsf, &RsfKeys::normal_stress), "5e6", '(', 0,
           kHuge, ']', "Pa",
           "effective normal stress sigma (friction.sigma stays Carlson-Langer's drop)")
          .when(rsf_law())
          .later(),
      real(key::rsf_v_threshold, at(&SceneValues::rsf, &RsfKeys::v_threshold), "0.001", '(', 0, 1e6,
           ']', "m/s",
           "seismic slip rate V_th: an event is an interval in which some block slips faster; "
           "must exceed drive.speed (the plate rate)")
          .when(rsf_law())
          .later(),
      real(key::rsf_v_init, at(&SceneValues::rsf, &RsfKeys::v_init), "2e-05", '(', 0, 1e6, ']',
           "m/s", "slip rate of every block at t = 0")
          .when(rsf_law())
          .later(),
      positive_or_auto(key::rsf_theta_init, at(&SceneValues::rsf, &RsfKeys::theta_init), 1e15, "s",
                       "state theta of every block at t = 0; auto: steady state at the plate "
                       "rate, rsf.dc/drive.speed")
          .when(rsf_law())
          .later(),
      path(key::rsf_blocks, at(&SceneValues::rsf, &RsfKeys::blocks),
           "CSV file of per-block a, b and D_c (header block,a,b,dc, one row per block 0..N-1 in "
           "order; docs/explanation/rate-and-state.md); relative to the scene file's folder; "
           "none: every block has rsf.a, rsf.b, rsf.dc")
          .when(rsf_law()),
      real(key::rsf_slow_slip_threshold, at(&SceneValues::rsf, &RsfKeys::slow_slip_threshold), "0",
           '[', 0, 1e6, ']', "m/s",
           "V_slow: slow-slip and afterslip episodes (some block faster than V_slow, none reaching "
           "rsf.v_threshold) are written to slow_slip.csv; between drive.speed and "
           "rsf.v_threshold; 0: off")
          .when(rsf_law())
          .later(),
      positive_or_auto(key::rsf_handover_speed, at(&SceneValues::rsf, &RsfKeys::handover_speed),
                       1e6, "m/s",
                       "V_h of the event-driven engine: below it a block follows its closed form "
                       "between events, and an event is integrated from the first block to reach "
                       "it until every block is below it again; below rsf.v_threshold; auto: "
                       "rsf.v_threshold/10, or less so that eta V_h <= 0.01 a sigma; at most 3 "
                       "drive.speed on a lattice of identical blocks (no rsf.blocks) and with "
                       "rsf.event_integration = active")
          .when(rsf_law(), event_driven())
          .later(),
      positive_or_auto(key::rsf_creep_quantum, at(&SceneValues::rsf, &RsfKeys::creep_quantum), 1,
                       "m",
                       "q of the event-driven engine: between events a block's closed-form slip is "
                       "passed on to its neighbours as stress steps (k_c times it) whenever it "
                       "reaches q, and at every event; smaller is closer to the continuous "
                       "integration and slower; auto: 0.1 a sigma/k_c (the least a, the stiffest "
                       "spring), so that a quantum moves a neighbour's slip rate by at most 10 %")
          .when(rsf_law(), event_driven())
          .later(),
      choice(key::rsf_event_integration, "whole",
             at(&SceneValues::rsf, &RsfKeys::event_integration),
             {{"whole", RsfEventIntegration::Whole},
              {"active", RsfEventIntegration::Active},
              {"groups", RsfEventIntegration::Groups}},
             "how the event-driven engine integrates an event: whole (every block, from the "
             "first to reach rsf.handover_speed until all are below it), active (only the "
             "blocks above it or not yet handed back, each back to its closed form on its own "
             "outside events; needs rsf.blocks and rsf.handover_speed up to 3 drive.speed; "
             "quasi-dynamic "
             "scenes, inertial ones integrate the whole grid) or groups (as active, with groups "
             "of active blocks that share no spring integrated apart, each at its own step size)")
          .when(rsf_law(), event_driven())
          .later(),
      real(key::rsf_alone_speed, at(&SceneValues::rsf, &RsfKeys::alone_speed), "auto", '[', 0, 1e6,
           ']', "m/s",
           "V_a of the active-block integration: a velocity-weakening block that neither "
           "nucleates (V theta/D_c >= 10) nor is locked below 3 drive.speed is integrated on its "
           "own between events (its full aging law; its neighbours' creep in quanta) up to V_a, "
           "where it joins the event's active blocks, and goes back below V_a/3; between "
           "drive.speed and rsf.v_threshold; auto: 100 drive.speed, at most rsf.v_threshold/10 "
           "and eta V_a <= 0.01 a sigma (off where that is not above drive.speed); 0: off (such "
           "blocks are integrated with the active blocks); rsf.event_integration = active or "
           "groups only")
          .when(rsf_law(), event_driven())
          .later(),
      real(key::rsf_alone_tolerance, at(&SceneValues::rsf, &RsfKeys::alone_tolerance), "auto", '[',
           1e-14, 1e-2, ']', "",
           "local error tolerance of the blocks integrated alone (as integrator.tolerance, per "
           "Dormand-Prince 5(4) step); auto: 1e-6, or integrator.tolerance where that is larger "
           "(their error then stays far below the creep quantum's, k q / (2 a sigma) in ln V); "
           "rsf.event_integration = active or groups only")
          .when(rsf_law(), event_driven())
          .later(),
      choice(key::rsf_pattern, "uniform", at(&SceneValues::rsf, &RsfKeys::pattern),
             {{"uniform", RsfPattern::Uniform}, {"asperities", RsfPattern::Asperities}},
             "per-block values: uniform (rsf.a, rsf.b everywhere), or asperities: blocks with x "
             "mod rsf.pattern_period < rsf.pattern_width (and the same across strike on a lattice) "
             "keep rsf.a and rsf.b, the others are barriers with a and b swapped")
          .when(rsf_law())
          .later(),
      integer(key::rsf_pattern_period, at(&SceneValues::rsf, &RsfKeys::pattern_period), "10", 2,
              1e7, "", "blocks from one asperity to the next")
          .when(needs(key::rsf_pattern, {"asperities"}))
          .later(),
      integer(key::rsf_pattern_width, at(&SceneValues::rsf, &RsfKeys::pattern_width), "5", 1, 1e7,
              "", "blocks of each asperity; below rsf.pattern_period")
          .when(needs(key::rsf_pattern, {"asperities"}))
          .later(),
  };
}

// A rate-and-state scene (friction.law = rsf, model.parameterisation = si): the two go
// together, continuous drive, a chain or one block, V_th above the plate rate.
void rate_and_state(const Scene& s, const std::string& where) {
  const SceneValues v = scene_values(s);
  const bool active = v.rsf.event_integration != RsfEventIntegration::Whole;
  if (!v.friction.law.rsf && v.model.units != Units::Si) return;
  if (!v.friction.law.rsf)
    throw Error("model.parameterisation = si is for friction.law = rsf, but friction.law = " +
                s.text(key::friction_law) +
                "; allowed: friction.law = rsf, or model.parameterisation = carlson-langer " +
                "or thesis" + where);
  if (v.model.units != Units::Si)
    throw Error("friction.law = rsf runs in SI units, but model.parameterisation = " +
                s.text(key::model_parameterisation) + "; allowed: model.parameterisation = si" +
                where);
  // The event-driven engine's closed forms are the aging law's, in the quasi-static balance.
  if (v.drive.mode == DriveMode::Events && v.rsf.state_law != rsf::StateLaw::Aging)
    throw Error("rsf.state_law = " + s.text(key::rsf_state_law) +
                " with drive.mode = events: the event-driven engine's closed form between events "
                "is the aging law's; allowed: rsf.state_law = aging, or drive.mode = continuous" +
                where);
  // Measured: on lattices of identical blocks, and with each event integrated on its active
  // blocks, the event-driven catalogue is the continuous one handing over at 3 V_pl, not at the
  // auto V_h; a lattice with per-block values (rsf.blocks) runs the same at either
  // (validation page "Event-driven against continuous rate-and-state").
  const bool identical_lattice = v.model.rows > 1 && v.rsf.blocks.empty();
  const bool slow_handover = identical_lattice || active;
  if (v.drive.mode == DriveMode::Events && slow_handover &&
      !(v.rsf.handover_speed && *v.rsf.handover_speed <= 3 * v.drive.speed * (1 + 1e-12))) {
    const std::string vh =
        v.rsf.handover_speed ? s.text(key::rsf_handover_speed) : std::string("auto");
    if (identical_lattice)
      throw Error(
          "rsf.handover_speed = " + vh +
          " with drive.mode = events on a lattice (model.rows = " + s.text(key::model_rows) +
          ") of identical blocks: there the event-driven engine reproduces the "
          "continuous integration's events handing over at up to 3 drive.speed only; "
          "allowed: rsf.handover_speed up to 3 drive.speed, per-block values from "
          "rsf.blocks, or drive.mode = continuous" +
          where);
    throw Error("rsf.handover_speed = " + vh +
                " with rsf.event_integration = " + s.text(key::rsf_event_integration) +
                ": events integrated on their active blocks "
                "reproduce the continuous integration's handing over at up to 3 drive.speed "
                "only; allowed: rsf.handover_speed up to 3 drive.speed, or "
                "rsf.event_integration = whole" +
                where);
  }
  // Measured: identical blocks (a pattern, no per-block file) stay in step in the continuous
  // integration, equivalent asperities failing together; the active-block integration falls out
  // of step at once (validation page, "Rough scenes: blocks out of step").
  if (v.drive.mode == DriveMode::Events && active && v.rsf.blocks.empty())
    throw Error("rsf.event_integration = " + s.text(key::rsf_event_integration) +
                " with rsf.pattern = " + s.text(key::rsf_pattern) +
                " and no rsf.blocks: on identical blocks the continuous integration keeps "
                "equivalent blocks in step, which the active-block integration does not follow; "
                "allowed: per-block values from rsf.blocks (e.g. a rough D_c from "
                "analysis/make_rough_blocks.py), or rsf.event_integration = whole" +
                where);
  if (v.drive.mode == DriveMode::Events && v.rsf.alone_speed && *v.rsf.alone_speed != 0) {
    if (!active)
      throw Error("rsf.alone_speed = " + s.text(key::rsf_alone_speed) +
                  " with rsf.event_integration = whole: blocks are integrated alone between "
                  "events only when each event is integrated on its active blocks; allowed: "
                  "rsf.event_integration = active or groups, or rsf.alone_speed = auto or 0" +
                  where);
    if (!(*v.rsf.alone_speed<v.rsf.v_threshold&& * v.rsf.alone_speed> v.drive.speed))
      throw Error("rsf.alone_speed = " + s.text(key::rsf_alone_speed) +
                  ": the speed up to which a block is integrated alone lies between the plate "
                  "rate and the seismic rate; allowed: 0 (off), auto or (" +
                  s.text(key::drive_speed) + ", " + s.text(key::rsf_v_threshold) + ")" + where);
  }
  if (v.drive.mode == DriveMode::Events && v.rsf.alone_tolerance && !active)
    throw Error("rsf.alone_tolerance = " + s.text(key::rsf_alone_tolerance) +
                " with rsf.event_integration = whole: no block is integrated alone; allowed: "
                "rsf.event_integration = active or groups, or rsf.alone_tolerance = auto" +
                where);
  if (v.drive.mode == DriveMode::Events && v.rsf.handover_speed &&
      !(*v.rsf.handover_speed<v.rsf.v_threshold&& * v.rsf.handover_speed> v.drive.speed))
    throw Error("rsf.handover_speed = " + s.text(key::rsf_handover_speed) +
                ": the hand-over speed lies between the plate rate and the seismic rate; allowed: "
                "auto or (" +
                s.text(key::drive_speed) + ", " + s.text(key::rsf_v_threshold) + ")" + where);
  if (v.model.kind != ModelChoice::Bk && v.model.kind != ModelChoice::OneDof)
    throw Error("model.kind = " + s.text(key::model_kind) +
                " with friction.law = rsf: allowed model.kind = bk or 1dof" + where);
  if (v.drive.schedule != Schedule::Constant)
    throw Error("drive.schedule = " + s.text(key::drive_schedule) +
                " with friction.law = rsf: the plate moves at a constant rate; allowed: "
                "drive.schedule = constant" +
                where);
  if (!(v.drive.speed > 0))
    throw Error("drive.speed = " + s.text(key::drive_speed) +
                " with friction.law = rsf: the plate rate must be positive (m/s)" + where);
  if (!(v.rsf.v_threshold > v.drive.speed))
    throw Error("rsf.v_threshold = " + s.text(key::rsf_v_threshold) +
                ": the seismic slip rate must exceed the plate rate drive.speed = " +
                s.text(key::drive_speed) + "; allowed: (" + s.text(key::drive_speed) + ", 1e6]" +
                where);
  // Slow slip lies between the plate rate and V_th; per-block values from a pattern or a file.
  const double v_slow = v.rsf.slow_slip_threshold;
  if (v_slow != 0 && !(v_slow > v.drive.speed && v_slow < v.rsf.v_threshold))
    throw Error("rsf.slow_slip_threshold = " + s.text(key::rsf_slow_slip_threshold) +
                ": slow slip lies between the plate rate and the seismic rate; allowed: 0 (off) "
                "or (" +
                s.text(key::drive_speed) + ", " + s.text(key::rsf_v_threshold) + ")" + where);
  if (v.rsf.pattern != RsfPattern::Uniform && !v.rsf.blocks.empty())
    throw Error("rsf.pattern = " + s.text(key::rsf_pattern) +
                " with rsf.blocks: per-block values come from one of them; allowed: rsf.pattern = "
                "uniform with a file, or no rsf.blocks" +
                where);
  if (v.rsf.pattern == RsfPattern::Asperities && !(v.rsf.law.b_rsf > 0))
    throw Error("rsf.b = " + s.text(key::rsf_b) +
                " with rsf.pattern = asperities: the barriers' direct effect is rsf.b; allowed: "
                "rsf.b > 0" +
                where);
  if (v.rsf.pattern == RsfPattern::Asperities && v.rsf.pattern_width >= v.rsf.pattern_period)
    throw Error("rsf.pattern_width = " + s.text(key::rsf_pattern_width) +
                ": an asperity must be narrower than the pattern's period rsf.pattern_period = " +
                s.text(key::rsf_pattern_period) + "; allowed: 1 to " +
                std::to_string(v.rsf.pattern_period - 1) + where);
}

// ---------------------------------------------------------------------------------------
// drive: how the substrate moves

std::vector<ParamSpec> drive_rows() {
  return {
      choice(key::drive_mode, "events", at(&SceneValues::drive, &DriveSettings::mode),
             {{"events", DriveMode::Events}, {"continuous", DriveMode::Continuous}},
             "events: quasistatic loading, one relaxation per slip event (nu -> 0); "
             "continuous: integrate at finite substrate speed"),
      real(
          key::drive_speed, at(&SceneValues::drive, &DriveSettings::speed), "0.01", '[', 0, 1e6,
          ']', "length/time",
          "substrate speed v (continuous mode; the start value of a steps schedule; the plate rate "
          "V_pl of friction.law = rsf in either mode)")
          .when(either(continuous(), rsf_law())),
      choice(
          key::drive_schedule, "constant", at(&SceneValues::drive, &DriveSettings::schedule),
          {{"constant", Schedule::Constant}, {"steps", Schedule::Steps}, {"ramp", Schedule::Ramp}},
          "substrate speed over time (continuous mode)")
          .when(continuous()),
      real(key::drive_step_increment, at(&SceneValues::drive, &DriveSettings::step_increment),
           "0.005", '[', -1e6, 1e6, ']', "length/time",
           "speed change at each step (schedule steps)")
          .when(steps_schedule()),
      real(key::drive_step_interval, at(&SceneValues::drive, &DriveSettings::step_interval), "2000",
           '(', 0, kLongTime, ']', "time", "time between speed steps (schedule steps)")
          .when(steps_schedule()),
      real(key::drive_ramp_from, at(&SceneValues::drive, &DriveSettings::ramp_from), "0", '[', 0,
           1e6, ']', "length/time", "speed at the start of the ramp (schedule ramp)")
          .when(ramp_schedule()),
      real(key::drive_ramp_to, at(&SceneValues::drive, &DriveSettings::ramp_to), "1", '[', 0, 1e6,
           ']', "length/time", "speed at the end of the ramp (schedule ramp)")
          .when(ramp_schedule()),
      real(key::drive_ramp_duration, at(&SceneValues::drive, &DriveSettings::ramp_duration),
           "40000", '(', 0, kLongTime, ']', "time",
           "time over which the speed ramps (schedule ramp)")
          .when(ramp_schedule()),
  };
}

// A continuous run: its step count, its speed schedule.
void continuous_run(const Scene& s, const std::string& where) {
  const SceneValues v = scene_values(s);
  if (v.drive.mode != DriveMode::Continuous) return;
  // The step counter is 64-bit and the clock a double: past 1e15 steps neither is safe.
  const double duration = v.run.duration;
  const double steps = duration / v.integrator.dt;
  if (!(steps <= kMaxSteps))
    throw Error("run.duration = " + s.text(key::run_duration) +
                " at integrator.dt = " + s.text(key::integrator_dt) + " is " + format_real(steps) +
                " time steps, more than a run can count (1e15); shorten run.duration or raise "
                "integrator.dt" +
                where);
  if (v.drive.schedule != Schedule::Steps) return;
  // The speed after the last step within the run, v0 + k inc, must stay in drive.speed's
  // range: a negative speed would drive the substrate backwards, which no friction law here
  // is written for.
  const double v0 = v.drive.speed, inc = v.drive.step_increment;
  const double interval = v.drive.step_interval;
  const double last = std::floor(duration / interval);
  const double v_end = v0 + last * inc;
  const ParamSpec& speed = *find_param(key::drive_speed);
  if (v_end >= speed.min && v_end <= speed.max) return;
  // The first step outside the range.
  const double k = inc < 0 ? std::floor(v0 / -inc) + 1 : std::floor((speed.max - v0) / inc) + 1;
  throw Error("drive.step_increment = " + s.text(key::drive_step_increment) +
              " takes the substrate speed out of " + allowed_text(speed) + " at step " +
              format_real(k) + " (time " + format_real(k * interval) + ", speed " +
              format_real(v0 + k * inc) + ") within run.duration = " + s.text(key::run_duration) +
              (inc < 0 ? ": the substrate would move backwards" : "") +
              "; shorten run.duration or change the schedule" + where);
}

// ---------------------------------------------------------------------------------------
// run: length, seed, start, checkpoints

std::vector<ParamSpec> run_rows() {
  return {
      integer(key::run_events, at(&SceneValues::run, &RunSettings::events), "100000", 0, 1e12, "",
              "events to record (events mode)")
          .when(event_driven()),
      integer(key::run_transient_events, at(&SceneValues::run, &RunSettings::transient_events),
              "1000", 0, 1e12, "", "events discarded before recording starts (events mode)")
          .when(event_driven()),
      real(key::run_duration, at(&SceneValues::run, &RunSettings::duration), "1000", '(', 0,
           kLongTime, ']', "time", "simulated time (continuous mode)")
          .when(continuous()),
      integer(key::run_seed, at(&SceneValues::run, &RunSettings::seed), "20261121", 0, kSeedMax, "",
              "random seed (initial disorder)"),
      real(key::run_initial_disorder, at(&SceneValues::run, &RunSettings::initial_disorder), "0.01",
           '[', 0, 10, ']', "D0", "initial displacements uniform in +-value*D0, D0 = F0 m_u / k_p")
          .when(rate_law(), chain_kinds()),
      choice(key::run_start, "disorder",
             at(&SceneValues::run, &RunSettings::start, &StartSettings::equilibrium),
             {{"disorder", false}, {"equilibrium", true}},
             "disorder: random displacements (run.initial_disorder), all stuck; equilibrium: "
             "steady sliding at the start speed plus run.start_mode (continuous mode)")
          .when(rate_law()),
      choice(key::run_start_mode, "none",
             at(&SceneValues::run, &RunSettings::start, &StartSettings::mode),
             {{"none", std::nullopt},
              {"chain", ModeFamily::Chain},
              {"pad", ModeFamily::Pad},
              {"1dof", ModeFamily::OneDof}},
             "family of the mode added to the equilibrium start (bkquake stability lists them)")
          .when(equilibrium_start()),
      integer(key::run_start_mode_index,
              at(&SceneValues::run, &RunSettings::start, &StartSettings::mode_index), "0", 0, 1e7,
              "", "index of that mode")
          .when(equilibrium_start()),
      real(key::run_start_amplitude,
           at(&SceneValues::run, &RunSettings::start, &StartSettings::amplitude), "1e-4", '(', 0, 1,
           ']', "", "largest speed of the perturbation as a fraction of the start speed")
          .when(equilibrium_start()),
      integer(key::run_max_steps_per_event,
              at(&SceneValues::run, &RunSettings::max_steps_per_event), "200000000", 1, 1e15, "",
              "give up on an event after this many relaxation steps (a runaway: dt or the scene is "
              "wrong)")
          .when(event_driven(), rate_law(), chain_kinds()),
      integer(
          key::run_checkpoint_events, at(&SceneValues::run, &RunSettings::checkpoint_events), "0",
          0, 1e12, "",
          "write a checkpoint every this many events (continuous runs: slip episodes; 0 = off)"),
      real(key::run_checkpoint_seconds, at(&SceneValues::run, &RunSettings::checkpoint_seconds),
           "600", '[', 0, 1e9, ']', "wall s",
           "write a checkpoint at least this often in wall-clock seconds, the first after 30 s "
           "(0 = off)"),
      choice(key::run_accuracy, "warn", at(&SceneValues::run, &RunSettings::accuracy_error),
             {{"warn", false}, {"error", true}},
             "what a run does when an accuracy indicator (energy residual, omega_max*dt, event "
             "steps) is above its threshold: warn on stderr, or fail with exit 2 keeping the "
             "outputs (unattended runs)")
          .when(chain_kinds()),
  };
}

void equilibrium_needs_continuous(const Scene& s, const std::string& where) {
  const SceneValues v = read(s, key::run_start, key::drive_mode);
  if (v.run.start.equilibrium && v.drive.mode != DriveMode::Continuous)
    throw Error("run.start = equilibrium needs drive.mode = continuous, but drive.mode = " +
                s.text(key::drive_mode) + where);
}

// ---------------------------------------------------------------------------------------
// integrator: the stepper of the dynamic phase

std::vector<ParamSpec> integrator_rows() {
  return {
      scheme_choice("rk4",
                    "rk2 (explicit midpoint), rk4, verlet, theta (theta-method, set-valued "
                    "friction), adaptive (event-located adaptive reference)")
          .when(rate_law(), chain_kinds()),
      real(key::integrator_dt, at(&SceneValues::integrator, &IntegratorSettings::dt), "0.01", '(',
           0, 1e6, ']', "time", "time step")
          .when(rate_law(), chain_kinds()),
      choice(key::integrator_transitions, "step",
             at(&SceneValues::integrator, &IntegratorSettings::located_transitions),
             {{"step", false}, {"located", true}},
             ("where stick and slip happen: step (at the end of the step that crosses them, "
              "first order) or located (inside the step, on its dense output: the scheme's "
              "order) (schemes " +
              shipped_locatable_text() + ")")
                 .c_str())
          .when(rate_law(), located_scheme())
          .later(),
      real(key::integrator_tolerance, at(&SceneValues::integrator, &IntegratorSettings::tolerance),
           "1e-08", '[', 1e-14, 1e-2, ']', "",
           "local error tolerance (scheme adaptive; friction.law = rsf: of ln V, ln theta and "
           "slip/(D_c + |slip|) per Dormand-Prince 5(4) step)")
          .when(adaptive_or_rsf(), chain_kinds()),
      real(key::integrator_theta, at(&SceneValues::integrator, &IntegratorSettings::theta), "0.5",
           '[', 0.5, 1, ']', "",
           "implicit weight theta of the theta-method: 1/2 trapezoidal (conserves), 1 backward "
           "Euler (damps) (scheme theta)")
          .when(theta_scheme(), chain_kinds()),
  };
}

// ---------------------------------------------------------------------------------------
// output

std::vector<ParamSpec> output_rows() {
  return {
      real(key::output_every, at(&SceneValues::output, &OutputSettings::every), "1", '(', 0,
           kLongTime, ']', "time", "time between timeseries rows (continuous mode)")
          .when(continuous()),
      boolean(key::output_blocks, at(&SceneValues::output, &OutputSettings::blocks), "false",
              "also write block trajectories (continuous mode)")
          .when(continuous()),
      integer(key::output_block_first, at(&SceneValues::output, &OutputSettings::block_first), "0",
              0, 1e7, "", "first block written to blocks.csv (output.blocks; 0-based)")
          .when(continuous()),
      integer(key::output_block_count, at(&SceneValues::output, &OutputSettings::block_count), "0",
              0, 1e7, "",
              "how many adjacent blocks blocks.csv holds from output.block_first (0: to the end)")
          .when(continuous()),
      boolean(key::output_status, at(&SceneValues::output, &OutputSettings::status), "false",
              "append the node status (blocks stuck, sliding forward, sliding backward) to "
              "timeseries.csv (continuous mode)")
          .when(continuous(), rate_law()),
      boolean(key::output_energy, at(&SceneValues::output, &OutputSettings::energy), "false",
              "write energy_samples.csv and energy.csv: mechanical energy from the sliding "
              "equilibrium, its windowed mean and rate, the braking force (continuous mode)")
          .when(continuous(), rate_law()),
      real(key::output_energy_window, at(&SceneValues::output, &OutputSettings::energy_window),
           "10", '(', 0, kLongTime, ']', "time", "window dT of the energy means (50 % overlap)")
          .when(continuous(), rate_law(), energy_on()),
      real(key::output_energy_tol, at(&SceneValues::output, &OutputSettings::energy_tol), "0.001",
           '(', 0, kHuge, ']', "1/time",
           "the energy has settled once |tau_E| stays below this in every later window")
          .when(continuous(), rate_law(), energy_on()),
      choice(key::output_catalog, "csv", CatalogAccess{},
             {{"csv", {CatalogFormat::Csv, false}},
              {"hdf5", {CatalogFormat::Hdf5, false}},
              {"hdf5-deflate", {CatalogFormat::Hdf5, true}},
              {"none", {CatalogFormat::None, false}}},
             "the event catalogue: csv (catalog.csv), hdf5 (catalog.h5, one table), "
             "hdf5-deflate (the same table compressed: a quarter of the size, slower), none (no "
             "catalogue; the histogram and the fit are still written)"),
      none_real(key::output_event_slip, at(&SceneValues::output, &OutputSettings::event_slip),
                kMuLimit, "",
                "write event_slip.csv (event runs): the slip of every block of each event with "
                "mu >= this, one row per block (event,block,slip; a lattice of more than one "
                "row adds row after block, the OFC automaton topplings after slip, its slip "
                "being the stress a site released); none: not written")
          .when(event_driven()),
      integer(key::output_segment_blocks, at(&SceneValues::output, &OutputSettings::segment_blocks),
              "4", 1, 1e6, "",
              "blocks M of the segment statistics' errors in segments.csv (thesis eq. 4.3)")
          .when(continuous(), rate_law()),
  };
}

// ---------------------------------------------------------------------------------------
// stats: magnitude histogram and fits

std::vector<ParamSpec> stats_rows() {
  return {
      real(key::stats_bin_width, at(&SceneValues::stats, &StatsSettings::bin_width), "0.2", '(', 0,
           10, ']', "", "magnitude bin width of the histogram"),
      auto_real(key::stats_mu_min, at(&SceneValues::stats, &StatsSettings::mu_min), kMuLimit, "",
                "lower end of the Gutenberg-Richter fit window, or auto"),
      auto_real(key::stats_mu_max, at(&SceneValues::stats, &StatsSettings::mu_max), kMuLimit, "",
                "upper end of the Gutenberg-Richter fit window, or auto"),
  };
}

void fit_window(const Scene& s, const std::string& where) {
  const SceneValues v = read(s, key::stats_mu_min, key::stats_mu_max);
  if (v.stats.mu_min && v.stats.mu_max && *v.stats.mu_min >= *v.stats.mu_max)
    throw Error("stats.mu_min = " + s.text(key::stats_mu_min) +
                " must be below stats.mu_max = " + s.text(key::stats_mu_max) + where);
}

// ---------------------------------------------------------------------------------------

// Each key once; each applies-when condition names a choice or boolean row and only values
// that row allows. A mistake here is a programming error, found by any test.
void check_table(const std::vector<ParamSpec>& table) {
  const auto row = [&](const std::string& key) -> const ParamSpec* {
    for (const auto& p : table)
      if (p.key == key) return &p;
    return nullptr;
  };
  for (std::size_t i = 0; i < table.size(); ++i) {
    const ParamSpec& p = table[i];
    if (row(p.key) != &p) throw std::logic_error("scene: key '" + p.key + "' declared twice");
    if (!p.fill || !p.text_of) throw std::logic_error("scene: " + p.key + " fills no member");
    for (const Requirement& r : p.applies_when)
      for (const KeyCondition& c : r.any_of) {
        const ParamSpec* controller = row(c.controller);
        if (!controller ||
            (controller->type != ParamType::Choice && controller->type != ParamType::Boolean))
          throw std::logic_error("scene: " + p.key + " depends on '" + c.controller +
                                 "', which is not a choice");
        const std::vector<std::string> allowed = controller->type == ParamType::Boolean
                                                     ? std::vector<std::string>{"true", "false"}
                                                     : controller->allowed_choices();
        for (const std::string& value : c.allowed())
          if (std::find(allowed.begin(), allowed.end(), value) == allowed.end())
            throw std::logic_error("scene: " + p.key + " depends on " + c.controller + " = " +
                                   value + ", which it does not allow");
      }
  }
}

}  // namespace

bool scheme_supports_located(const std::string& scheme) {
  const SchemeTraits* traits = scheme_traits(scheme);  // the scheme's own declaration
  return traits != nullptr && traits->locatable;
}

std::vector<ParamSpec> make_parameter_table() {
  std::vector<ParamSpec> table;
  for (auto section : {model_rows, stiffness_rows, si_model_rows, ofc_rows, friction_rows, rsf_rows,
                       drive_rows, run_rows, integrator_rows, output_rows, stats_rows})
    for (ParamSpec& p : section()) table.push_back(std::move(p));
  check_table(table);
  return table;
}

const std::vector<CrossKeyRule>& cross_key_rules() {
  static const std::vector<CrossKeyRule> rules = {table_file,
                                                  periodic_chain_length,
                                                  automaton_lattice,
                                                  chain_lattice,
                                                  chain_range,
                                                  stencil_cost,
                                                  equilibrium_needs_continuous,
                                                  fit_window,
                                                  rate_and_state,
                                                  continuous_run};
  return rules;
}

SceneValues scene_values(const Scene& scene) {
  SceneValues v;
  for (const ParamSpec& p : parameter_table()) p.fill(v, scene.text(p.key));
  return v;
}

}  // namespace bkq
