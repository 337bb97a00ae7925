// Derivation of the physical parameters from a scene (SPEC §1): thesis Table 3.1
// (block quantities scaled from the pad's) or Carlson–Langer dimensionless units (eq. 2.2).
#include "model/parameters.hpp"

#include <algorithm>
#include <cmath>

#include "io/scene.hpp"

namespace bkq {

namespace {

// Critical damping of a mass m on a spring k is 2 sqrt(k m); zeta scales it (thesis §3.1).
double damper(double zeta, double k, double m) {
  return zeta * 2.0 * std::sqrt(k * m);
}

}  // namespace

double ModelParams::max_angular_frequency() const {
  // Thesis eq. 3.2: the fastest chain mode has neighbours in antiphase, sqrt((4 k_c + k_p)/m_u).
  double w = std::sqrt(((has_neighbours() ? 4.0 * k_c : 0.0) + k_p) / m_u);
  // A damper is a real eigenvalue of size c/m; explicit steppers must resolve it too.
  w = std::max(w, c_u / m_u);
  if (pad_moves()) {
    const double K = k_p0 + n * k_p;
    w = std::max({w, std::sqrt(K / m_x), c_p / m_x});
  }
  return w;
}

double ModelParams::loading_rate() const {
  // SPEC §2: BK, every stuck block gains k_p per unit substrate displacement; with a
  // quasi-statically relaxing pad the pad follows by N k_p/(k_p0 + N k_p) of the way.
  if (!pad_moves()) return k_p;
  return k_p * k_p0 / (k_p0 + n * k_p);
}

ModelParams model_from_scene(const Scene& scene) {
  ModelParams p;
  const std::string& kind = scene.choice("model.kind");
  p.kind = kind == "bkp" ? ModelKind::BKP : kind == "1dof" ? ModelKind::OneDof : ModelKind::BK;
  p.boundary = scene.choice("model.boundary") == "periodic" ? Boundary::Periodic : Boundary::Free;
  p.n = p.kind == ModelKind::OneDof ? 1 : static_cast<int>(scene.integer("model.blocks"));

  const std::string& law = scene.choice("friction.law");
  p.law = law == "thesis" ? FrictionLaw::Thesis
          : law == "cl89" ? FrictionLaw::Cl89
          : law == "none" ? FrictionLaw::None
                          : FrictionLaw::Clst91;
  p.sigma = scene.real("friction.sigma");

  const double s_m = scene.real("model.s_m");
  const double s_p = scene.real("model.s_p");
  const double zeta = scene.real("model.damping_ratio");
  double m_x = 0, k_p0 = 0;
  if (scene.choice("model.parameterisation") == "thesis") {
    // Thesis Table 3.1: the blocks share the pad's mass and spring, the chain keeps the
    // axial stiffness of a single element (k_c grows with N).
    m_x = scene.real("model.pad_mass");
    k_p0 = scene.real("model.caliper_stiffness");
    p.m_u = s_m * m_x / p.n;
    p.k_p = s_p * k_p0 / p.n;
    p.k_c = scene.real("model.s_c") * k_p0 * p.n;
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
    const double alpha = scene.real("friction.alpha");
    p.v_c = alpha > 0 ? 1.0 / (2.0 * alpha) : HUGE_VAL;
    m_x = p.n * p.m_u / s_m;
    k_p0 = p.n * p.k_p / s_p;
  }
  if (p.n == 1) p.k_c = 0;
  if (p.kind == ModelKind::BKP) {
    p.m_x = m_x;
    p.k_p0 = k_p0;
    p.c_p = damper(zeta, k_p0 + p.n * p.k_p, m_x);
  } else if (p.kind == ModelKind::OneDof) {
    // Thesis eq. 2.11: one mass on a spring with a damper, m x'' = -c x' - k x - F(x' + v).
    p.c_u = damper(zeta, p.k_p, p.m_u);
  }
  return p;
}

const char* to_string(ModelKind k) {
  switch (k) {
    case ModelKind::BK:
      return "bk";
    case ModelKind::BKP:
      return "bkp";
    case ModelKind::OneDof:
      return "1dof";
  }
  return "?";
}

const char* to_string(FrictionLaw f) {
  switch (f) {
    case FrictionLaw::Thesis:
      return "thesis";
    case FrictionLaw::Clst91:
      return "clst91";
    case FrictionLaw::Cl89:
      return "cl89";
    case FrictionLaw::None:
      return "none";
  }
  return "?";
}

}  // namespace bkq
