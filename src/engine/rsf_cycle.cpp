// The rate-and-state cycle integrator; see rsf_cycle.hpp for the equations and the scheme.
#include "engine/rsf_cycle.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "engine/dormand_prince.hpp"

namespace bkq {

namespace {}  // namespace

double hermite_value(double t0, double x0, double d0, double t1, double x1, double d1, double t) {
  const double h = t1 - t0, s = (t - t0) / h;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * h * d0 + (3 * s2 - 2 * s3) * x1 +
         (s3 - s2) * h * d1;
}

Extremum hermite_extremum(double t0, double x0, double d0, double t1, double x1, double d1) {
  // h dp/dt = A s^2 + B s + C, equal to h d0 at s = 0 and h d1 at s = 1; bisect its sign change.
  const double h = t1 - t0;
  const double A = 6 * x0 + 3 * h * d0 - 6 * x1 + 3 * h * d1;
  const double B = -6 * x0 - 4 * h * d0 + 6 * x1 - 2 * h * d1;
  const double C = h * d0;
  const auto slope = [&](double s) { return (A * s + B) * s + C; };
  double lo = 0, hi = 1;
  const bool rising_at_lo = slope(0) > 0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((slope(mid) > 0) == rising_at_lo ? lo : hi) = mid;
  }
  const double t = t0 + 0.5 * (lo + hi) * h;
  return {t, hermite_value(t0, x0, d0, t1, x1, d1, t)};
}

RsfNeighbours rsf_neighbours(const RsfModel& m) {
  const int n = m.n(), ny = m.rows, nx = m.nx();
  if (ny < 1 || nx * ny != n)
    throw Error("rsf: " + std::to_string(n) + " blocks do not fill " + std::to_string(ny) +
                " rows");
  const LatticeStencil springs = m.stencil();
  RsfNeighbours nb;
  nb.start.reserve(n + 1);
  nb.start.push_back(0);
  // One axis' neighbour coordinate, or -1 past a free edge.
  const auto wrap = [](int c, int size, bool periodic) {
    if (c >= 0 && c < size) return c;
    if (!periodic) return -1;
    return ((c % size) + size) % size;
  };
  for (int j = 0; j < n; ++j) {
    const int x = j % nx, y = j / nx;
    for (const LatticeSpring& s : springs)
      for (const int sign : {-1, 1}) {
        const int xi = wrap(x + sign * s.dx, nx, m.periodic);
        const int yi = wrap(y + sign * s.dy, ny, m.periodic_y);
        if (xi < 0 || yi < 0 || (xi == x && yi == y)) continue;
        nb.index.push_back(yi * nx + xi);
        nb.k.push_back(s.k);
      }
    nb.start.push_back(static_cast<int>(nb.index.size()));
  }
  return nb;
}

RsfCycle::RsfCycle(RsfModel model, double tolerance, const std::vector<double>& v,
                   const std::vector<double>& theta)
    : m_(std::move(model)), tol_(tolerance) {
  const int n = m_.n();
  if (n < 1) throw Error("rsf: a chain needs at least one block");
  nb_ = rsf_neighbours(m_);
  for (const auto* x : {&v, &theta})
    if (x->size() != 1 && x->size() != static_cast<std::size_t>(n))
      throw Error("rsf: a start value per block or one for all, got " + std::to_string(x->size()) +
                  " for " + std::to_string(n) + " blocks");
  const auto at = [](const std::vector<double>& x, int j) { return x.size() == 1 ? x[0] : x[j]; };
  dp_.y.assign(3 * n, 0.0);
  tau0_.assign(n, 0.0);
  for (int j = 0; j < n; ++j) {
    dp_.y[n + j] = std::log(at(v, j));
    dp_.y[2 * n + j] = std::log(at(theta, j));
    tau0_[j] = m_.sigma * m_.law[j].friction(m_.form, dp_.y[n + j], dp_.y[2 * n + j]).f +
               m_.eta * at(v, j);
  }
  for (auto& k : dp_.k) k.assign(3 * n, 0.0);
  dp_.ytmp.assign(3 * n, 0.0);
  dp_.err.assign(3 * n, 0.0);
  v_.assign(n, 0.0);
  dp_.dy.assign(3 * n, 0.0);
  rhs(0, dp_.y.data(), dp_.dy.data());
  dp_.y_prev = dp_.y;
  dp_.dy_prev = dp_.dy;
  // First step: a small share of the fastest time scale, D_c/V or theta; the control grows it.
  double scale = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j)
    scale = std::min({scale, m_.law[j].params().dc / at(v, j), at(theta, j)});
  dp_.h = 1e-3 * scale;
}

