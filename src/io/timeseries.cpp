// The time-series schema (continuous runs, Ferre 2018 ch. 4): each column listed once with its
// units and meaning; header and rows follow its order.
#include "io/timeseries.hpp"

#include "core/format.hpp"

namespace bkq {

const Schema& timeseries_schema() {
  static const Schema schema = {
      {"t", "time", "simulated time of the sample"},
      {"speed", "length/time", "substrate speed v at t"},
      {"substrate", "length", "substrate displacement s at t"},
      {"pad_x", "length", "pad position x (0 for bk)"},
      {"pad_v", "length/time", "pad velocity (0 for bk)"},
      {"pad_friction", "force", "pad friction: sum of the pulling-spring forces k_p (u_j - x)"},
      {"sliding", "", "number of blocks sliding at t", "integer"},
  };
  return schema;
}

std::string timeseries_header() {
  return header_of(timeseries_schema());
}

std::string timeseries_row(const TimeSeriesRow& r) {
  // Same order as timeseries_schema().
  std::string s;
  s.reserve(160);
  for (double v : {r.t, r.speed, r.substrate, r.pad_x, r.pad_v, r.pad_friction}) {
    s += format_real(v);
    s += ',';
  }
  s += std::to_string(r.sliding);
  return s;
}

const Schema& timeseries_status_schema() {
  static const Schema schema = {
      {"stuck", "", "blocks stuck at t (output.status)", kInteger},
      {"slip_forward", "", "blocks sliding with relative velocity > 0 (output.status)", kInteger},
      {"slip_backward", "", "blocks sliding with relative velocity < 0: backslip (output.status)",
       kInteger},
  };
  return schema;
}

// Appended, not "," + ...: GCC 12 warns falsely (-Wrestrict) there.
std::string status_header_suffix() {
  std::string s(1, ',');
  s += header_of(timeseries_status_schema());
  return s;
}

std::string status_row_suffix(const NodeStatus& n) {
  std::string s(1, ',');
  s += std::to_string(n.stuck);
  s += ',';
  s += std::to_string(n.forward);
  s += ',';
  s += std::to_string(n.backward);
  return s;
}

std::string blocks_header(int first, int count) {
  std::string header = "t";
  for (const char* what : {",u", ",v"})
    for (int j = first; j < first + count; ++j) {
      header += what;
      header += std::to_string(j);
    }
  return header;
}

std::string blocks_row(double t, const std::vector<double>& u, const std::vector<double>& v) {
  std::string row = blocks_row(t, u);
  for (double x : v) {
    row += ',';
    row += format_real(x);
  }
  return row;
}

std::string blocks_row(double t, const std::vector<double>& u) {
  std::string row = format_real(t);
  for (double x : u) {
    row += ',';
    row += format_real(x);
  }
  return row;
}

}  // namespace bkq
