// `bkquake stability` and the equilibrium start of continuous runs; see stability.hpp.
#include "app/stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/scene_values.hpp"
#include "io/stability_csv.hpp"

namespace bkq {

namespace {

double parse_number(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !std::isfinite(v))
    throw Error(what + ": '" + text + "' is not a number");
  return v;
}

double start_speed(const Settings& s) {
  return substrate_of(s.drive).at(0.0).v;
}

// The analysis of one scene.
StabilityPoint analyse(const Scene& scene, double value, const StabilityOptions& opt) {
  const Settings settings = settings_from_scene(scene);
  const ModelParams& p = settings.model;
  if (p.lattice())
    throw Error("stability: model.rows = " + std::to_string(p.rows) +
                " with model.blocks = " + std::to_string(p.nx()) +
                ": the linear analysis is written for chains; allowed: model.rows = 1 (or "
                "model.blocks = 1, a column, which is the chain along y)");
  StabilityPoint pt;
  pt.value = value;
  pt.speed = settings.drive.speed;
  pt.equilibrium = sliding_equilibrium(p, pt.speed);
  if (!pt.equilibrium.exists())
    throw Error("stability: " + no_equilibrium_message(p, pt.equilibrium.why, pt.speed));
  pt.equilibrium.u.clear();
  const double slope = pt.equilibrium.friction.slope;
  if (opt.dense && p.n > kDenseLimit)
    throw Error("stability: --dense: model.blocks = " + std::to_string(p.n) +
                " is above the dense solver's limit " + std::to_string(kDenseLimit) +
                " (O(N^3)); the modal reduction is exact for every N");
  if (!opt.dense) check_modal_reduction(p);
  pt.modes = opt.dense ? dense_eigenmodes(p, slope) : modal_eigenmodes(p, slope);
  for (const ModeSelect& sel : opt.shapes) pt.shapes.push_back(find_mode(p, slope, sel));
  return pt;
}

}  // namespace

StabilitySweep parse_sweep(const std::string& text, bool log) {
  const std::string what = "stability: --sweep " + text;
  const auto eq = text.find('=');
  const auto c1 = text.find(':', eq == std::string::npos ? 0 : eq);
  const auto c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  if (eq == std::string::npos || c1 == std::string::npos || c2 == std::string::npos)
    throw Error(what + ": expected KEY=FROM:TO:COUNT, e.g. drive.speed=0.01:1:50");
  StabilitySweep s;
  s.key = text.substr(0, eq);
  s.from = parse_number(text.substr(eq + 1, c1 - eq - 1), what + ": FROM");
  s.to = parse_number(text.substr(c1 + 1, c2 - c1 - 1), what + ": TO");
  const double count = parse_number(text.substr(c2 + 1), what + ": COUNT");
  if (count < 1 || count > 100000 || count != std::floor(count))
    throw Error(what + ": COUNT must be an integer in [1, 100000]");
  s.count = static_cast<int>(count);
  s.log = log;
  const ParamSpec* spec = find_param(s.key);
  if (!spec)
    throw Error(what + ": unknown key '" + s.key +
                "'; see 'bkquake run --dump-defaults' for all keys");
  if (spec->type != ParamType::Real && spec->type != ParamType::Integer)
    throw Error(what + ": " + s.key + " is not a number; only real and integer keys can be swept");
  if (log && !(s.from > 0 && s.to > 0)) throw Error(what + ": --log needs FROM and TO above 0");
  return s;
}

ModeSelect parse_mode(const std::string& text, const std::string& what) {
  const auto comma = text.find(',');
  const std::string family = text.substr(0, comma);
  ModeSelect m;
  if (family == "chain")
    m.family = ModeFamily::Chain;
  else if (family == "pad")
    m.family = ModeFamily::Pad;
  else if (family == "1dof")
    m.family = ModeFamily::OneDof;
  else
    throw Error(what + ": expected FAMILY,INDEX with FAMILY chain|pad|1dof, got '" + text + "'");
  if (comma == std::string::npos)
    throw Error(what + ": expected FAMILY,INDEX (e.g. chain,3), got '" + text + "'");
  const double index = parse_number(text.substr(comma + 1), what + ": INDEX");
  if (index < 0 || index != std::floor(index) || index > 1e7)
    throw Error(what + ": INDEX must be an integer >= 0, got '" + text + "'");
  m.index = static_cast<int>(index);
  return m;
}