void RsfCycle::rhs(double t, const double* y, double* dy) {
  const int n = m_.n();
  const double* slip = y;
  const double* ln_v = y + n;
  const double* ln_th = y + 2 * n;
  for (int j = 0; j < n; ++j) v_[j] = std::exp(ln_v[j]);
  for (int j = 0; j < n; ++j) {
    const rsf::Law& law = m_.law[j];
    const double dlnth = law.dlntheta_dt(m_.state_law, ln_v[j], ln_th[j]);
    const rsf::FrictionValue fr = law.friction(m_.form, ln_v[j], ln_th[j]);
    double dlnv;
    if (m_.dynamics == RsfDynamics::QuasiDynamic) {
      const double dtau = m_.k * (m_.v_pl - v_[j]) + coupling(j, v_.data());
      dlnv = (dtau - m_.sigma * fr.f_lntheta * dlnth) / (m_.sigma * fr.f_lnv + m_.eta * v_[j]);
    } else if (m_.dynamics == RsfDynamics::ImposedRate) {
      dlnv = 0;
    } else {
      const double tau = tau0_[j] + m_.k * (m_.v_pl * t - slip[j]) + coupling(j, slip);
      dlnv = (tau - m_.eta * v_[j] - m_.sigma * fr.f) / (m_.mass * v_[j]);
    }
    dy[j] = v_[j];
    dy[n + j] = dlnv;
    dy[2 * n + j] = dlnth;
  }
}

// Sum over block j's springs of k (x_i - x_j).
double RsfCycle::coupling(int j, const double* x) const {
  double s = 0;
  for (int e = nb_.start[j]; e < nb_.start[j + 1]; ++e) s += nb_.k[e] * (x[nb_.index[e]] - x[j]);
  return s;
}

double RsfCycle::error_norm(const std::vector<double>& err, const std::vector<double>& y) const {
  const int n = m_.n();
  double e = 0;
  for (int j = 0; j < n; ++j) {
    const double slip_scale = tol_ * (m_.law[j].params().dc + std::fabs(y[j]));
    e = dopri::worse(e, std::fabs(err[j]) / slip_scale);
  }
  for (int i = n; i < 3 * n; ++i) e = dopri::worse(e, std::fabs(err[i]) / tol_);
  return e;
}

double RsfCycle::step(double t_max) {
  return dp_.step(
      t_max, [&](double t, const double* y, double* dy) { rhs(t, y, dy); },
      [&] { return error_norm(dp_.err, dp_.ytmp); },
      [](double t) {
        // A step that no longer moves the clock: the scene's time scales are beyond double
        // precision at this t (or the state left the range of exp).
        throw Error("rsf: the step size fell below the clock's resolution at t = " +
                    std::to_string(t) + " s (rsf.dc, rsf.v_init or integrator.tolerance)");
      });
}

void RsfCycle::advance_to(double t_end) {
  while (dp_.t < t_end) step(t_end);
}

double RsfCycle::friction_stress(int j) const {
  return m_.sigma * m_.law[j].friction(m_.form, ln_v(j), ln_theta(j)).f;
}

double RsfCycle::friction_stress_rate(int j) const {
  const rsf::FrictionValue fr = m_.law[j].friction(m_.form, ln_v(j), ln_theta(j));
  const int n = m_.n();
  return m_.sigma * (fr.f_lnv * dp_.dy[n + j] + fr.f_lntheta * dp_.dy[2 * n + j]);
}

double RsfCycle::elastic_stress(int j) const {
  return tau0_[j] + m_.k * (m_.v_pl * dp_.t - slip(j)) + coupling(j, dp_.y.data());
}

std::vector<double> RsfCycle::snapshot() const {
  std::vector<double> s = {dp_.t, dp_.t_prev, dp_.h, static_cast<double>(dp_.accepted),
                           static_cast<double>(dp_.rejected)};
  for (const auto* v : {&tau0_, &dp_.y, &dp_.dy, &dp_.y_prev, &dp_.dy_prev})
    s.insert(s.end(), v->begin(), v->end());
  return s;
}

void RsfCycle::restore(const std::vector<double>& s) {
  const std::size_t n = static_cast<std::size_t>(m_.n());
  if (s.size() != 5 + n + 12 * n) throw Error("rsf: a checkpoint of another chain's size");
  dp_.t = s[0];
  dp_.t_prev = s[1];
  dp_.h = s[2];
  dp_.accepted = static_cast<std::int64_t>(s[3]);
  dp_.rejected = static_cast<std::int64_t>(s[4]);
  auto it = s.begin() + 5;
  for (auto* v : {&tau0_, &dp_.y, &dp_.dy, &dp_.y_prev, &dp_.dy_prev}) {
    const std::size_t len = v == &tau0_ ? n : 3 * n;
    v->assign(it, it + static_cast<std::ptrdiff_t>(len));
    it += static_cast<std::ptrdiff_t>(len);
  }
}

}  // namespace bkq
