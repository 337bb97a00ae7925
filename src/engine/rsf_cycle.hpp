// Rate-and-state seismic cycles (model/laws/rsf.hpp) of a spring-slider or a chain of them,
// through interseismic creep and ruptures alike, by one adaptive explicit integrator. A path
// of its own beside the continuous driver: the event kernels never see this law's state.
//
// Model, per unit fault area (SI), block j = 0..N-1, slip delta_j, slip rate V_j, state theta_j:
//   elastic stress  tau_j = tau0_j + k (V_pl t - delta_j) + sum_{i nb j} k_ji (delta_i - delta_j)
//   quasi-dynamic   tau_j - eta V_j = sigma f(V_j, theta_j)       (Rice 1993; eta = G/(2 c_s))
//   inertial        m dV_j/dt = tau_j - eta V_j - sigma f(V_j, theta_j)
// The blocks sit on a grid of `rows` rows of N/rows blocks (site j = y nx + x; one row is the
// chain) and are coupled by a stencil of springs (model/coupling.hpp: nearest neighbours, or
// range and power kernels on chains and lattices). Free edges drop the springs that reach past
// them; periodic edges wrap. The neighbour lists are built once (compressed rows), so the
// coupling sums cost one term per spring: 2N for a nearest-neighbour chain, 4N for a lattice,
// 2RN for a chain of range R and about pi R^2 N for a lattice's disc.
// Variables y = (delta_j, ln V_j, ln theta_j): V spans 1e-12..10 m/s and theta many decades,
// and in logarithms both stay O(1)-smooth (QDYN integrates the same way). The quasi-dynamic
// balance differentiated in time gives ln V explicitly, with f_lnv = V df/dV, f_lntheta =
// theta df/dtheta (a and b_rsf for the log form):
//   d ln V_j/dt = [dtau_j/dt - sigma f_lntheta d ln theta_j/dt] / (sigma f_lnv + eta V_j),
//   dtau_j/dt   = k (V_pl - V_j) + k_c sum_{i nb j} (V_i - V_j),
// an O(N) right-hand side with no implicit solve; slip only feeds back in the inertial case,
//   d ln V_j/dt = (tau_j - eta V_j - sigma f)/(m V_j).
//
// Scheme: Dormand-Prince 5(4) (Dormand & Prince 1980; Hairer, Norsett & Wanner, Solving ODEs I,
// II.5), 7 stages, first same as last (6 right-hand sides per accepted step), order 5
// propagated (local extrapolation). Error estimate: the difference of the embedded 5th- and
// 4th-order solutions, err_i = h sum_s e_s k_s,i, in the max norm scaled by tol for ln V and
// ln theta (absolute: a relative error of V and theta) and by tol (D_c + |delta_i|) for slip.
// A step is accepted when that norm is <= 1; the next h = h min(5, max(0.2, 0.9 err^-1/5))
// (no growth right after a rejection). Explicit, so its stability region bounds h by about
// 3.3/|lambda| of the local Jacobian; the error control keeps h inside it (it shows as
// rejected steps, counted).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "engine/dormand_prince.hpp"
#include "model/coupling.hpp"
#include "model/laws/rsf.hpp"

