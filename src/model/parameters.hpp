// Physical parameters of a chain, derived once from a scene in one of the two
// parameterisations of Ferre 2018 eq. 3.1 (Ferre 2018 Table 3.1, or the dimensionless
// Carlson–Langer units of eq. 2.2). Everything downstream sees only these numbers.
#pragma once

#include <string>
#include <vector>

#include "model/law_list.hpp"

namespace bkq {

enum class ModelKind { BK, BKP, OneDof };
enum class Boundary { Free, Periodic };
// How the blocks are coupled to each other (model/coupling.hpp): nearest neighbours only, or
// every block within model.range on either side, by equal springs (Range) or by springs
// decaying as 1/r^p (Power).
enum class Coupling { Nearest, Range, Power };

// The rows of a tabulated friction law (friction.law = table, model/laws/table.hpp):
// |phi| per unit block mass at increasing relative speeds >= 0.
struct FrictionTable {
  std::vector<double> speed, friction;
};

struct ModelParams {
  ModelKind kind = ModelKind::BK;
  Boundary boundary = Boundary::Free;  // along strike (the chain's ends)
  int n = 100;                         // number of blocks (sites of a lattice)
  // A lattice (Carlson 1991): `rows` rows across strike of nx() = n / rows blocks along strike,
  // stored row by row, site j = y nx + x. rows = 1 is the chain; a lattice of one column is
  // the chain along y (line_as_chain), so rows > 1 below means nx() > 1 as well.
  int rows = 1;
  Boundary boundary_y = Boundary::Free;  // across strike: free edges or periodic rows
  double k_c_y = 0;                      // across-strike neighbour spring (k_c along strike)

  double m_u = 1;  // block mass
  double k_p = 1;  // pulling spring (block to pad)
  double k_c = 0;  // neighbour spring (with range coupling: the springs' total, model/coupling.hpp)
  Coupling coupling = Coupling::Nearest;
  int range = 1;                 // R: coupled to the blocks within R on each side
  double coupling_exponent = 3;  // p of the power kernel's 1/r^p
  // Viscous coupling eta (Myers & Langer 1993): dashpots between the blocks the springs couple,
  // shaped as the coupling's stencil with their sum eta (model/coupling.hpp).
  double viscosity = 0;
  double c_u = 0;  // block damper (1DOF model only, Ferre 2018 eq. 2.11)

  double m_x = 0;   // pad mass (BKP)
  double k_p0 = 0;  // caliper-pad spring (BKP)
  double c_p = 0;   // pad damper (BKP)

  // Rayleigh damping alpha_M M + beta_K K of the whole linear structure (Sinou, Chiello & Charroyer
  // 2019 §4.2): M and K are the mass and stiffness matrices of blocks and pad (K holds k_c, the k_p
  // coupling and, for bkp, the pad row with k_p0). Off (0) by default; the analysis
  // (stats/stability) and the continuous runs' force kernels (model/chain) apply it.
  double rayleigh_alpha = 0;  // alpha_M [1/time]
  double rayleigh_beta = 0;   // beta_K [time]

  FrictionLaw law = law_id<law::Clst91>;  // model/laws/: phi(y) and the stick threshold
  double F0 = 1;        // static threshold per unit block mass: stuck while |f| <= F0*m_u
  double sigma = 0;     // drop from static to kinetic friction
  double v_c = 1e300;   // characteristic velocity (Carlson–Langer: 1/(2 alpha)); huge = flat law
  FrictionTable table;  // the table law's rows (empty for the other laws)

  bool pad_moves() const { return kind == ModelKind::BKP; }
  bool has_neighbours() const { return (k_c != 0 || (lattice() && k_c_y != 0)) && n > 1; }
  // A two-dimensional lattice (more than one row and more than one column).
  bool lattice() const { return rows > 1; }
  int nx() const { return n / rows; }
  // How far the coupling reaches on each side: 1 for nearest neighbours (and for range or
  // power at R = 1, which are the nearest-neighbour chain), R otherwise (on a lattice, the
  // radius of the disc of coupled sites).
  int reach() const { return coupling == Coupling::Nearest ? 1 : range; }
  // Coupling beyond the nearest neighbours of a chain: the kernels that read only j +- 1 do not
  // apply.
  bool long_range() const { return has_neighbours() && reach() > 1; }
  // Dashpots between blocks (model.viscosity).
  bool viscous() const { return viscosity != 0 && n > 1; }
  // Static threshold on the spring force of one block.
  double threshold() const { return F0 * m_u; }
  // Largest angular frequency of the linear part (Ferre 2018 eq. 3.2, and the pad's), or the
  // largest damping rate where that is larger (dampers, Rayleigh damping).
  double max_angular_frequency() const;
  // Stuck blocks' force grows by this much per unit substrate displacement (quasistatic load).
  double loading_rate() const;
};

// Damper of a mass m on a spring k at damping ratio zeta: zeta 2 sqrt(k m) (Ferre 2018 §3.1).
double critical_damping(double zeta, double k, double m);

// A lattice of one column (n = rows) is the chain of its rows: the across-strike spring and
// boundary become the chain's. Anything else is returned as it is.
ModelParams line_as_chain(ModelParams p);

const char* to_string(ModelKind k);

}  // namespace bkq
