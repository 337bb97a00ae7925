// How a sweep's tasks reach the ranks: one process on its own (no MPI, or MPI with one
// rank) or an MPI job through Boost.MPI. Rank 0 hands out task numbers dynamically, one
// at a time to whichever rank asks (a rank that finishes takes the next), and runs tasks
// itself on a second thread while its main thread serves the others; results come back to
// rank 0, which alone sees them (on_result runs on its main thread only). A build without
// MPI runs as one rank and refuses to start as several copies under mpirun.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bkq {

struct TaskResult {
  int task = -1;
  int status = 0;  // 0 ok, 1 failed, 128 + signal: stopped by it (the sweep stops)
  double seconds = 0;
  std::string error;
};

// What the dispatcher did, for the closing line of a sweep (rank 0's view).
struct DispatchStats {
  long long messages = 0;          // point-to-point messages sent and received by rank 0
  int remote_tasks = 0;            // tasks run by ranks other than 0
  double idle_at_end_seconds = 0;  // summed over ranks: from a rank's last task to the end
  double dispatch_seconds = 0;     // wall time of the whole dispatch
};

class SweepComm {
 public:
  virtual ~SweepComm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Every rank gets rank 0's `ok` (rank 0 checks the folder before anyone runs).
  virtual bool agree(bool ok) = 0;
  // Runs the tasks in `order` (rank 0's list; others pass anything) with `run` on every
  // rank; rank 0 calls `on_result` for each result as it arrives; when it returns false no
  // further task is handed out. Returns on every rank once all handed-out tasks are done.
  virtual DispatchStats dispatch(const std::vector<int>& order,
                                 const std::function<TaskResult(int)>& run,
                                 const std::function<bool(const TaskResult&)>& on_result) = 0;
};

// The ranks of this process: MPI when started by mpirun/srun and built with MPI, else
// one rank. `note` says which ("MPI, 4 ranks", "one rank: built without MPI"). A build
// without MPI started as several ranks throws bkq::Error (exit 2).
std::unique_ptr<SweepComm> make_sweep_comm(std::string& note);

// One rank whatever the build: make_sweep_comm's answer when not started by a launcher.
std::unique_ptr<SweepComm> make_one_rank_comm();

// Whether this build has MPI (Boost.MPI over Open MPI): otherwise a sweep runs as one rank.
bool mpi_available();

// The number of ranks the launcher announced in the environment (Open MPI, PMI, PMIx,
// SLURM's srun), 0 when not started by one.
int launcher_world_size();

}  // namespace bkq