namespace bkq {

// ImposedRate holds every V_j at its start value (a lab velocity step: only the state evolves).
enum class RsfDynamics { QuasiDynamic, Inertial, ImposedRate };

struct RsfModel {
  std::vector<rsf::Law> law;  // per block; its size is N
  rsf::StateLaw state_law = rsf::StateLaw::Aging;
  rsf::Form form = rsf::Form::Log;
  RsfDynamics dynamics = RsfDynamics::QuasiDynamic;
  double sigma = 5e6;     // normal stress [Pa]
  double k = 2e9;         // loading spring per unit area [Pa/m]
  double k_c = 0;         // nearest-neighbour coupling spring [Pa/m] (the springs' total)
  bool periodic = false;  // a ring instead of free ends (along strike)
  int rows = 1;           // rows across strike; N/rows blocks along strike
  bool periodic_y = false;
  // The coupling springs (dx along strike, dy across); empty: nearest neighbours along the
  // chain, {(1, 0, k_c)}.
  LatticeStencil springs;
  double v_pl = 1e-6;  // plate (loader) rate [m/s]
  double eta = 0;      // radiation damping G/(2 c_s) [Pa s/m]; 0: off
  double mass = 0;     // inertia per unit area [kg/m^2] (inertial dynamics only)
  int n() const { return static_cast<int>(law.size()); }
  int nx() const { return n() / rows; }
  // `springs`, or the nearest-neighbour chain's one spring.
  LatticeStencil stencil() const {
    if (!springs.empty() || k_c == 0) return springs;
    return {{1, 0, k_c}};
  }
};

// Every block's neighbours and springs in compressed rows: block j's are entries
// start[j] .. start[j+1]-1 of index and k.
struct RsfNeighbours {
  std::vector<int> start, index;
  std::vector<double> k;
};
RsfNeighbours rsf_neighbours(const RsfModel& m);

// Hermite cubic through (t0, x0, x0') and (t1, x1, x1'): the time of its interior extremum
// (where the derivative changes sign, x0' x1' <= 0) and the value there.
struct Extremum {
  double t = 0, x = 0;
};
Extremum hermite_extremum(double t0, double x0, double d0, double t1, double x1, double d1);
// The Hermite cubic's value at t in [t0, t1].
double hermite_value(double t0, double x0, double d0, double t1, double x1, double d1, double t);

class RsfCycle {
 public:
  // Starts at t = 0, slip 0, slip rates v and states theta (one value each, or one per
  // block), with the elastic stress in balance (tau0_j = sigma f + eta V_j).
  RsfCycle(RsfModel model, double tolerance, const std::vector<double>& v,
           const std::vector<double>& theta);

  // One accepted step, ending at most at t_max. Returns the accepted step size.
  double step(double t_max = std::numeric_limits<double>::infinity());
  // Steps until t reaches t_end exactly.
  void advance_to(double t_end);

  const RsfModel& model() const { return m_; }
  int n() const { return m_.n(); }
  double t() const { return dp_.t; }
  double t_prev() const { return dp_.t_prev; }
  double next_step() const { return dp_.h; }  // the step size the next step tries first
  double slip(int j) const { return dp_.y[j]; }
  double ln_v(int j) const { return dp_.y[n() + j]; }
  double ln_theta(int j) const { return dp_.y[2 * n() + j]; }
  // The state and its time derivative now and at the start of the last step (y layout:
  // slip, ln V, ln theta, each N long): what dense output and extremum location use.
  const std::vector<double>& y() const { return dp_.y; }
  const std::vector<double>& dy() const { return dp_.dy; }
  const std::vector<double>& y_prev() const { return dp_.y_prev; }
  const std::vector<double>& dy_prev() const { return dp_.dy_prev; }
  // Frictional stress sigma f(V_j, theta_j) (QDYN's tau) and the elastic stress tau_j.
  double friction_stress(int j) const;
  double elastic_stress(int j) const;
  // d(friction stress)/dt now, from the state's derivative.
  double friction_stress_rate(int j) const;

  double tolerance() const { return tol_; }
  std::int64_t accepted() const { return dp_.accepted; }
  std::int64_t rejected() const { return dp_.rejected; }

  // Everything a resumed integration needs, as numbers (the run's checkpoint stores them).
  std::vector<double> snapshot() const;
  void restore(const std::vector<double>& s);

 private:
  void rhs(double t, const double* y, double* dy);
  double error_norm(const std::vector<double>& err, const std::vector<double>& y) const;

  RsfModel m_;
  double tol_;
  // The integration's time, step size, state (slip, ln V, ln theta) and stages.
  dopri::Adaptive<> dp_;
  std::vector<double> tau0_;
  double coupling(int j, const double* x) const;

  RsfNeighbours nb_;
  std::vector<double> v_;
};

}  // namespace bkq
