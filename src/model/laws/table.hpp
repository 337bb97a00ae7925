// A tabulated law (friction.law = table; the special 1DOF of Ferre 2018 Fig. 4.8):
// |phi| given at speeds y_0 < ... < y_n (ModelParams::table, read from a file by
// io/friction_table), odd in y (backslip allowed, the thesis stick rule), and
//   |phi(y)| = f_0                                  for 0 <= |y| <= y_0 (held; the static
//                                                    threshold F0 holds a block at y = 0)
//            = linear interpolation of the rows      for y_0 <= |y| <= y_n
//            = phi_thesis(|y|) f_n / phi_thesis(y_n)  for |y| > y_n,
// phi_thesis being eq. 3.5 with the scene's F0, sigma and v_c: the thesis law scaled to
// meet the table's last row.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "model/laws/rational.hpp"

namespace bkq::law {

struct Table {
  static constexpr std::string_view name = "table";
  static constexpr bool backslip = true;
  static constexpr bool frictionless = false;
  static constexpr bool drives_events = true;

  double threshold = 1;

  explicit Table(const ModelParams& p) : threshold(p.threshold()) {
    const FrictionTable& t = p.table;
    if (t.speed.empty() || t.speed.size() != t.friction.size())
      throw Error("friction.table: the friction law 'table' needs a table of at least one row");
    for (std::size_t i = 0; i < t.speed.size(); ++i) {
      const bool increasing = i == 0 || t.speed[i] > t.speed[i - 1];
      if (!(t.speed[i] >= 0) || !std::isfinite(t.speed[i]) || !increasing ||
          !(t.friction[i] >= 0) || !std::isfinite(t.friction[i]))
        throw Error("friction.table: row " + std::to_string(i + 1) +
                    ": speeds must be finite, >= 0 and increasing, friction finite and >= 0");
    }
    auto rows = std::make_shared<Rows>();
    Rows& r = *rows;
    r.speed = t.speed;
    r.friction = t.friction;
    r.beyond = Rational::weakening(p);
    r.index_rows();
    const double at_end = r.beyond.at(r.speed.back());
    r.scale = at_end > 0 ? r.friction.back() / at_end : 0.0;
    rows_ = std::move(rows);
  }

  // The block at the threshold must be able to slide off it: the friction just above
  // y = 0 must lie below the static threshold F0.
  static void check_events(const ModelParams& p) {
    const Table law(p);
    if (!(law.magnitude(0.0) < p.F0))
      throw Error(
          "friction.table: its first friction value is not below the static threshold F0, so "
          "event-driven runs never start an event; use drive.mode = continuous");
  }

  double magnitude(double y) const {
    const Rows& r = *rows_;
    const double a = std::abs(y);
    if (!(a <= r.speed.back())) return r.beyond.at(a) * r.scale;  // beyond the table (or NaN)
    if (a <= r.speed.front()) return r.friction.front();
    // The row at or below a (a lies above the first row and at most at the last).
    const std::size_t i = r.row_below(a);
    if (i + 1 == r.speed.size()) return r.friction.back();
    const double t = (a - r.speed[i]) / (r.speed[i + 1] - r.speed[i]);
    return r.friction[i] + t * (r.friction[i + 1] - r.friction[i]);
  }

 private:
  // Shared, so a copy of the law (the kernels take one by value) copies no rows.
  struct Rows {
    std::vector<double> speed, friction;
    Rational beyond;   // the thesis law past the last row
    double scale = 0;  // f_n / phi_thesis(y_n)
    // A uniform grid of buckets over [speed.front(), speed.back()]: bucket b starts at the
    // last row at or below its left edge, so a lookup searches only the rows of one bucket
    // (about one for an evenly spaced table) instead of all of them: the cost of a
    // lookup does not grow with the table.
    std::vector<std::uint32_t> bucket_first;  // size buckets + 1
    double inv_width = 0;                     // buckets per unit speed

    void index_rows() {
      const std::size_t n = speed.size();
      const double span = speed.back() - speed.front();
      if (n < 8 || !(span > 0) || n > (std::size_t{1} << 31)) return;  // search all rows
      const std::size_t buckets = n;
      inv_width = static_cast<double>(buckets) / span;
      bucket_first.resize(buckets + 1);
      std::size_t i = 0;
      for (std::size_t b = 0; b <= buckets; ++b) {
        const double edge = speed.front() + static_cast<double>(b) / inv_width;
        while (i + 1 < n && speed[i + 1] <= edge) ++i;
        bucket_first[b] = static_cast<std::uint32_t>(i);
      }
    }

    // The last row i with speed[i] <= a, for speed.front() < a <= speed.back(): the rows of
    // a's bucket (and one either side, for rounding at its edges) are searched; should that
    // not bracket a, all rows are, so the row is always upper_bound's.
    std::size_t row_below(double a) const {
      if (!bucket_first.empty()) {
        const auto last = static_cast<double>(bucket_first.size() - 2);
        const auto b = static_cast<std::size_t>(
            std::clamp(std::floor((a - speed.front()) * inv_width), 0.0, last));
        const std::size_t lo = bucket_first[b] > 0 ? bucket_first[b] - 1 : 0;
        const std::size_t hi = std::min<std::size_t>(bucket_first[b + 1] + 2, speed.size());
        if (speed[lo] <= a && (hi == speed.size() || a < speed[hi - 1])) {
          const auto it = std::upper_bound(speed.begin() + static_cast<std::ptrdiff_t>(lo),
                                           speed.begin() + static_cast<std::ptrdiff_t>(hi), a);
          return static_cast<std::size_t>(it - speed.begin()) - 1;
        }
      }
      const auto it = std::upper_bound(speed.begin(), speed.end(), a);
      return static_cast<std::size_t>(it - speed.begin()) - 1;
    }
  };
  std::shared_ptr<const Rows> rows_;
};

}  // namespace bkq::law
