// The sweep's ranks (see sweep_comm.hpp): what holds with and without MPI, the one-rank
// loop and the launcher's environment. make_sweep_comm is in sweep_comm_mpi.cpp (built with
// MPI) or sweep_comm_serial.cpp (without), one of the two.
#include "app/sweep_comm.hpp"

#include <chrono>
#include <cstdlib>

namespace bkq {

namespace {

using Clock = std::chrono::steady_clock;

int env_int(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : 0;
}

class SerialComm final : public SweepComm {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  bool agree(bool ok) override { return ok; }
  DispatchStats dispatch(const std::vector<int>& order, const std::function<TaskResult(int)>& run,
                         const std::function<bool(const TaskResult&)>& on_result) override {
    const auto t0 = Clock::now();
    for (const int task : order)
      if (!on_result(run(task))) break;
    DispatchStats s;
    s.dispatch_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return s;
  }
};

}  // namespace

std::unique_ptr<SweepComm> make_one_rank_comm() {
  return std::make_unique<SerialComm>();
}

int launcher_world_size() {
  if (const int n = env_int("OMPI_COMM_WORLD_SIZE")) return n;
  if (const int n = env_int("PMI_SIZE")) return n;
  if (std::getenv("SLURM_PROCID"))
    if (const int n = env_int("SLURM_STEP_NUM_TASKS")) return n;
  return 0;
}

}  // namespace bkq
