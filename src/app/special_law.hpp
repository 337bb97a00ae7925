// `bkquake special-law BK_RUN_DIR...`: the friction law felt by the pad held still in plain
// BK runs (Ferre 2018 §4.2, Fig. 4.8, the "special" 1DOF's law), tabulated from the runs'
// segments.csv: at each segment's speed y, friction = -pad_friction_mean / (N m_u), the
// mean pad friction per block and per unit block mass with the sign of a friction law.
// Segments of several runs at the same speed are averaged.
#pragma once

#include <string>
#include <vector>

namespace bkq {

struct LawPoint {
  double speed = 0, friction = 0;
  int segments = 0;  // how many segments were averaged
};

// Throws bkq::Error for a folder that is not a continuous bk run with segments.csv.
std::vector<LawPoint> special_law(const std::vector<std::string>& run_dirs);
// The table as CSV text (io/segments_csv.hpp special_law_schema()), each of `comments` as
// a '# ' line first (friction.law = table skips them).
std::string special_law_csv(const std::vector<LawPoint>& law,
                            const std::vector<std::string>& comments = {});

}  // namespace bkq