std::string mode_name(const Eigenmode& m) {
  return std::string(to_string(m.family)) + ":" + std::to_string(m.index);
}

std::string no_equilibrium_message(const ModelParams& p, NoEquilibrium why, double v) {
  switch (why) {
    case NoEquilibrium::None:
      break;
    case NoEquilibrium::NotSliding:
      return "no sliding equilibrium at drive.speed = " + format_real(v) +
             ": at zero relative velocity friction is set-valued and the blocks stick; give "
             "drive.speed > 0";
    case NoEquilibrium::NoPadSpring:
      return "no sliding equilibrium with model.caliper_stiffness = 0: nothing holds the pad "
             "against the blocks' friction N m_u phi(v) = " +
             format_real(p.n * p.m_u * kinetic_branch(p, v).phi) +
             " (the pad drifts); give model.caliper_stiffness > 0";
    case NoEquilibrium::NoKinetic:
      return std::string("no sliding equilibrium: friction.law = ") + to_string(p.law) +
             " has no smooth kinetic branch at drive.speed = " + format_real(v);
  }
  return "";
}

void check_modal_reduction(const ModelParams& p) {
  if (p.reach() == 1 || !(p.long_range() || p.viscous()) || p.boundary != Boundary::Free) return;
  throw Error(std::string("model.coupling = ") +
              (p.coupling == Coupling::Power ? "power" : "range") +
              " with model.boundary = free: the cosine modes are not this chain's modes (its "
              "springs are cut at the ends), so the modal reduction does not apply; allowed: "
              "model.boundary = periodic, or --dense (bkquake stability)");
}

std::pair<Eigenmode, ModeShape> find_mode(const ModelParams& p, double slope, ModeSelect sel) {
  check_modal_reduction(p);
  const std::vector<Eigenmode> modes = modal_eigenmodes(p, slope);
  const Eigenmode* best = nullptr;
  for (const Eigenmode& m : modes)
    if (m.family == sel.family && m.index == sel.index && (!best || m.growth() > best->growth()))
      best = &m;
  if (!best) {
    std::string have = p.kind == ModelKind::OneDof ? "1dof,0"
                       : p.pad_moves() ? "chain,0.." + std::to_string(p.n - 1) + ", pad,0"
                                       : "chain,0.." + std::to_string(p.n - 1);
    throw Error(std::string("mode ") + to_string(sel.family) + "," + std::to_string(sel.index) +
                " does not exist for this scene (model.kind = " + to_string(p.kind) +
                ", model.blocks = " + std::to_string(p.n) + "); its modes are " + have);
  }
  return {*best, modal_shape(p, slope, *best)};
}

std::vector<StabilityPoint> run_stability(const Scene& base, const StabilityOptions& opt) {
  std::vector<StabilityPoint> out;
  if (!opt.sweep) {
    Scene scene = base;
    scene.validate();
    out.push_back(analyse(scene, scene_values(scene).drive.speed, opt));
    return out;
  }
  const StabilitySweep& s = *opt.sweep;
  const bool integer = find_param(s.key)->type == ParamType::Integer;
  for (int i = 0; i < s.count; ++i) {
    const double f = s.count > 1 ? static_cast<double>(i) / (s.count - 1) : 0.0;
    double value = s.log ? s.from * std::pow(s.to / s.from, f) : s.from + f * (s.to - s.from);
    if (i == s.count - 1) value = s.to;
    if (integer) value = std::round(value);
    if (integer && !out.empty() && out.back().value == value) continue;
    Scene scene = base;
    scene.set(s.key,
              integer ? std::to_string(static_cast<std::int64_t>(value)) : format_real(value),
              "--sweep");
    scene.validate();
    out.push_back(analyse(scene, value, opt));
  }
  return out;
}

