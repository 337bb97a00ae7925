// `bkquake sweep`: runs every point of a sweep file (io/sweep_file.hpp), each replica an
// ordinary run of the app layer (run_scene) in its own folder, on one rank or on the
// ranks of an MPI job (app/sweep_comm.hpp), merges each point's replicas (app/merge) and
// writes sweep.csv. The results do not depend on the number of ranks: a replica's seed
// comes from the point's seed, the point and the replica number only.
//
// DIR/sweep.ini         the sweep file as read, with provenance and the --set options
// DIR/sweep.csv         one row per point (sweep_csv_schema()), rewritten as points finish
// DIR/bkquake.lock      while a sweep runs (io/folder_lock: a second sweep is refused)
// DIR/points/pNNNN/     point.json, and the merged histogram.csv and summary.json
// DIR/points/pNNNN/rNN/ one replica: scene.ini, catalog.csv, histogram.csv, summary.json
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/sweep_file.hpp"

namespace bkq {

struct SweepRequest {
  std::string sweep_file;
  std::vector<std::string> overrides;  // --set section.key=value, after the file's [set]
  std::string out_dir;
  bool resume = false;
  bool force = false;  // write over the folder: an earlier sweep's points and files go
};

// Runs the sweep on this process's ranks. Returns the exit status: 0 when every point
// succeeded, 3 when some failed (named in sweep.csv and on stderr), 130/143 when stopped
// by a signal. Bad input (the sweep file, a refused folder) throws bkq::Error on every rank.
int run_sweep(const SweepRequest& request);

// The seed of replica `replica` of point `point`: the point's run.seed + point * replicas
// + replica, or the point's run.seed + replica when run.seed itself is swept (wrapping
// within [0, 2^63)).
std::uint64_t sweep_seed(std::uint64_t point_seed, bool seed_swept, std::size_t point, int replicas,
                         int replica);

// Exit status of a sweep with failed points.
inline constexpr int kExitSweepFailures = 3;

}  // namespace bkq
