// One slider near steady sliding, integrated alone; see rsf_alone.hpp.
#include "engine/rsf_alone.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "engine/dormand_prince.hpp"
#include "integrate/dopri5_dense.hpp"

namespace bkq::rsf {

namespace {

// One component of the dense output between points p and e at fraction th.
double dense_value(const AloneSlider::Point& p, const AloneSlider::Point& e, int i, double th) {
  return dopri::dense(p.y[i], e.y[i], p.dy[i], e.dy[i], e.dense[i], e.dt - p.dt, th);
}

// The time after p at which component i of the dense output reaches `target`, between p
// (below it) and e (at or above it): Newton's method on the quartic in th from the chord's
// root, kept inside a bracket that bisection narrows where Newton would leave it. A point where
// the quartic is exactly the target is the root (Newton would stay on the bracket's end it just
// set, and bisection crawl to it).
double dense_root(const AloneSlider::Point& p, const AloneSlider::Point& e, int i, double target) {
  const double h = e.dt - p.dt, diff = e.y[i] - p.y[i], bspl = h * p.dy[i] - diff;
  const double r4 = diff - h * e.dy[i] - bspl, r5 = h * e.dense[i];
  // y(th) = y0 + c1 th + c2 th^2 + c3 th^3 + c4 th^4
  const double c1 = diff + bspl, c2 = r4 + r5 - bspl, c3 = -(r4 + 2 * r5), c4 = r5;
  double lo = 0, hi = 1, th = (target - p.y[i]) / diff;
  for (int n = 0; n < 100; ++n) {
    const double f = p.y[i] - target + th * (c1 + th * (c2 + th * (c3 + th * c4)));
    if (f == 0) return th * h;
    (f < 0 ? lo : hi) = th;
    const double df = c1 + th * (2 * c2 + th * (3 * c3 + th * 4 * c4));
    double next = df > 0 ? th - f / df : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::fabs(next - th) <= 1e-15) return next * h;
    if (hi - lo <= 1e-15) break;
    th = next;
  }
  return hi * h;
}
}  // namespace

AloneSlider::AloneSlider(double tolerance) : tol_(tolerance) {}

void AloneSlider::rhs(const Slider& s, const double* y, double* dy) const {
  const double v = std::exp(y[1]);
  const double dlnth = std::exp(-y[2]) - v / s.dc;
  dy[0] = v;
  dy[1] = (s.stressing_rate - s.k_eff * v - s.b_rsf * s.sigma * dlnth) / (s.a * s.sigma);
  dy[2] = dlnth;
}

AloneSlider::Point AloneSlider::step(const Slider& s, double dt_max) {
  dp_.step(
      dt_max, [&](double, const double* y, double* dy) { rhs(s, y, dy); },
      [&] {
        double err = 0;
        for (int i = 0; i < 3; ++i) {
          const double scale = i == 0 ? tol_ * (s.dc + std::fabs(dp_.ytmp[i])) : tol_;
          err = dopri::worse(err, std::fabs(dp_.err[i]) / scale);
        }
        return err;
      },
      [](double) {
        throw Error(
            "rsf: the step size of a block integrated alone fell below the clock's "
            "resolution (rsf.dc, integrator.tolerance)");
      });
  Point q;
  q.dt = dp_.t;
  for (int i = 0; i < 3; ++i) {
    q.y[i] = dp_.y[i];
    q.dy[i] = dp_.dy[i];
    for (int l = 0; l < 7; ++l) q.dense[i] += dopri::kDense[l] * dp_.k[l][i];
  }
  return q;
}

AloneSlider::Forecast AloneSlider::forecast(const Slider& s, SliderState x, const Limits& lim,
                                            std::vector<Point>& path, double h_first) {
  path.clear();
  Point p;
  p.y[1] = x.ln_v;
  p.y[2] = x.ln_theta;
  rhs(s, p.y, p.dy);
  path.push_back(p);
  const double ln_dc = std::log(s.dc);
  const auto outside = [&](const Point& q) {
    const double lo = q.y[1] + q.y[2] - ln_dc;
    return lo >= lim.ln_omega_hi || (lo < lim.ln_omega_lo && q.y[1] < lim.ln_v_locked);
  };
  if (x.ln_v >= lim.ln_v_target) return {0, Exit::Speed};
  if (!(lim.amount > 0)) return {0, Exit::Slip};
  if (outside(p)) return {0, Exit::Phase};
  dp_.t = 0;
  dp_.h = h_first > 0 ? h_first : 0.05 * std::min(s.dc / std::exp(x.ln_v), std::exp(x.ln_theta));
  std::copy(p.y, p.y + 3, dp_.y.begin());
  std::copy(p.dy, p.dy + 3, dp_.dy.begin());
  for (int n = 0; n < lim.horizon; ++n) {
    const Point q = step(s, std::numeric_limits<double>::infinity());
    ++steps_;
    path.push_back(q);
    // The earlier of the speed's and the slip's crossings inside the step.
    double cross = std::numeric_limits<double>::infinity();
    Exit exit = Exit::Phase;
    if (q.y[1] >= lim.ln_v_target) {
      cross = dense_root(p, q, 1, lim.ln_v_target);
      exit = Exit::Speed;
    }
    if (q.y[0] >= lim.amount) {
      const double c = dense_root(p, q, 0, lim.amount);
      if (c < cross) {
        cross = c;
        exit = Exit::Slip;
      }
    }
    if (exit != Exit::Phase) return {p.dt + cross, exit, dp_.h};
    if (outside(q)) return {q.dt, Exit::Phase, dp_.h};
    p = q;
  }
  return {p.dt, Exit::Phase, dp_.h};
}

AloneSlider::Point AloneSlider::at(const Slider& s, const std::vector<Point>& path, double dt) {
  // A clock read back as t_ref + dt - t_ref may land a rounding past the path's end.
  if (dt > path.back().dt && dt - path.back().dt <= 1e-12 * dt) dt = path.back().dt;
  auto it = std::upper_bound(path.begin(), path.end(), dt,
                             [](double t, const Point& p) { return t < p.dt; });
  Point p = *(it == path.begin() ? it : it - 1);
  if (p.dt == dt) return p;
  if (it != path.end()) {
    const double th = (dt - p.dt) / (it->dt - p.dt);
    Point q;
    q.dt = dt;
    for (int i = 0; i < 3; ++i) q.y[i] = dense_value(p, *it, i, th);
    return q;
  }
  // Past the path: steps from its end, with its last step size.
  dp_.t = p.dt;
  dp_.h = path.size() > 1 ? p.dt - path[path.size() - 2].dt : dt - p.dt;
  std::copy(p.y, p.y + 3, dp_.y.begin());
  std::copy(p.dy, p.dy + 3, dp_.dy.begin());
  while (dp_.t < dt) p = step(s, dt);
  return p;
}

}  // namespace bkq::rsf