std::string stability_csv(const std::vector<StabilityPoint>& points) {
  std::string s = header_of(stability_schema()) + "\n";
  for (const StabilityPoint& pt : points)
    for (const Eigenmode& m : pt.modes) {
      s += format_real(pt.value) + "," + mode_name(m) + "," + format_real(m.growth()) + "," +
           format_real(m.lambda.imag()) + "," + format_real(m.frequency()) + "," +
           (m.unstable() ? "1" : "0") + "\n";
    }
  return s;
}

std::string stability_summary_csv(const std::vector<StabilityPoint>& points) {
  std::string s = header_of(stability_summary_schema()) + "\n";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const StabilityPoint& pt : points) {
    int unstable = 0;
    const Eigenmode* top = nullptr;
    const Eigenmode* pad = nullptr;
    for (const Eigenmode& m : pt.modes) {
      unstable += m.unstable() ? 1 : 0;
      if (!top || m.growth() > top->growth()) top = &m;
      if (m.family == ModeFamily::Pad && (!pad || m.growth() > pad->growth())) pad = &m;
    }
    s += format_real(pt.value) + "," + format_real(pt.speed) + "," +
         format_real(pt.equilibrium.friction.phi) + "," +
         format_real(pt.equilibrium.friction.slope) + "," + format_real(pt.equilibrium.x) + "," +
         std::to_string(pt.modes.size()) + "," + std::to_string(unstable) + "," +
         format_real(top ? top->growth() : nan) + "," + format_real(top ? top->frequency() : nan) +
         "," + (top ? mode_name(*top) : "") + "," + format_real(pad ? pad->growth() : nan) + "," +
         format_real(pad ? pad->frequency() : nan) + "\n";
  }
  return s;
}

std::string modes_csv(const std::vector<StabilityPoint>& points) {
  std::string s = header_of(modes_schema()) + "\n";
  for (const StabilityPoint& pt : points)
    for (const auto& [m, shape] : pt.shapes)
      for (std::size_t k = 0; k < shape.size(); ++k)
        s += format_real(pt.value) + "," + mode_name(m) + "," + format_real(m.growth()) + "," +
             format_real(m.lambda.imag()) + "," + std::to_string(k) + "," +
             format_real(shape[k].real()) + "," + format_real(shape[k].imag()) + "\n";
  return s;
}

ChainState equilibrium_start(const ChainForces& forces, const Settings& settings) {
  const ModelParams& p = forces.params();
  const double v = start_speed(settings);
  const SlidingEquilibrium eq = sliding_equilibrium(p, v);
  if (!eq.exists()) throw Error("run.start = equilibrium: " + no_equilibrium_message(p, eq.why, v));
  ChainState st;
  st.resize(p.n);
  std::vector<double> du(p.n, 0.0), dv(p.n, 0.0);
  double dx = 0, dxd = 0;
  const StartSettings& start = settings.run.start;
  if (start.mode) {
    const auto [mode, shape] =
        find_mode(p, eq.friction.slope, ModeSelect{*start.mode, start.mode_index});
    // u = eps Re(s), u' = eps Re(lambda s), eps so that the largest |lambda s_k| eps is
    // amplitude * v (|s_k| <= 1, so no block comes near sticking for amplitude << 1).
    double biggest = 0;
    for (const auto& z : shape) biggest = std::max(biggest, std::abs(mode.lambda * z));
    const double eps = start.amplitude * v / biggest;
    for (int j = 0; j < p.n; ++j) {
      du[j] = eps * shape[j].real();
      dv[j] = eps * (mode.lambda * shape[j]).real();
    }
    if (p.pad_moves()) {
      dx = eps * shape[p.n].real();
      dxd = eps * (mode.lambda * shape[p.n]).real();
    }
  }
  // Substrate frame: w = u + s (s = 0 at t = 0), relative velocity w' = v + u'.
  for (int j = 0; j < p.n; ++j) {
    st.w[j] = eq.u[j] + du[j];
    st.wd[j] = v + dv[j];
    st.mobile[j] = 1.0;
    st.dir[j] = st.wd[j] >= 0 ? 1.0 : -1.0;
  }
  st.x = eq.x + dx;
  st.xd = dxd;
  st.recompute_sum_w();
  return st;
}

}  // namespace bkq
