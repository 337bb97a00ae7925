// The friction study of Ferre 2018 Fig. 4.6 (§4.2): each model configuration (a scene of
// data/scenes/brake/) runs the speed range 0.005 .. 1 as five continuous runs of speed
// segments, the lower speeds with a finer increment; the segment statistics of every run
// (segments.csv) are gathered into friction_study.csv. The special 1DOF, whose law is the
// friction the held pad feels in the BK runs (special-law), runs after them when the scene
// and the tabulated law (friction.law = table) exist. Runs go to DIR/<config>/seed<S>/run<R>,
// in parallel on `jobs` threads, with a progress line per finished run. DIR follows the
// folder rule of every command that writes a folder (io/output.hpp): new or empty, or
// force; locked while the study runs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bkq {

// One run of the grid: segments at v0, v0 + inc, ..., `count` of them.
struct StudyRun {
  double v0, inc;
  int count;
};
// The thesis grid: 0.005-0.075 by 0.005, 0.08-0.20 by 0.01, 0.22-0.40 by 0.02, 0.45-0.85 by
// 0.05, 0.86-1.00 by 0.01 (it holds 0.045-0.065, 0.08-0.12, 0.16-0.19, 0.28, 0.5, 0.88-0.91).
const std::vector<StudyRun>& study_grid();

struct StudyRequest {
  std::string scenes_dir = "data/scenes/brake";
  std::string out = "friction_study";
  std::vector<std::string> configs = {"bkp", "bk", "1dof", "special-1dof"};
  int seeds = 1;  // bkp and bk run with run.seed = scene seed + 0 .. seeds-1
  int jobs = 2;
  double segment = 2000;  // time units per speed segment
  bool quiet = false;
  bool force = false;  // write into an output folder that already holds files
};

// Returns the path of friction_study.csv. Throws bkq::Error on a missing scene or failed run.
std::string run_friction_study(const StudyRequest& req);

}  // namespace bkq
