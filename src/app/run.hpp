// Entry point from the command line into a simulation: given the effective scene and
// an output folder, run the scene's drive mode and write every output with provenance.
#pragma once

#include <string>
#include <vector>

#include "app/observers/observer.hpp"
#include "io/scene.hpp"

namespace bkq {

struct RunRequest {
  Scene scene;
  std::string out_dir = "out";
  bool resume = false;
  bool force = false;
  bool quiet = false;
  // Attached after the scene's own outputs (a study's or a test's); not owned.
  std::vector<RunObserver*> observers;
};

// Runs the scene; returns the process exit status: 0 when finished, 130 or 143 when the
// run was stopped by SIGINT or SIGTERM (after writing a checkpoint). Throws
// bkq::Error on bad input, on a refused --resume and on a failed write.
int run_scene(const RunRequest& request);

}  // namespace bkq
