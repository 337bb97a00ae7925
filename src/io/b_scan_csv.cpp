// b_scan.csv (see b_scan_csv.hpp).
#include "io/b_scan_csv.hpp"

#include <cmath>

#include "core/format.hpp"

namespace bkq {

const Schema& b_scan_schema() {
  static const Schema schema = {
      {"mu_min", "", "lower end of the window (a bin edge)"},
      {"mu_max", "", "upper end of the window (a bin edge)"},
      {"events", "", "events in the window", kInteger},
      {"b", "", "binned maximum-likelihood b per unit of mu = ln M (Tinti & Mulargia 1987)"},
      {"b_err", "", "its standard error (Shi & Bolt 1982)"},
      {"ks_distance", "", "KS distance between the binned and fitted survival functions"},
      {"accepted", "", "1 when the window is one of those of b's systematic error, else 0",
       kInteger},
  };
  return schema;
}

std::string b_scan_csv(const std::vector<WindowFit>& rows) {
  const auto num = [](double x) { return std::isfinite(x) ? format_real(x) : std::string(); };
  std::string out = header_of(b_scan_schema()) + "\n";
  for (const WindowFit& r : rows)
    out += num(r.mu_min) + "," + num(r.mu_max) + "," + std::to_string(r.events) + "," + num(r.b) +
           "," + num(r.b_err) + "," + num(r.ks_distance) + "," + (r.accepted ? "1" : "0") + "\n";
  return out;
}

}  // namespace bkq
