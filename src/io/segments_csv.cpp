// segments.csv written and read; see segments_csv.hpp.
#include "io/segments_csv.hpp"

#include <fstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/csv_util.hpp"
#include "io/input_file.hpp"

namespace bkq {

const Schema& segments_schema() {
  static const Schema schema = {
      {"segment", "", "speed segment, 0-based, in time order", kInteger},
      {"t_start", "time", "start of the segment"},
      {"t_end", "time", "end of the segment (the run's end for the last one)"},
      {"speed", "length/time", "substrate speed during the segment"},
      {"pad_friction_mean", "force", "mean pad friction over the segment's last half (eq. 4.1)"},
      {"pad_friction_mean_err", "force", "block-averaging error of the mean (eqs. 4.3-4.4)"},
      {"pad_friction_amp", "force", "amplitude sqrt(2) RMS about the mean (eq. 4.2)"},
      {"pad_friction_amp_err", "force", "block-averaging error of the amplitude"},
      {"pad_position_mean", "length", "mean pad position x (0 for bk)"},
      {"pad_position_mean_err", "length", "its block-averaging error"},
      {"pad_position_amp", "length", "amplitude of the pad position"},
      {"pad_position_amp_err", "length", "its block-averaging error"},
      {"pad_velocity_mean", "length/time", "mean pad velocity (0 for bk)"},
      {"pad_velocity_mean_err", "length/time", "its block-averaging error"},
      {"pad_velocity_amp", "length/time", "amplitude of the pad velocity"},
      {"pad_velocity_amp_err", "length/time", "its block-averaging error"},
  };
  return schema;
}

const Schema& special_law_schema() {
  static const Schema schema = {
      {"speed", "length/time", "relative speed y of block and substrate (> 0, increasing)"},
      {"friction", "force/mass", "friction phi(y) per unit block mass (> 0 opposes y > 0)"},
  };
  return schema;
}

const Schema& friction_study_schema() {
  static const Schema schema = {
      {"configuration", "", "bkp, bk, 1dof or special-1dof (data/scenes/brake/)", kText},
      {"seed", "", "run.seed of the run", kInteger},
      {"run", "", "which of the five runs of the speed grid (0-based)", kInteger},
      {"speed", "length/time", "substrate speed of the segment"},
      {"friction_mean", "force", "mean pad friction (segments.csv pad_friction_mean)"},
      {"friction_mean_err", "force", "its block-averaging error"},
      {"friction_amp", "force", "amplitude of the pad friction"},
      {"friction_amp_err", "force", "its block-averaging error"},
      {"position_amp_scaled", "force", "pad-position amplitude times m_x (0 without a pad)"},
      {"position_amp_scaled_err", "force", "its block-averaging error times m_x"},
      {"friction_law", "force", "N m_u phi(v): the friction law of Table 3.1 on the whole pad"},
  };
  return schema;
}

std::string segments_header() {
  return header_of(segments_schema());
}

std::string segments_row(const SegmentRow& r) {
  std::string s = std::to_string(r.segment);
  for (double v : {r.t_start, r.t_end, r.speed}) s += ',' + format_real(v);
  for (const SegmentStat& st : r.stats)
    for (double v : {st.mean, st.mean_err, st.amp, st.amp_err}) s += ',' + format_real(v);
  return s;
}

std::vector<std::vector<double>> read_numeric_columns(const std::filesystem::path& path,
                                                      const std::vector<std::string>& names) {
  const std::string file = path.string();
  std::ifstream f = open_input(path, "table");
  std::string line;
  std::int64_t lineno = 0;
  std::vector<int> index;
  std::vector<std::vector<double>> cols(names.size());
  std::string header_line;
  while (std::getline(f, line)) {
    ++lineno;
    if (line.empty() || line[0] == '#') continue;
    const auto fields = csv::split(line);
    if (index.empty()) {
      header_line = line;
      const auto header = csv::split(header_line);
      for (const auto& n : names) {
        const int c = csv::find_column(header, n);
        if (c < 0) throw Error(file + ": missing column '" + n + "'");
        index.push_back(c);
      }
      continue;
    }
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (index[k] >= static_cast<int>(fields.size()))
        throw Error(file + " line " + std::to_string(lineno) + ": too few columns");
      cols[k].push_back(
          csv::parse_double(fields[static_cast<std::size_t>(index[k])], file, lineno, names[k]));
    }
  }
  check_read(f, path, "table", lineno);
  if (index.empty()) throw Error(file + ": empty file, expected a header line");
  return cols;
}

std::vector<SegmentRow> read_segments_csv(const std::filesystem::path& path) {
  std::vector<std::string> names;
  for (const auto& c : segments_schema()) names.emplace_back(c.name);
  const auto cols = read_numeric_columns(path, names);
  std::vector<SegmentRow> rows(cols[0].size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    SegmentRow& r = rows[i];
    r.segment = static_cast<std::int64_t>(cols[0][i]);
    r.t_start = cols[1][i];
    r.t_end = cols[2][i];
    r.speed = cols[3][i];
    for (std::size_t s = 0; s < r.stats.size(); ++s) {
      r.stats[s] = {cols[4 + 4 * s][i], cols[5 + 4 * s][i], cols[6 + 4 * s][i], cols[7 + 4 * s][i]};
    }
  }
  return rows;
}

}  // namespace bkq
